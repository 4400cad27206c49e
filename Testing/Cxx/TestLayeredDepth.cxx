// The layered depth image (vtkCausticsLayeredDepth, 000_54cf099eeccf42d9.txt §2.2):
// the depth complexity it counts, the layers it peels (and those it must not), the
// order and content of the layers, per-object LDIs, a light's view, bad input, and
// the layers kept while nothing they depend on changes.
#include "vtkActor.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

namespace
{
/** A built-in scene rendered once by the base pass, so that its geometry is on the GPU. */
struct Fixture
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsRenderPass> Pass;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  vtkNew<vtkCausticsLayeredDepth> Layers;
  float WorldToClip[16];
  int Size;

  explicit Fixture(const char* scene, int size = 128)
    : Size(size)
  {
    this->Scene->SetSceneName(scene);
    EXPECT_TRUE(this->Scene->Populate(this->Renderer)) << this->Scene->GetLastError();
    this->Renderer->SetPass(this->Pass);
    this->Pass->KeepBuffersOn(); // upload the geometry even without caustics
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
    this->Window->Render();
    caustics::gl::ToColumnMajor(this->SceneData().View.worldToClip, this->WorldToClip);
    this->GL()->MakeCurrent();
  }
  ~Fixture()
  {
    this->GL()->MakeCurrent();
    this->Layers->ReleaseGraphicsResources(this->Window);
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  vtkOpenGLRenderWindow* GL() { return vtkOpenGLRenderWindow::SafeDownCast(this->Window); }
  const caustics::SceneData& SceneData() { return this->Pass->GetSceneExtractor()->GetScene(); }
  bool Render()
  {
    return this->Layers->Render(this->GL(), this->Pass->GetGeometry(), this->SceneData(),
      this->WorldToClip, this->Size, this->Size);
  }
  /** Component c of `texture` layer `layer` at pixel (i, j). */
  double At(const char* texture, int layer, int i, int j, int c)
  {
    vtkNew<vtkImageData> image;
    EXPECT_TRUE(this->Layers->ReadLayer(texture, layer, image));
    return image->GetPointData()->GetArray(0)->GetComponent(
      static_cast<vtkIdType>(j) * this->Size + i, c);
  }
  /** Pixel of a world point in the camera image. */
  void Pixel(double x, double y, double z, int& i, int& j)
  {
    double px = 0, py = 0;
    EXPECT_TRUE(this->SceneData().View.WorldToPixel({ { x, y, z } }, px, py));
    i = static_cast<int>(px);
    j = static_cast<int>(py);
  }
};
}

TEST(LayeredDepth, CountsBallLensDepthComplexityAndPeelsInOrder)
{
  Fixture f("ball-lens");
  ASSERT_TRUE(f.Render());
  // The camera looks down at the ball from above and in front: no view ray through
  // the ball reaches the 12 m floor behind it, so the deepest pixels see the ball's
  // front and back (2); elsewhere the floor (1).
  EXPECT_EQ(f.Layers->ReadDepthComplexity(), 2);
  EXPECT_EQ(f.Layers->ReadNumberOfPeeledLayers(0), 2);
  EXPECT_EQ(f.Layers->GetNumberOfObjects(), 1);
  EXPECT_EQ(f.Layers->GetNumberOfAllocatedLayers(), 8);

  int i, j;
  f.Pixel(0.0, 3.0, 0.0, i, j); // the ball's centre
  EXPECT_EQ(std::lround(f.At("Normal", 0, i, j, 3)), 3) << "front of the ball: a refractor";
  EXPECT_EQ(std::lround(f.At("Normal", 1, i, j, 3)), 3) << "back of the ball";
  EXPECT_LT(f.At("Depth", 0, i, j, 0), f.At("Depth", 1, i, j, 0));
  EXPECT_LT(f.At("Depth", 1, i, j, 0), 1.0);
  // Front and back of a unit sphere along a ray through its centre: 2 m apart. The
  // pixel centre is within half a pixel (~0.02 m at the ball) of the centre ray,
  // which shortens the chord by < 2e-4 m, and the facets' sag is < 1e-3 m.
  double chord2 = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    chord2 += std::pow(f.At("Position", 1, i, j, c) - f.At("Position", 0, i, j, c), 2);
  }
  EXPECT_NEAR(std::sqrt(chord2), 2.0, 2e-3);
  // Outward normals as modelled: the front faces the camera, the back faces away.
  EXPECT_GT(f.At("Normal", 0, i, j, 2), 0.9);
  EXPECT_LT(f.At("Normal", 1, i, j, 2), -0.9);
  EXPECT_EQ(f.At("Complexity", 0, i, j, 0), 2.0);

  // A floor pixel away from the ball: one surface, then nothing.
  f.Pixel(3.0, 0.0, 2.0, i, j);
  EXPECT_EQ(std::lround(f.At("Normal", 0, i, j, 3)), 1);
  EXPECT_NEAR(f.At("Position", 0, i, j, 1), 0.0, 1e-5) << "on the floor plane";
  EXPECT_EQ(f.At("Position", 1, i, j, 3), -1.0) << "cleared: no second surface";
  EXPECT_EQ(f.At("Depth", 1, i, j, 0), 1.0);
  EXPECT_EQ(f.At("Complexity", 0, i, j, 0), 1.0);
}

