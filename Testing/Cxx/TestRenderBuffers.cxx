// Numbers in the shared render buffers: camera G-buffer normals, light-buffer
// flux bookkeeping and the buffers kept while nothing they show changes, direct
// irradiance, and the skip path of the pass.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsTimings.h"
#include "TestTechniqueFrame.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <vector>

namespace
{
/** A window rendering a built-in scene through the caustics pass. */
struct Fixture
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsRenderPass> Pass;
  vtkNew<vtkCausticsBuiltinScene> Scene;

  explicit Fixture(const char* scene, int size = 256)
  {
    this->Scene->SetSceneName(scene);
    EXPECT_TRUE(this->Scene->Populate(this->Renderer)) << this->Scene->GetLastError();
    this->Renderer->SetPass(this->Pass);
    this->Window->SetMultiSamples(0);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
    this->Pass->GetTimings()->SynchronousOn();
  }
  ~Fixture()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  vtkSmartPointer<vtkImageData> Read(const char* name)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    EXPECT_TRUE(this->Pass->ReadBuffer(name, image)) << name;
    return image;
  }
};

/** Every texel of every texture, read back: what a consumer can see. */
std::vector<std::vector<double>> ReadAll(std::initializer_list<vtkTextureObject*> textures)
{
  std::vector<std::vector<double>> all;
  for (vtkTextureObject* texture : textures)
  {
    const int components = texture->GetComponents();
    auto image = caustics::gl::ReadTexture(texture, "t", components);
    vtkDataArray* array = image->GetPointData()->GetArray(0);
    std::vector<double> values(array->GetNumberOfValues());
    for (vtkIdType v = 0; v < array->GetNumberOfValues(); ++v)
    {
      values[v] = array->GetComponent(v / components, static_cast<int>(v % components));
    }
    all.push_back(std::move(values));
  }
  return all;
}

/** Fills a float colour texture with 7: a frame that draws it again wipes the mark. */
void Mark(vtkTextureObject* texture)
{
  const float value[4] = { 7.0f, 7.0f, 7.0f, 7.0f };
  glClearTexImage(texture->GetHandle(), 0, GL_RGBA, GL_FLOAT, value);
}

bool Marked(vtkTextureObject* texture)
{
  return ReadAll({ texture })[0][0] == 7.0;
}

/** A property of one change between frames, for the kept-buffers tests. */
struct Change
{
  const char* What;
  std::function<void()> Apply;
};

/** The ball lens scene's actors: the refractor and the other one. */
void BallAndFloor(const caustics::SceneData& scene, vtkActor*& ball, vtkActor*& floor)
{
  for (const caustics::Mesh& mesh : scene.Meshes)
  {
    const bool refractor = scene.Materials[mesh.material].role == caustics::Role::Refractor;
    (refractor ? ball : floor) = mesh.actor;
  }
}

double Sum(vtkImageData* image, int component)
{
  vtkDataArray* array = image->GetPointData()->GetArray(0);
  double sum = 0.0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    sum += array->GetComponent(i, component);
  }
  return sum;
}
}

