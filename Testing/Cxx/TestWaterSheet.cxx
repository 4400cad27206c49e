// A sinusoidal water sheet over a floor against its exact caustic (issue 13's fold
// test): water of index 1.33 whose surface is y = 1 + A sin(k x) (A = 2 cm,
// wavelength 0.5 m), 6 m wide, over a 2 m floor seen from straight above
// (orthographic, 256 x 256 pixels, 256 x 256 photons), under a sun in the x-y plane.
// The exact floor irradiance, averaged over each pixel, follows from tracing the
// 1-D map x -> x' densely on the CPU: every ray refracts once (Fresnel transmittance
// of unpolarized light) and lands on the floor.
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
constexpr double Amplitude = 0.02, Wavelength = 0.5, Height = 1.0, WaterIndex = 1.33;
constexpr double FloorHalf = 1.0, SheetHalf = 3.0;
constexpr int Size = 256, Photons = 256;
const double WaveNumber = 2.0 * M_PI / Wavelength;

vtkSmartPointer<vtkPolyData> MakeSheet(int resolution)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  for (int j = 0; j <= resolution; ++j)
  {
    const double z = -SheetHalf + 2.0 * SheetHalf * j / resolution;
    for (int i = 0; i <= resolution; ++i)
    {
      const double x = -SheetHalf + 2.0 * SheetHalf * i / resolution;
      points->InsertNextPoint(x, Height + Amplitude * std::sin(WaveNumber * x), z);
      const double slope = Amplitude * WaveNumber * std::cos(WaveNumber * x);
      const double length = std::sqrt(1.0 + slope * slope);
      normals->InsertNextTuple3(-slope / length, 1.0 / length, 0.0);
    }
  }
  vtkNew<vtkCellArray> triangles;
  for (int j = 0; j < resolution; ++j)
  {
    for (int i = 0; i < resolution; ++i)
    {
      const vtkIdType a = j * (resolution + 1) + i, b = a + 1, c = a + resolution + 1, d = c + 1;
      const vtkIdType t1[3] = { a, c, b }, t2[3] = { b, c, d };
      triangles->InsertNextCell(3, t1);
      triangles->InsertNextCell(3, t2);
    }
  }
  auto sheet = vtkSmartPointer<vtkPolyData>::New();
  sheet->SetPoints(points);
  sheet->SetPolys(triangles);
  sheet->GetPointData()->SetNormals(normals);
  return sheet;
}

vtkSmartPointer<vtkActor> MakeActor(vtkPolyData* data)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/**
 * The exact floor irradiance (W/m^2 per W/m^2 of sun) averaged over each pixel
 * column, the sun `elevation` degrees above the floor, travelling towards +x.
 */
std::vector<double> ExactColumns(double elevation)
{
  const double e = elevation * M_PI / 180.0;
  const double ix = std::cos(e), iy = -std::sin(e);
  const int samples = 4000000;
  const double first = -SheetHalf, last = SheetHalf; // the sheet
  const double dx = (last - first) / samples;
  const double pixel = 2.0 * FloorHalf / Size;
  std::vector<double> columns(Size, 0.0);
  for (int s = 0; s < samples; ++s)
  {
    const double x = first + (s + 0.5) * dx;
    const double h = Height + Amplitude * std::sin(WaveNumber * x);
    const double slope = Amplitude * WaveNumber * std::cos(WaveNumber * x);
    const double nx = -slope / std::sqrt(1.0 + slope * slope), ny = 1.0 / std::sqrt(1.0 + slope * slope);
    const double cosI = -(ix * nx + iy * ny), eta = 1.0 / WaterIndex;
    const double cosT = std::sqrt(std::max(0.0, 1.0 - eta * eta * (1.0 - cosI * cosI)));
    const double tx = eta * ix + (eta * cosI - cosT) * nx, ty = eta * iy + (eta * cosI - cosT) * ny;
    const double rs = std::pow((cosI - WaterIndex * cosT) / (cosI + WaterIndex * cosT), 2);
    const double rp = std::pow((WaterIndex * cosI - cosT) / (WaterIndex * cosI + cosT), 2);
    const double landed = x + h * tx / -ty;
    const int column = static_cast<int>(std::floor((landed + FloorHalf) / pixel));
    if (column >= 0 && column < Size)
    {
      // The sun's flux through the surface element (dx, h' dx): its cross-section of
      // the beam, |sin e + h' cos e| dx, times the Fresnel transmittance.
      const double section = std::abs(std::sin(e) + slope * std::cos(e)) * dx;
      columns[column] += section * (1.0 - 0.5 * (rs + rp)) / pixel;
    }
  }
  return columns;
}