TEST(LayeredDepth, NeverPeelsBeyondTheDepthComplexity)
{
  Fixture f("ball-lens");
  f.Layers->ReuseUnchangedOff(); // the second frame below must peel again
  ASSERT_TRUE(f.Render());
  // Mark layers 2..7 (beyond the complexity of 2): a later frame must not touch them.
  const float mark[4] = { 7.0f, 7.0f, 7.0f, 7.0f };
  glClearTexSubImage(
    f.Layers->GetPositionTexture(), 0, 0, 0, 2, f.Size, f.Size, 6, GL_RGBA, GL_FLOAT, mark);
  ASSERT_TRUE(f.Render());
  int i, j;
  f.Pixel(3.0, 0.0, 2.0, i, j);
  for (int layer = 2; layer < 8; ++layer)
  {
    EXPECT_EQ(f.At("Position", layer, i, j, 3), 7.0) << "layer " << layer << " was drawn";
  }
  // Layers below the complexity were cleared and peeled again.
  EXPECT_EQ(f.At("Position", 1, i, j, 3), -1.0);

  // A cap below the complexity: only that many layers exist and are peeled.
  f.Layers->SetMaximumNumberOfLayers(1);
  ASSERT_TRUE(f.Render());
  EXPECT_EQ(f.Layers->ReadDepthComplexity(), 2) << "the count is not capped";
  EXPECT_EQ(f.Layers->ReadNumberOfPeeledLayers(0), 1);
  EXPECT_EQ(f.Layers->GetNumberOfAllocatedLayers(), 1);
  f.Pixel(0.0, 3.0, 0.0, i, j);
  EXPECT_EQ(std::lround(f.At("Normal", 0, i, j, 3)), 3) << "the nearest layer is kept";
}