TEST(GBuffer, SphereCentreNormalFacesTheCamera)
{
  Fixture f("ball-lens");
  f.Pass->KeepBuffersOn();
  f.Window->Render();
  const caustics::SceneData& scene = f.Pass->GetSceneExtractor()->GetScene();
  double px, py;
  ASSERT_TRUE(scene.View.WorldToPixel({ { 0.0, 3.0, 0.0 } }, px, py));
  const int i = static_cast<int>(px), j = static_cast<int>(py);
  auto normals = f.Read("RefractiveNormal");
  vtkDataArray* n = normals->GetPointData()->GetArray(0);
  const vtkIdType id = static_cast<vtkIdType>(j) * 256 + i;
  EXPECT_EQ(std::lround(n->GetComponent(id, 3)), 3) << "the ball is a refractor";
  caustics::Vec3 origin, direction;
  scene.View.PixelRay(i, j, origin, direction);
  // Expected: the sphere's normal where this pixel's ray meets it (the pixel centre
  // is up to half a pixel, ~0.01 rad, off the ball's centre ray). Interpolating
  // radial vertex normals at a point of a flat facet gives exactly the direction
  // from the centre to that point, which differs from the true sphere's hit by
  // the facet's sagitta (< 3e-4 R) times the ray's obliquity (~0.01): negligible.
  // What remains is RGBA16F storage: 2^-11 relative per component, so 1e-3 in norm.
  const double centre[3] = { 0.0, 3.0, 0.0 };
  double oc[3];
  for (int c = 0; c < 3; ++c)
  {
    oc[c] = origin[c] - centre[c];
  }
  const double b = vtkMath::Dot(oc, direction.data());
  const double t = -b - std::sqrt(b * b - (vtkMath::Dot(oc, oc) - 1.0));
  double error = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    const double expected = origin[c] + t * direction[c] - centre[c];
    error += std::pow(n->GetComponent(id, c) - expected, 2);
  }
  EXPECT_LT(std::sqrt(error), 1e-3);
  // And it faces the camera within the half-pixel offset.
  double facing = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    facing -= n->GetComponent(id, c) * direction[c];
  }
  EXPECT_GT(facing, 0.999);
  // The opaque G-buffer holds no refractor: a floor pixel has the floor's +y
  // normal and the receiver role; the ball's centre ray misses the floor.
  auto opaque = f.Read("Normal");
  auto opaquePosition = f.Read("Position");
  EXPECT_LT(opaquePosition->GetPointData()->GetArray(0)->GetComponent(id, 3), 0.0);
  ASSERT_TRUE(scene.View.WorldToPixel({ { 2.0, 0.0, 2.0 } }, px, py));
  const vtkIdType floorId = static_cast<vtkIdType>(py) * 256 + static_cast<vtkIdType>(px);
  EXPECT_NEAR(opaque->GetPointData()->GetArray(0)->GetComponent(floorId, 1), 1.0, 1e-3);
  EXPECT_EQ(std::lround(opaque->GetPointData()->GetArray(0)->GetComponent(floorId, 3)), 1);
}

TEST(GBuffer, KeepsUnchangedTargetsAndRedrawsOnAnyChange)
{
  Fixture f("ball-lens", 64);
  f.Pass->KeepBuffersOn(); // upload the geometry even without caustics
  f.Window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(f.Window);
  gl->MakeCurrent();
  auto scene = [&]() -> const caustics::SceneData&
  { return f.Pass->GetSceneExtractor()->GetScene(); };
  float matrix[16];
  caustics::gl::ToColumnMajor(scene().View.worldToClip, matrix);
  int size = 32;
  int roles = vtkCausticsSceneGeometry::AllRoles;
  vtkNew<vtkCausticsGBuffer> kept;
  auto render = [&](vtkCausticsGBuffer* g)
  { return g->Render(gl, f.Pass->GetGeometry(), matrix, size, size, roles); };
  auto contents = [](vtkCausticsGBuffer* g)
  {
    return ReadAll({ g->GetPositionTexture(), g->GetNormalTexture(), g->GetAlbedoTexture(),
      g->GetDepthTexture() });
  };
  ASSERT_TRUE(render(kept));
  EXPECT_FALSE(kept->GetLastRenderReused()) << "a first frame draws";

  // Nothing changed: the targets are kept, untouched.
  Mark(kept->GetPositionTexture());
  ASSERT_TRUE(render(kept));
  EXPECT_TRUE(kept->GetLastRenderReused());
  EXPECT_TRUE(Marked(kept->GetPositionTexture()));
  kept->ReuseUnchangedOff(); // wipe the mark
  ASSERT_TRUE(render(kept));
  kept->ReuseUnchangedOn();

  // Each change redraws, to exactly what a fresh instance draws, and the frame
  // after it keeps the new targets.
  vtkActor* ball = nullptr;
  vtkActor* floor = nullptr;
  BallAndFloor(scene(), ball, floor);
  ASSERT_NE(ball, nullptr);
  ASSERT_NE(floor, nullptr);
  const std::vector<Change> changes = {
    { "a moved actor", [&]() { ball->AddPosition(0.25, 0.0, 0.0); } },
    { "the camera", [&]() { matrix[12] += 0.05f; } },
    { "a resize", [&]() { size = 48; } },
    { "the role mask", [&]() { roles = vtkCausticsSceneGeometry::SpecularRoles; } },
    { "keep farthest", [&]() { kept->KeepFarthestOn(); } },
    { "a material's albedo",
      [&]()
      {
        roles = vtkCausticsSceneGeometry::AllRoles;
        kept->KeepFarthestOff();
        floor->GetProperty()->SetColor(0.2, 0.4, 0.6);
      } },
    { "a material's role",
      [&]() { vtkCausticsMaterial::SetRole(ball, vtkCausticsMaterial::ROLE_REFLECTOR); } },
  };
  auto last = contents(kept);
  for (const Change& change : changes)
  {
    Mark(kept->GetPositionTexture());
    change.Apply();
    f.Window->Render(); // a new snapshot of the scene, uploaded
    gl->MakeCurrent();
    ASSERT_TRUE(render(kept));
    EXPECT_FALSE(kept->GetLastRenderReused()) << change.What;
    vtkNew<vtkCausticsGBuffer> fresh;
    fresh->SetKeepFarthest(kept->GetKeepFarthest());
    ASSERT_TRUE(render(fresh));
    const auto now = contents(kept);
    EXPECT_TRUE(now == contents(fresh)) << change.What << ": not what a fresh instance draws";
    EXPECT_TRUE(now != last) << change.What << " changes the targets (else this proves nothing)";
    fresh->ReleaseGraphicsResources(f.Window);
    ASSERT_TRUE(render(kept));
    EXPECT_TRUE(kept->GetLastRenderReused()) << "after " << change.What;
    last = now;
  }
  std::ostringstream print;
  kept->Print(print);
  EXPECT_NE(print.str().find("ReuseUnchanged: 1"), std::string::npos);
  kept->ReleaseGraphicsResources(f.Window);
}