struct SheetFrame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkLight> Sun;
  vtkSmartPointer<vtkCausticsRenderPass> Pass;

  explicit SheetFrame(const char* technique)
  {
    vtkNew<vtkPlaneSource> floor;
    floor->SetOrigin(-FloorHalf, 0, FloorHalf);
    floor->SetPoint1(FloorHalf, 0, FloorHalf);
    floor->SetPoint2(-FloorHalf, 0, -FloorHalf);
    floor->Update();
    this->Renderer->AddActor(MakeActor(floor->GetOutput()));
    auto water = MakeActor(MakeSheet(512));
    vtkCausticsMaterial::MakeGlass(water->GetProperty(), WaterIndex);
    this->Renderer->AddActor(water);
    this->Sun->SetLightTypeToSceneLight();
    this->Sun->SetPositional(false);
    this->Sun->SetFocalPoint(0, 0, 0);
    this->Sun->SetIntensity(1.0);
    this->Renderer->AddLight(this->Sun);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetPosition(0, 5, 0);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 0, -1); // x to the right
    camera->SetParallelScale(FloorHalf);
    camera->SetClippingRange(1, 10);
    this->Pass = vtkCausticsTechniques::Create(technique);
    this->Pass->SetLightBufferResolution(Photons);
    this->Pass->KeepBuffersOn();
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Size, Size);
    this->Window->AddRenderer(this->Renderer);
  }
  ~SheetFrame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }

  struct Error
  {
    double RelativeL2 = 1.0;
    double Flux = 0.0;
  };

  /**
   * The caustic irradiance against the exact columns, over the inner 3/4 of the
   * floor (the sheet's edges stay out of it at every elevation tested).
   */
  Error Compare(double elevation, int reconstruction)
  {
    const double e = elevation * M_PI / 180.0;
    this->Sun->SetPosition(-std::cos(e), std::sin(e), 0.0);
    if (auto* screenSpace = vtkCausticsScreenSpacePhotonPass::SafeDownCast(this->Pass))
    {
      screenSpace->SetReconstruction(reconstruction);
    }
    if (auto* maps = vtkCausticsHierarchicalCausticMapPass::SafeDownCast(this->Pass))
    {
      maps->SetReconstruction(reconstruction);
    }
    this->Window->Render();
    vtkNew<vtkImageData> image;
    Error error;
    if (!this->Pass->ReadBuffer("CausticIrradiance", image))
    {
      ADD_FAILURE() << "no caustic irradiance";
      return error;
    }
    const std::vector<double> exact = ExactColumns(elevation);
    vtkDataArray* irradiance = image->GetPointData()->GetArray(0);
    double difference = 0.0, norm = 0.0, test = 0.0;
    for (int y = Size / 8; y < Size - Size / 8; ++y)
    {
      for (int x = Size / 8; x < Size - Size / 8; ++x)
      {
        const double value = irradiance->GetComponent(y * Size + x, 0);
        difference += (value - exact[x]) * (value - exact[x]);
        norm += exact[x] * exact[x];
        test += value - exact[x];
      }
    }
    error.RelativeL2 = std::sqrt(difference / norm);
    double truth = 0.0;
    for (int x = Size / 8; x < Size - Size / 8; ++x)
    {
      truth += exact[x] * (Size - Size / 4);
    }
    error.Flux = 1.0 + test / truth;
    return error;
  }
};
}

namespace
{
struct Bounds
{
  double Elevation, Triangles, Splats; // most relative L2 of each reconstruction
};

/** `flux`: most |flux ratio - 1| of either reconstruction. */
void CheckSheet(const char* technique, double flux, std::initializer_list<Bounds> cases)
{
  SheetFrame frame(technique);
  for (const Bounds& c : cases)
  {
    const auto triangles = frame.Compare(c.Elevation, 1);
    const auto splats = frame.Compare(c.Elevation, 0);
    EXPECT_LT(triangles.RelativeL2, c.Triangles) << technique << ", triangles, sun at " << c.Elevation;
    EXPECT_LT(splats.RelativeL2, c.Splats) << technique << ", splats, sun at " << c.Elevation;
    EXPECT_LT(triangles.RelativeL2, 0.5 * splats.RelativeL2) << technique << ", sun at " << c.Elevation;
    EXPECT_NEAR(triangles.Flux, 1.0, flux) << technique << ", triangles, sun at " << c.Elevation;
    EXPECT_NEAR(splats.Flux, 1.0, flux) << technique << ", splats, sun at " << c.Elevation;
    std::cout << technique << ", sun at " << c.Elevation << " degrees: relative L2 splats "
              << 100.0 * splats.RelativeL2 << " %, triangles " << 100.0 * triangles.RelativeL2
              << " %; flux " << splats.Flux << ", " << triangles.Flux << "\n";
  }
}
}

// Caustic triangles keep the crests' focusing that splats blur. Measured relative L2
// (splats, triangles): screen-space 14.1 and 6.1 % under a vertical sun, 51.4 and
// 13.9 % at 60 degrees; caustic maps 31.4 and 6.7 %, 73.5 and 14.0 %. The bounds
// sit just above. The flux: screen-space within 1e-4 (bound 0.2 %), caustic maps
// within 0.4 % (bound 0.5 %). (At 30 degrees the floor lies beyond
// the crests' folds, which are narrower than the photons' spacing: screen-space 50
// and 61 %, not asserted; see docs/accuracy.md.)
TEST(WaterSheet, CausticTrianglesMatchTheExactFoci)
{
  CheckSheet("screen-space", 0.002, { { 90.0, 0.07, 0.155 }, { 60.0, 0.155, 0.53 } });
  CheckSheet("caustic-maps", 0.005, { { 90.0, 0.075, 0.33 }, { 60.0, 0.155, 0.76 } });
}