TEST(LayeredDepth, RoleMaskAndPerObjectLayers)
{
  Fixture f("ball-lens");
  f.Layers->SetRoleMask(vtkCausticsSceneGeometry::RoleBit(3));
  ASSERT_TRUE(f.Render());
  EXPECT_EQ(f.Layers->ReadDepthComplexity(), 2) << "the ball alone: front and back";

  f.Layers->SetRoleMask(vtkCausticsSceneGeometry::AllRoles);
  f.Layers->PerObjectOn();
  ASSERT_TRUE(f.Render());
  ASSERT_EQ(f.Layers->GetNumberOfObjects(), 2);
  // Objects follow the scene's mesh order: the floor, then the ball.
  EXPECT_EQ(f.Layers->ReadNumberOfPeeledLayers(0), 1);
  EXPECT_EQ(f.Layers->ReadNumberOfPeeledLayers(1), 2);
  EXPECT_EQ(f.Layers->ReadDepthComplexity(), 2);
  // Each object's LDI holds only its own surfaces: the ball's its front and back,
  // the floor's the floor (in the shadow of the ball, seen in front of it).
  int i, j;
  f.Pixel(0.0, 2.05, 0.3, i, j); // near the ball's bottom, in front of the floor
  const int ballFirst = f.Layers->GetMaximumNumberOfLayers();
  EXPECT_EQ(std::lround(f.At("Normal", ballFirst, i, j, 3)), 3);
  EXPECT_EQ(std::lround(f.At("Normal", ballFirst + 1, i, j, 3)), 3);
  EXPECT_EQ(f.At("Position", 0, i, j, 3), -1.0) << "no floor behind the ball from here";
  f.Pixel(0.0, 0.0, 0.0, i, j); // the floor under the ball
  EXPECT_EQ(std::lround(f.At("Normal", 0, i, j, 3)), 1) << "the floor's own LDI";
  EXPECT_EQ(f.At("Position", ballFirst, i, j, 3), -1.0) << "the ball's LDI is empty there";

  // One LDI per object, capped: the remaining meshes share the last one.
  Fixture pool("pool");
  pool.Layers->PerObjectOn();
  pool.Layers->SetMaximumNumberOfObjects(2);
  ASSERT_TRUE(pool.Render());
  EXPECT_EQ(pool.Layers->GetNumberOfObjects(), 2);
  EXPECT_GE(pool.Layers->ReadNumberOfPeeledLayers(1), 2) << "walls and water share the last";
}

TEST(LayeredDepth, SeesTheSceneFromALight)
{
  Fixture f("ball-lens");
  const caustics::LightView view =
    caustics::ComputeLightView(f.SceneData(), 0, caustics::LightView::Focus::Specular);
  ASSERT_TRUE(view.valid);
  float matrix[16];
  caustics::gl::ToColumnMajor(view.worldToClip, matrix);
  ASSERT_TRUE(
    f.Layers->Render(f.GL(), f.Pass->GetGeometry(), f.SceneData(), matrix, f.Size, f.Size));
  // Straight down through the ball: top, bottom, floor.
  EXPECT_EQ(f.Layers->ReadDepthComplexity(), 3);
  const int c = f.Size / 2;
  EXPECT_NEAR(f.At("Position", 0, c, c, 1), 4.0, 0.01);
  EXPECT_NEAR(f.At("Position", 1, c, c, 1), 2.0, 0.01);
  EXPECT_NEAR(f.At("Position", 2, c, c, 1), 0.0, 1e-5);
}