TEST(LightBuffers, DirectionalFluxSumsToPowerInFrustum)
{
  Fixture f("ball-lens");
  f.Pass->SetLightBufferResolution(128);
  f.Window->Render();
  ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics());
  const auto& scene = f.Pass->GetSceneExtractor()->GetScene();
  auto flux = f.Read("LightFlux:0");
  // Orthographic frustum around the ball's bounding sphere: power = E x (2R)^2.
  const caustics::LightView view =
    caustics::ComputeLightView(scene, 0, caustics::LightView::Focus::SeenSpecular);
  const caustics::Vec3 power = view.FrustumPower(scene.Lights[0]);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(Sum(flux, c) / power[c], 1.0, 0.005) << "channel " << c;
  }
  // The light sees the top of the ball (a refractor) at the frustum's centre.
  auto normal = f.Read("LightNormal:0");
  const vtkIdType centre = 64 * 128 + 64;
  EXPECT_EQ(std::lround(normal->GetPointData()->GetArray(0)->GetComponent(centre, 3)), 3);
  EXPECT_GT(normal->GetPointData()->GetArray(0)->GetComponent(centre, 1), 0.99);
}

TEST(LightBuffers, PointAndSpotFluxSumsToPowerInFrustum)
{
  Fixture f("bunny");
  f.Pass->SetLightBufferResolution(128);
  f.Window->Render();
  ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics());
  const auto& scene = f.Pass->GetSceneExtractor()->GetScene();
  const caustics::Light& spot = scene.Lights[0];
  ASSERT_EQ(spot.type, caustics::Light::Type::Spot);
  const caustics::LightView view =
    caustics::ComputeLightView(scene, 0, caustics::LightView::Focus::SeenSpecular);
  ASSERT_TRUE(view.perspective);
  // Expected power: I x integral of the spot falloff over the frustum's solid
  // angle, by a fine midpoint sum on the image plane (independent of the shader's
  // per-texel rule: 2048^2 cells).
  const int cells = 2048;
  const double t = view.halfExtent, h = 2.0 * t / cells;
  double expected = 0.0;
  for (int j = 0; j < cells; ++j)
  {
    for (int i = 0; i < cells; ++i)
    {
      const double x = -t + (i + 0.5) * h, y = -t + (j + 0.5) * h;
      double d[3];
      for (int c = 0; c < 3; ++c)
      {
        d[c] = view.axis[c] + x * view.right[c] + y * view.up[c];
      }
      const double length = vtkMath::Norm(d);
      const double cosAngle = vtkMath::Dot(d, spot.direction.data()) / length;
      expected += h * h / std::pow(1.0 + x * x + y * y, 1.5) * spot.SpotFactor(cosAngle);
    }
  }
  expected *= spot.radiometric[0];
  auto flux = f.Read("LightFlux:0");
  EXPECT_NEAR(Sum(flux, 0) / expected, 1.0, 0.005);
  // Without the falloff, the measure (alpha) sums to the frustum's solid angle.
  EXPECT_NEAR(Sum(flux, 3) / view.FrustumSolidAngle(), 1.0, 0.005);
}

