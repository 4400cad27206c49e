// Numerical stress for the cascaded photon pass (vtkCausticsCascadedPhotonPass):
// grazing light, an object where every refracted photon is totally reflected inside,
// indices of refraction 1 and 4, no photons, an empty scene, NaN and degenerate
// triangles, the scene scaled by 1e-3 and 1e4, and a window resized between
// frames. Every frame must finish with finite caustic irradiance and, where physics
// says so, the right amount of it. (Random scenes: CausticsStress --technique cascaded.)
#include "TestReferenceUtilities.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsMaterial.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace
{
/** A scene (built-in, or empty for nullptr) rendered by the cascaded pass. */
struct Cascade
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkCausticsCascadedPhotonPass> Pass;
  vtkNew<vtkRenderWindow> Window;

  explicit Cascade(const char* scene, double ior = 0.0, int size = 128)
  {
    if (scene)
    {
      vtkNew<vtkCausticsBuiltinScene> builtin;
      builtin->SetSceneName(scene);
      if (ior > 0.0)
      {
        builtin->SetRefractiveIndex(ior);
      }
      EXPECT_TRUE(builtin->Populate(this->Renderer));
    }
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
  }
  ~Cascade()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  /** The sun of the tests: `irradiance` W/m^2 travelling along d. */
  void SetSun(double dx, double dy, double dz, double irradiance = 2.0)
  {
    this->Renderer->RemoveAllLights();
    this->Renderer->AddLight(reftest::Directional(dx, dy, dz, irradiance));
  }
  /** Renders; the caustic irradiance, or nullptr when the frame made none. */
  vtkSmartPointer<vtkImageData> Render()
  {
    this->Window->Render();
    auto image = vtkSmartPointer<vtkImageData>::New();
    return this->Pass->GetLastFrameHadCaustics() &&
        this->Pass->ReadBuffer("CausticIrradiance", image)
      ? image
      : nullptr;
  }
};

vtkDataArray* Irradiance(vtkImageData* image)
{
  return image->GetPointData()->GetArray("CausticIrradiance");
}

int NonFinite(vtkImageData* image)
{
  vtkDataArray* a = Irradiance(image);
  int count = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    count += std::isfinite(a->GetVariantValue(i).ToDouble()) ? 0 : 1;
  }
  return count;
}

double Largest(vtkImageData* image)
{
  vtkDataArray* a = Irradiance(image);
  double largest = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    largest = std::max(largest, a->GetVariantValue(i).ToDouble());
  }
  return largest;
}

/** Checks a frame that must have caustics: finite everywhere, some light. */
void CheckFrame(const vtkSmartPointer<vtkImageData>& image, const char* what)
{
  ASSERT_NE(image, nullptr) << what;
  EXPECT_EQ(NonFinite(image), 0) << what;
  EXPECT_GT(Largest(image), 0.0) << what;
}

/** A glass actor of IOR `ior` made of the given polygons (3 or 4 corners). */
vtkSmartPointer<vtkActor> Glass(
  const std::vector<std::vector<std::array<double, 3>>>& faces, double ior)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  for (const auto& face : faces)
  {
    polys->InsertNextCell(static_cast<int>(face.size()));
    for (const auto& corner : face)
    {
      polys->InsertCellPoint(points->InsertNextPoint(corner.data()));
    }
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  auto actor = reftest::MakeActor(mesh, "glass");
  vtkCausticsMaterial::MakeGlass(actor->GetProperty(), ior);
  return actor;
}
}

TEST(CascadedStress, GrazingLight)
{
  // 89.9 degrees from the vertical: the floor is seen edge-on from the light.
  Cascade c("ball-lens");
  const double angle = 89.9 * 3.14159265358979323846 / 180.0;
  c.SetSun(std::sin(angle), -std::cos(angle), 0.0);
  auto image = c.Render();
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(NonFinite(image), 0);
}

TEST(CascadedStress, TotalInternalReflectionOnly)
{
  // A Porro prism under a vertical 2 W/m^2 sun: light enters the top face head-on,
  // is totally reflected by both 45-degree faces and leaves through the top, back
  // up to the sky; nothing comes down (reached: 0 W/m^2 everywhere). The same prism
  // of index 1 lets the sun through: 2 W/m^2 under it.
  for (double ior : { 1.5, 1.0 })
  {
    Cascade c("ball-lens");
    c.Renderer->RemoveAllViewProps();
    c.Renderer->AddActor(reftest::Floor(4.0));
    const double h = 2.0, s = 0.5;
    c.Renderer->AddActor(
      Glass({ { { -s, h + s, s }, { s, h + s, s }, { s, h + s, -s }, { -s, h + s, -s } },
              { { -s, h + s, -s }, { 0, h, -s }, { 0, h, s }, { -s, h + s, s } },
              { { s, h + s, s }, { 0, h, s }, { 0, h, -s }, { s, h + s, -s } },
              { { -s, h + s, s }, { 0, h, s }, { s, h + s, s } },
              { { s, h + s, -s }, { 0, h, -s }, { -s, h + s, -s } } },
        ior));
    c.SetSun(0.0, -1.0, 0.0);
    c.Window->Render();
    vtkNew<vtkImageData> image;
    ASSERT_TRUE(c.Pass->ReadBuffer("CausticIrradiance", image));
    EXPECT_EQ(NonFinite(image), 0);
    const double largest = Largest(image);
    std::cout << "IOR " << ior << ": largest caustic irradiance under the prism: " << largest
              << " W/m^2\n";
    if (ior > 1.0)
    {
      EXPECT_LT(largest, 0.2); // 10 % of the sun's
    }
    else
    {
      EXPECT_GT(largest, 1.8);
    }
  }
}