TEST(LayeredDepth, KeepsUnchangedLayersAndRedrawsOnAnyChange)
{
  Fixture f("ball-lens");
  ASSERT_TRUE(f.Render());
  EXPECT_FALSE(f.Layers->GetLastRenderReused()) << "a first frame draws";
  int i, j;
  f.Pixel(0.0, 3.0, 0.0, i, j); // the ball's centre
  // A mark in layer 0 tells whether a frame drew the layers again.
  const float mark[4] = { 7.0f, 7.0f, 7.0f, 7.0f };
  auto markLayers = [&]()
  {
    glClearTexSubImage(
      f.Layers->GetPositionTexture(), 0, 0, 0, 0, f.Size, f.Size, 1, GL_RGBA, GL_FLOAT, mark);
  };
  auto drawn = [&]() { return f.At("Position", 0, i, j, 3) != 7.0; };

  // Nothing changed: the layers are kept, untouched.
  markLayers();
  ASSERT_TRUE(f.Render());
  EXPECT_TRUE(f.Layers->GetLastRenderReused());
  EXPECT_FALSE(drawn());

  // Each change redraws (and the frame after it keeps the new layers).
  struct Change
  {
    const char* What;
    std::function<void()> Apply;
  };
  vtkActor* ball = nullptr;
  for (const caustics::Mesh& mesh : f.SceneData().Meshes)
  {
    if (f.SceneData().Materials[mesh.material].role == caustics::Role::Refractor)
    {
      ball = mesh.actor;
    }
  }
  ASSERT_NE(ball, nullptr);
  int size = f.Size;
  const std::vector<Change> changes = {
    { "a moved actor", [&]() { ball->AddPosition(0.0, 0.25, 0.0); } },
    { "the camera", [&]() { f.WorldToClip[12] += 0.01f; } },
    { "a resize", [&]() { size = f.Size / 2; } },
    { "the layer cap", [&]() { f.Layers->SetMaximumNumberOfLayers(4); } },
    { "a material's role",
      [&]() { vtkCausticsMaterial::SetRole(ball, vtkCausticsMaterial::ROLE_RECEIVER); } },
  };
  for (const Change& change : changes)
  {
    markLayers();
    change.Apply();
    f.Window->Render(); // a new snapshot of the scene, uploaded
    ASSERT_TRUE(
      f.Layers->Render(f.GL(), f.Pass->GetGeometry(), f.SceneData(), f.WorldToClip, size, size));
    EXPECT_FALSE(f.Layers->GetLastRenderReused()) << change.What;
    if (size == f.Size)
    {
      EXPECT_TRUE(drawn()) << change.What;
    }
    ASSERT_TRUE(
      f.Layers->Render(f.GL(), f.Pass->GetGeometry(), f.SceneData(), f.WorldToClip, size, size));
    EXPECT_TRUE(f.Layers->GetLastRenderReused()) << "after " << change.What;
  }
  // What the layers hold now is the moved ball (a unit sphere about (0, 3.25, 0), not
  // (0, 3, 0); facets sag < 1e-3 m), with the receiver role.
  size = f.Size;
  f.Layers->SetMaximumNumberOfLayers(8);
  caustics::gl::ToColumnMajor(f.SceneData().View.worldToClip, f.WorldToClip);
  ASSERT_TRUE(f.Render());
  vtkNew<vtkImageData> position, normal;
  ASSERT_TRUE(f.Layers->ReadLayer("Position", 0, position));
  ASSERT_TRUE(f.Layers->ReadLayer("Normal", 0, normal));
  int ballPixels = 0;
  double worstMoved = 0.0, farthestOld = 0.0;
  for (vtkIdType t = 0; t < position->GetNumberOfPoints(); ++t)
  {
    double p[4];
    position->GetPointData()->GetArray(0)->GetTuple(t, p);
    if (p[3] < 0.0 || p[1] < 0.5)
    {
      continue; // nothing, or the floor
    }
    ++ballPixels;
    auto radius = [&](double centreY)
    { return std::sqrt(p[0] * p[0] + (p[1] - centreY) * (p[1] - centreY) + p[2] * p[2]); };
    worstMoved = std::max(worstMoved, std::abs(radius(3.25) - 1.0));
    farthestOld = std::max(farthestOld, std::abs(radius(3.0) - 1.0));
    EXPECT_EQ(std::lround(normal->GetPointData()->GetArray(0)->GetComponent(t, 3)), 1)
      << "the ball is a receiver now";
  }
  EXPECT_GT(ballPixels, 1000);
  EXPECT_LT(worstMoved, 2e-3) << "every pixel of the ball shows it where it is now";
  EXPECT_GT(farthestOld, 0.1) << "and not where it was";

  // Off: every frame draws.
  f.Layers->ReuseUnchangedOff();
  markLayers();
  ASSERT_TRUE(f.Render());
  EXPECT_FALSE(f.Layers->GetLastRenderReused());
  EXPECT_TRUE(drawn());
}

TEST(LayeredDepth, RejectsBadSizesAndPrints)
{
  Fixture f("ring", 64);
  f.Layers->GlobalWarningDisplayOff();
  EXPECT_FALSE(
    f.Layers->Render(f.GL(), f.Pass->GetGeometry(), f.SceneData(), f.WorldToClip, 0, 64));
  EXPECT_FALSE(
    f.Layers->Render(f.GL(), f.Pass->GetGeometry(), f.SceneData(), f.WorldToClip, 64, 1 << 20));
  vtkNew<vtkImageData> image;
  EXPECT_FALSE(f.Layers->ReadLayer("Nothing", 0, image));
  ASSERT_TRUE(f.Render());
  EXPECT_FALSE(f.Layers->ReadLayer("Position", 99, image));
  std::ostringstream print;
  f.Layers->Print(print);
  EXPECT_NE(print.str().find("MaximumNumberOfLayers: 8"), std::string::npos);
  EXPECT_NE(print.str().find("ReuseUnchanged: 1"), std::string::npos);
}