TEST(LightBuffers, KeepsUnchangedMapsAndRedrawsOnAnyChange)
{
  Fixture f("ball-lens", 64);
  f.Pass->KeepBuffersOn(); // upload the geometry even without caustics
  f.Window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(f.Window);
  gl->MakeCurrent();
  auto scene = [&]() -> const caustics::SceneData&
  { return f.Pass->GetSceneExtractor()->GetScene(); };
  vtkNew<vtkCausticsLightBuffers> kept;
  kept->SetResolution(32);
  auto render = [&](vtkCausticsLightBuffers* buffers)
  { return buffers->Render(gl, f.Pass->GetGeometry(), scene()); };
  ASSERT_TRUE(render(kept));
  EXPECT_FALSE(kept->GetLastRenderReused()) << "a first frame draws";

  // Every texture of every light.
  auto contents = [](vtkCausticsLightBuffers* buffers)
  {
    std::vector<std::vector<double>> all;
    for (int i = 0; i < buffers->GetNumberOfLights(); ++i)
    {
      vtkCausticsGBuffer* g = buffers->GetGBuffer(i);
      for (auto& texture : ReadAll({ g->GetPositionTexture(), g->GetNormalTexture(),
             g->GetAlbedoTexture(), g->GetDepthTexture(), buffers->GetFluxTexture(i) }))
      {
        all.push_back(std::move(texture));
      }
    }
    return all;
  };
  // A mark in the flux tells whether a frame drew the buffers again. (Each G-buffer
  // keeps its targets by its own inputs, GBuffer.KeepsUnchangedTargetsAndRedrawsOnAnyChange:
  // a new intensity leaves them as they are.)
  auto mark = [&]() { Mark(kept->GetFluxTexture(0)); };
  auto marked = [&]() { return Marked(kept->GetFluxTexture(0)); };

  // Nothing changed: the buffers are kept, untouched; a moved camera changes nothing.
  mark();
  ASSERT_TRUE(render(kept));
  EXPECT_TRUE(kept->GetLastRenderReused());
  EXPECT_TRUE(marked());
  f.Renderer->GetActiveCamera()->Azimuth(30.0);
  f.Window->Render(); // a new snapshot of the scene, uploaded
  gl->MakeCurrent();
  EXPECT_TRUE(render(kept) && kept->GetLastRenderReused()) << "the camera is no input";
  EXPECT_TRUE(marked());
  kept->ReuseUnchangedOff(); // wipe the mark
  ASSERT_TRUE(render(kept));
  kept->ReuseUnchangedOn();

  // Each change redraws, to exactly what a fresh instance draws, and the frame
  // after it keeps the new buffers.
  vtkActor* ball = nullptr;
  vtkActor* floor = nullptr;
  BallAndFloor(scene(), ball, floor);
  ASSERT_NE(ball, nullptr);
  ASSERT_NE(floor, nullptr);
  auto* light = vtkLight::SafeDownCast(f.Renderer->GetLights()->GetItemAsObject(0));
  ASSERT_NE(light, nullptr);
  const std::vector<Change> changes = {
    { "a moved actor", [&]() { ball->AddPosition(0.25, 0.0, 0.0); } },
    { "a turned light", [&]() { light->SetPosition(0.3, 1.0, 0.2); } },
    { "the light's intensity", [&]() { light->SetIntensity(2.0); } },
    { "a resolution", [&]() { kept->SetResolution(48); } },
    { "a focus", [&]() { kept->SetFocus(vtkCausticsLightBuffers::FOCUS_SCENE); } },
    { "a material's albedo", [&]() { floor->GetProperty()->SetColor(0.2, 0.4, 0.6); } },
    { "a material's role",
      [&]() { vtkCausticsMaterial::SetRole(ball, vtkCausticsMaterial::ROLE_REFLECTOR); } },
  };
  auto last = contents(kept);
  for (const Change& change : changes)
  {
    mark();
    change.Apply();
    f.Window->Render();
    gl->MakeCurrent();
    ASSERT_TRUE(render(kept));
    EXPECT_FALSE(kept->GetLastRenderReused()) << change.What;
    vtkNew<vtkCausticsLightBuffers> fresh;
    fresh->SetResolution(kept->GetResolution());
    fresh->SetFocus(kept->GetFocus());
    ASSERT_TRUE(render(fresh));
    const auto now = contents(kept);
    EXPECT_TRUE(now == contents(fresh)) << change.What << ": not what a fresh instance draws";
    EXPECT_TRUE(now != last) << change.What << " changes the buffers (else this proves nothing)";
    fresh->ReleaseGraphicsResources(f.Window);
    ASSERT_TRUE(render(kept));
    EXPECT_TRUE(kept->GetLastRenderReused()) << "after " << change.What;
    last = now;
  }

  // Off: every frame draws, the G-buffers too.
  kept->ReuseUnchangedOff();
  mark();
  Mark(kept->GetGBuffer(0)->GetPositionTexture());
  ASSERT_TRUE(render(kept));
  EXPECT_FALSE(kept->GetLastRenderReused());
  EXPECT_FALSE(marked());
  EXPECT_FALSE(Marked(kept->GetGBuffer(0)->GetPositionTexture()));
  std::ostringstream print;
  kept->Print(print);
  EXPECT_NE(print.str().find("ReuseUnchanged: 0"), std::string::npos);
  kept->ReleaseGraphicsResources(f.Window);
}