TEST(CascadedStress, IndicesOneAndFour)
{
  for (double ior : { 1.0, 4.0 })
  {
    Cascade c("ball-lens", ior);
    CheckFrame(c.Render(), ior == 1.0 ? "IOR 1" : "IOR 4");
  }
}

TEST(CascadedStress, NoPhotons)
{
  {
    Cascade c("ball-lens");
    c.Pass->SetNumberOfPhotons(0);
    auto image = c.Render();
    ASSERT_NE(image, nullptr);
    EXPECT_EQ(Largest(image), 0.0);
  }
  {
    // One texel of light buffer, one photon.
    Cascade c("ball-lens");
    c.Pass->SetLightBufferResolution(1);
    c.Pass->SetNumberOfPhotons(1);
    auto image = c.Render();
    if (image)
    {
      EXPECT_EQ(NonFinite(image), 0);
    }
  }
}

TEST(CascadedStress, EmptyScene)
{
  Cascade c(nullptr);
  c.SetSun(0.0, -1.0, 0.0);
  EXPECT_EQ(c.Render(), nullptr);
}

TEST(CascadedStress, DegenerateAndNaNTriangles)
{
  Cascade c("ball-lens");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  c.Renderer->AddActor(Glass({ { { nan, 1.0, 0.0 }, { 1.0, 1.0, 0.0 }, { 0.0, 1.0, 1.0 } },
                               { { 2.0, 1.0, 2.0 }, { 2.0, 1.0, 2.0 }, { 2.0, 1.0, 2.0 } },
                               { { -2.0, 1.0, 2.0 }, { -1.0, 1.0, 2.0 }, { 0.0, 1.0, 2.0 } } },
    1.5));
  CheckFrame(c.Render(), "NaN and degenerate triangles");
}

TEST(CascadedStress, ExtremeScales)
{
  // A directional light's caustic irradiance does not depend on the scene's size:
  // the ball lens scaled by 1e-3 and 1e4 (geometry and camera), with the same
  // sample set (FrameIndex 0), gives the picture of scale 1.
  std::vector<double> reference;
  for (double scale : { 1.0, 1e-3, 1e4 })
  {
    Cascade c("ball-lens", 0.0, 128);
    vtkActorCollection* actors = c.Renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor())
    {
      actor->SetScale(scale);
    }
    vtkCamera* camera = c.Renderer->GetActiveCamera();
    double position[3], focal[3];
    camera->GetPosition(position);
    camera->GetFocalPoint(focal);
    camera->SetPosition(scale * position[0], scale * position[1], scale * position[2]);
    camera->SetFocalPoint(scale * focal[0], scale * focal[1], scale * focal[2]);
    c.Renderer->ResetCameraClippingRange();
    auto image = c.Render();
    CheckFrame(image, "scaled");
    if (!image)
    {
      continue;
    }
    vtkDataArray* a = Irradiance(image);
    std::vector<double> values(a->GetNumberOfValues());
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      values[i] = a->GetVariantValue(i).ToDouble();
    }
    if (scale == 1.0)
    {
      reference = values;
      continue;
    }
    double difference = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < values.size() && i < reference.size(); ++i)
    {
      difference += (values[i] - reference[i]) * (values[i] - reference[i]);
      norm += reference[i] * reference[i];
    }
    const double relative = std::sqrt(difference / std::max(norm, 1e-300));
    std::cout << "scale " << scale << ": relative L2 against scale 1: " << relative << "\n";
    EXPECT_LT(relative, 0.01) << scale; // reached 0.0012 and 0.0017
  }
}

TEST(CascadedStress, WindowResizedBetweenFrames)
{
  Cascade c("ball-lens", 0.0, 128);
  for (const auto& size : { std::array<int, 2>{ 128, 128 }, std::array<int, 2>{ 200, 90 },
         std::array<int, 2>{ 64, 160 }, std::array<int, 2>{ 128, 128 } })
  {
    c.Window->SetSize(size[0], size[1]);
    auto image = c.Render();
    CheckFrame(image, "resized");
    if (image)
    {
      int dims[3];
      image->GetDimensions(dims);
      EXPECT_EQ(dims[0], size[0]);
      EXPECT_EQ(dims[1], size[1]);
    }
  }
}