// Shadow maps alone (ShadowMapsOnly, as the render pass's): no flux and no albedo
// target, the same positions, normals and depth as the full buffers, and turning
// the option off draws the flux and albedo again.
TEST(LightBuffers, ShadowMapsOnlyKeepsPositionsNormalsAndDepth)
{
  Fixture f("ball-lens", 64);
  f.Pass->KeepBuffersOn(); // upload the geometry even without caustics
  f.Window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(f.Window);
  gl->MakeCurrent();
  const caustics::SceneData& scene = f.Pass->GetSceneExtractor()->GetScene();
  vtkNew<vtkCausticsLightBuffers> shadows, full;
  shadows->SetResolution(32);
  shadows->ShadowMapsOnlyOn();
  full->SetResolution(32);
  ASSERT_TRUE(shadows->Render(gl, f.Pass->GetGeometry(), scene));
  ASSERT_TRUE(full->Render(gl, f.Pass->GetGeometry(), scene));
  ASSERT_EQ(shadows->GetNumberOfLights(), 1);
  EXPECT_EQ(shadows->GetFluxTexture(0), nullptr);
  EXPECT_EQ(shadows->GetGBuffer(0)->GetAlbedoTexture()->GetHandle(), 0u);
  ASSERT_NE(full->GetFluxTexture(0), nullptr);
  auto targets = [](vtkCausticsLightBuffers* buffers) {
    vtkCausticsGBuffer* g = buffers->GetGBuffer(0);
    return ReadAll({ g->GetPositionTexture(), g->GetNormalTexture(), g->GetDepthTexture() });
  };
  EXPECT_TRUE(targets(shadows) == targets(full));
  shadows->ShadowMapsOnlyOff();
  ASSERT_TRUE(shadows->Render(gl, f.Pass->GetGeometry(), scene));
  EXPECT_FALSE(shadows->GetLastRenderReused()) << "ShadowMapsOnly is an input";
  ASSERT_NE(shadows->GetFluxTexture(0), nullptr);
  EXPECT_TRUE(ReadAll({ shadows->GetFluxTexture(0), shadows->GetGBuffer(0)->GetAlbedoTexture() }) ==
    ReadAll({ full->GetFluxTexture(0), full->GetGBuffer(0)->GetAlbedoTexture() }));
  EXPECT_TRUE(targets(shadows) == targets(full));
  shadows->ReleaseGraphicsResources(f.Window);
  full->ReleaseGraphicsResources(f.Window);
}

TEST(DirectIrradiance, LitFloorAndShadowUnderTheBall)
{
  Fixture f("ball-lens");
  f.Pass->ComputeDirectIrradianceOn();
  f.Window->Render();
  const auto& scene = f.Pass->GetSceneExtractor()->GetScene();
  auto direct = f.Read("DirectIrradiance");
  vtkDataArray* e = direct->GetPointData()->GetArray(0);
  // Floor point (3, 0, 2): far from the ball's shadow, light straight down at 1 W/m^2.
  double px, py;
  ASSERT_TRUE(scene.View.WorldToPixel({ { 3.0, 0.0, 2.0 } }, px, py));
  vtkIdType id = static_cast<vtkIdType>(py) * 256 + static_cast<vtkIdType>(px);
  EXPECT_NEAR(e->GetComponent(id, 0), 1.0, 1e-4);
  // Under the ball, in its shadow (the light through it is the caustic term).
  ASSERT_TRUE(scene.View.WorldToPixel({ { 0.0, 0.0, 0.5 } }, px, py));
  id = static_cast<vtkIdType>(py) * 256 + static_cast<vtkIdType>(px);
  EXPECT_NEAR(e->GetComponent(id, 0), 0.0, 1e-6);
  // No caustic technique in the base pass: zero caustic irradiance, exactly.
  auto caustic = f.Read("CausticIrradiance");
  EXPECT_EQ(Sum(caustic, 0), 0.0);
}

TEST(RenderPass, SkipsEverythingWithoutSpecularActors)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkPlaneSource> plane;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkNew<vtkLight> light;
  renderer->AddLight(light);
  vtkNew<vtkCausticsRenderPass> pass;
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(64, 64);
  window->AddRenderer(renderer);
  window->Render();
  EXPECT_FALSE(pass->GetLastFrameHadCaustics());
  vtkCausticsTimings* timings = pass->GetTimings();
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    const std::string stage = timings->GetStageName(i);
    EXPECT_TRUE(stage == "scene snapshot" || stage == "vtk delegate") << stage << " ran";
  }
  vtkNew<vtkImageData> image;
  pass->GlobalWarningDisplayOff();
  EXPECT_FALSE(pass->ReadBuffer("CausticIrradiance", image));
  // The picture is VTK's own: the plane was drawn.
  unsigned char* pixels = window->GetPixelData(32, 32, 32, 32, 1);
  EXPECT_GT(pixels[0] + pixels[1] + pixels[2], 0);
  delete[] pixels;
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}

TEST(RenderPass, ReadBufferRejectsUnknownNames)
{
  Fixture f("ring", 64);
  f.Pass->KeepBuffersOn();
  f.Window->Render();
  vtkNew<vtkImageData> image;
  f.Pass->GlobalWarningDisplayOff();
  EXPECT_FALSE(f.Pass->ReadBuffer("NoSuchBuffer", image));
  EXPECT_FALSE(f.Pass->ReadBuffer("LightFlux:7", image));
  EXPECT_FALSE(f.Pass->ReadBuffer("LightFlux:x", image));
  EXPECT_TRUE(f.Pass->ReadBuffer("FinalColor", image));
  EXPECT_TRUE(f.Pass->ReadBuffer("ReceiverMask", image));
}

// Two windows, each with its own pass: releasing one pass's resources while the
// other window's context is current must delete them in their own context, and
// leave the other window's caustics as they were (before, the other pass's
// programs of the same names were deleted and its next frame lost its caustics).
TEST(RenderPass, ReleasingOneWindowKeepsTheOthersCaustics)
{
  auto flux = [](TechniqueFrame& frame)
  {
    frame.Pass->KeepBuffersOn();
    vtkSmartPointer<vtkImageData> image = frame.Render("CausticIrradiance");
    return image ? Sum(image, 0) : -1.0;
  };
  TechniqueFrame kept("caustic-maps", 64, 64);
  const double before = flux(kept);
  ASSERT_GT(before, 0.0);
  {
    TechniqueFrame released("caustic-maps", 64, 64);
    ASSERT_GT(flux(released), 0.0);
    kept.Window->MakeCurrent();
  } // released here, with the kept window's context current
  EXPECT_NEAR(flux(kept), before, 1e-6 * before);
}
