// A sinusoidal water sheet over a floor against its exact caustic (issue 13's fold
// test): water of index 1.33 whose surface is y = 1 + A sin(k x) (A = 2 cm,
// wavelength 0.5 m), 6 m wide, over a 2 m floor seen from straight above
// (orthographic, 256 x 256 pixels, 256 x 256 photons), under a sun in the x-y plane.
// The exact floor irradiance, averaged over each pixel, follows from tracing the
// 1-D map x -> x' densely on the CPU: every ray refracts once (Fresnel transmittance
// of unpolarized light) and lands on the floor.
#include "TestWaterSheetUtilities.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCubeSource.h"
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
#include <functional>
#include <iostream>
#include <vector>

namespace
{
using namespace watersheet;
constexpr double FloorHalf = 1.0;
constexpr int Size = 256, Photons = 256;

/**
 * The exact floor irradiance (W/m^2 per W/m^2 of sun) averaged over each pixel
 * column, the sun `elevation` degrees above the floor, travelling towards +x.
 */
std::vector<double> ExactColumns(double elevation, double viewHalf)
{
  const double e = elevation * M_PI / 180.0;
  const double ix = std::cos(e), iy = -std::sin(e);
  const int samples = 4000000;
  const double first = -SheetHalf, last = SheetHalf; // the sheet
  const double dx = (last - first) / samples;
  const double pixel = 2.0 * viewHalf / Size;
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
    const int column = static_cast<int>(std::floor((landed + viewHalf) / pixel));
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

  double ViewHalf; // half the floor's width the camera frames (m)

  /** `viewHalf`: half the width of floor the camera frames, centred under the sheet. */
  explicit SheetFrame(const char* technique, double viewHalf = FloorHalf)
    : ViewHalf(viewHalf)
  {
    this->Renderer->AddActor(MakeFloor(FloorHalf));
    auto water = MakeActor(MakeSheet(2048, 128));
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
    camera->SetParallelScale(viewHalf);
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
  /**
   * A silver square beyond the floor's edge, facing up: the sun's light it reflects
   * leaves up and away, and it is out of the camera's view. It must change nothing.
   */
  void AddIdleMirror()
  {
    const double origin[3] = { 3.5, 0.5, -0.5 }, u[3] = { 1.0, 0.0, 0.0 }, v[3] = { 0.0, 0.0, 1.0 };
    this->Renderer->AddActor(MakeMirror(origin, u, v));
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
    int Peaks = 0;                // fold peaks of the exact solution in the compared part
    double PeakLow = 1e300;       // least and greatest technique / exact over them
    double PeakHigh = 0.0;
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
    if (!this->Pass->ReadBuffer("CausticIrradiance", image))
    {
      ADD_FAILURE() << "no caustic irradiance";
      return Error();
    }
    return this->CompareImage(image->GetPointData()->GetArray(0), elevation);
  }

  /**
   * The CPU reference's caustic irradiance of the same frame (camera rays through the
   * water, `photons` per light; `footprint`: PixelFootprintEstimate, else its kernel of
   * two pixel footprints) against the exact columns.
   */
  Error CompareReference(double elevation, double photons, bool footprint)
  {
    const double e = elevation * M_PI / 180.0;
    this->Sun->SetPosition(-std::cos(e), std::sin(e), 0.0);
    vtkNew<vtkCausticsReferenceRenderer> reference;
    reference->SetInputRenderer(this->Renderer);
    reference->SetImageSize(Size, Size);
    reference->SetPhotonsPerLight(static_cast<vtkIdType>(photons));
    reference->SetCameraSeesRefractors(false);
    reference->SetPixelFootprintEstimate(footprint);
    if (!reference->Update())
    {
      ADD_FAILURE() << reference->GetLastError();
      return Error();
    }
    return this->CompareImage(
      reference->GetOutput()->GetPointData()->GetArray("CausticIrradiance"), elevation);
  }

  /** `irradiance` (Size^2 tuples, row by row) against the exact columns. */
  Error CompareImage(vtkDataArray* irradiance, double elevation)
  {
    Error error;
    const std::vector<double> exact = ExactColumns(elevation, this->ViewHalf);
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
    // The fold peaks: columns where the exact irradiance is a local maximum (over two
    // columns each side) at 1.5 times its mean or more, each against the technique's
    // highest column mean within one column of it (a peak's place is quantized to
    // whole pixels).
    const int first = Size / 8, last = Size - Size / 8;
    std::vector<double> columns(Size, 0.0);
    double mean = 0.0;
    for (int x = first; x < last; ++x)
    {
      for (int y = first; y < last; ++y)
      {
        columns[x] += irradiance->GetComponent(y * Size + x, 0) / (last - first);
      }
      mean += exact[x] / (last - first);
    }
    for (int x = first + 2; x < last - 2; ++x)
    {
      const bool peak = exact[x] >= 1.5 * mean &&
        exact[x] >= *std::max_element(exact.begin() + x - 2, exact.begin() + x + 3);
      if (peak)
      {
        const double ratio =
          *std::max_element(columns.begin() + x - 1, columns.begin() + x + 2) / exact[x];
        error.PeakLow = std::min(error.PeakLow, ratio);
        error.PeakHigh = std::max(error.PeakHigh, ratio);
        ++error.Peaks;
      }
    }
    return error;
  }
};
}

namespace
{
struct Bounds
{
  double Elevation, Triangles, Splats; // most relative L2 of each reconstruction
  double Flux;                         // most |flux ratio - 1| of either
  double Gain = 0.5;                   // most triangles' relative L2 over the splats'
  double PeakFloor = 0.0; // least triangles' fold peak over the exact one (at most 1.1)
};

void CheckSheet(const char* technique, std::initializer_list<Bounds> cases)
{
  SheetFrame frame(technique);
  for (const Bounds& c : cases)
  {
    const auto triangles = frame.Compare(c.Elevation, 1);
    const auto splats = frame.Compare(c.Elevation, 0);
    EXPECT_LT(triangles.RelativeL2, c.Triangles) << technique << ", triangles, sun at " << c.Elevation;
    EXPECT_LT(splats.RelativeL2, c.Splats) << technique << ", splats, sun at " << c.Elevation;
    EXPECT_LT(triangles.RelativeL2, c.Gain * splats.RelativeL2) << technique << ", sun at " << c.Elevation;
    EXPECT_NEAR(triangles.Flux, 1.0, c.Flux) << technique << ", triangles, sun at " << c.Elevation;
    EXPECT_NEAR(splats.Flux, 1.0, c.Flux) << technique << ", splats, sun at " << c.Elevation;
    EXPECT_GE(triangles.Peaks, 3) << technique << ", sun at " << c.Elevation;
    EXPECT_GT(triangles.PeakLow, c.PeakFloor) << technique << ", sun at " << c.Elevation;
    EXPECT_LT(triangles.PeakHigh, 1.1) << technique << ", sun at " << c.Elevation;
    std::cout << technique << ", sun at " << c.Elevation << " degrees: relative L2 splats "
              << 100.0 * splats.RelativeL2 << " %, triangles " << 100.0 * triangles.RelativeL2
              << " %; flux " << splats.Flux << ", " << triangles.Flux << "; " << triangles.Peaks
              << " fold peaks at " << triangles.PeakLow << " to " << triangles.PeakHigh
              << " of the exact (triangles), " << splats.PeakLow << " to " << splats.PeakHigh
              << " (splats)\n";
  }
}
}

// Caustic triangles keep the crests' focusing that splats blur. The camera frames 2 m
// of floor under the 6 m sheet, so the photons go to the part of the sheet whose light
// it sees (vtkCausticsLightBuffers FOCUS_SEEN), through a light view fitted to that
// part's outline (a rectangle: caustics::LightView::aspect). The sheet has 2048 facets
// across, so that it is the sine the exact solution assumes (512 facets differ from it
// by 2.9 % at 30 degrees: MakeSheet). Measured relative L2 (splats, triangles), the
// largest flux error and the fold peaks (issue 13: within 10 % of the pixel-averaged
// exact value) of the triangles:
// - screen-space: 6.7 and 0.36 % under a vertical sun, 37.2 and 0.40 % at 60 degrees
//   (flux within 0.12 %, peaks 0.997-1.002), 26.9 and 1.93 % at 30 degrees (flux
//   1.0040: the floor beyond the crests' folds; peaks 0.941-0.993);
// - caustic maps: 5.2 and 0.36 %, 19.4 and 0.40 %, 17.8 and 1.73 % (flux within 0.28 %;
//   peaks 0.997-0.998, 0.998-1.002, 0.941-0.993: the triangles go to the camera's
//   view as screen-space's do, and the photons land alike on the flat floor). When
//   they went into the map's finest level (512 texels, averaged over each pixel's
//   footprint) they read 0.38, 5.4 and 9.5 %, peaks down to 0.79 at 30 degrees: a
//   texel a pixel wide across the crests spread a fold into the next column;
// - the splats' fold peaks: 0.91, 0.64 and 0.72-0.74 with screen-space.
// With a square light view (before), screen-space's triangles were 8.2 % at 30
// degrees (peaks 0.909-0.969); with 512 facets as well, 10.1 % (0.906-0.980). The
// bounds sit just beyond the figures. (Aimed at the whole sheet: screen-space
// triangles 6.1, 13.9 and 60.8 %, with 512 facets.)
TEST(WaterSheet, CausticTrianglesMatchTheExactFoci)
{
  CheckSheet("screen-space",
    { { 90.0, 0.005, 0.075, 0.002, 0.5, 0.99 }, { 60.0, 0.006, 0.40, 0.002, 0.5, 0.99 },
      { 30.0, 0.025, 0.28, 0.005, 0.1, 0.93 } });
  CheckSheet("caustic-maps",
    { { 90.0, 0.005, 0.055, 0.002, 0.5, 0.99 }, { 60.0, 0.006, 0.20, 0.003, 0.5, 0.99 },
      { 30.0, 0.02, 0.20, 0.002, 0.15, 0.93 } });
}

// The caustic maps' triangles do not depend on the map's resolution: they go to the
// camera's view, and the map only lands the photons (on the flat floor, exactly at any
// resolution) and sizes the splats of the refused triangles. Measured at 30 degrees,
// CausticMapResolution 256 and 2048: 1.73 % both, peaks 0.941-0.993. (In the map's
// finest level, averaged over each pixel's footprint, they were 9.5 / 2.5 / 2.0 % at
// 512 / 1024 / 2048 texels, peaks from 0.79 / 0.92 / 0.94.)
TEST(WaterSheet, CausticMapTrianglesDoNotDependOnTheMap)
{
  SheetFrame frame("caustic-maps");
  auto* maps = vtkCausticsHierarchicalCausticMapPass::SafeDownCast(frame.Pass);
  ASSERT_NE(maps, nullptr);
  std::vector<double> errors;
  for (int resolution : { 256, 2048 })
  {
    maps->SetCausticMapResolution(resolution);
    const auto error = frame.Compare(30.0, 1);
    EXPECT_LT(error.RelativeL2, 0.02) << "map " << resolution;
    EXPECT_NEAR(error.Flux, 1.0, 0.001) << "map " << resolution;
    EXPECT_GT(error.PeakLow, 0.93) << "map " << resolution;
    EXPECT_LT(error.PeakHigh, 1.1) << "map " << resolution;
    errors.push_back(error.RelativeL2);
    std::cout << "caustic-maps triangles, sun at 30 degrees, map " << resolution << ": relative L2 "
              << 100.0 * error.RelativeL2 << " %, flux " << error.Flux << ", fold peaks "
              << error.PeakLow << " to " << error.PeakHigh << " of the exact\n";
  }
  EXPECT_NEAR(errors.front(), errors.back(), 0.002);
}

// The reference's pixel-footprint estimate (vtkCausticsReferenceRenderer::
// PixelFootprintEstimate: the flux landing in each pixel's footprint over its area) is
// the exact solution's pixel average, folds included; its kernel of two pixel
// footprints (the tests' reference) blurs the folds as screen-space's splats do.
// 1.6e7 photons. Measured, sun at 30 / 60 degrees: footprint relative L2 6.3 / 3.3 %
// (the photons' noise), flux 1.008 / 1.000 (at 30 degrees the techniques' triangles
// too read 1.004), fold peaks 0.997-1.001 / 0.9996-1.0005; kernel 26.8 / 37.2 %, peaks
// 0.72-0.75 / 0.63.
TEST(WaterSheet, ReferenceFootprintEstimateIsThePixelMean)
{
  SheetFrame frame("screen-space");
  for (double elevation : { 30.0, 60.0 })
  {
    const auto footprint = frame.CompareReference(elevation, 1.6e7, true);
    const auto kernel = frame.CompareReference(elevation, 1.6e7, false);
    std::cout << "reference, sun at " << elevation << " degrees: pixel footprint relative L2 "
              << 100.0 * footprint.RelativeL2 << " %, flux " << footprint.Flux << ", fold peaks "
              << footprint.PeakLow << " to " << footprint.PeakHigh << "; kernel "
              << 100.0 * kernel.RelativeL2 << " %, flux " << kernel.Flux << ", peaks "
              << kernel.PeakLow << " to " << kernel.PeakHigh << "\n";
    EXPECT_NEAR(footprint.Flux, 1.0, 0.01) << elevation;
    EXPECT_LT(footprint.RelativeL2, 0.075) << elevation;
    EXPECT_GE(footprint.Peaks, 3) << elevation;
    EXPECT_GT(footprint.PeakLow, 0.98) << elevation;
    EXPECT_LT(footprint.PeakHigh, 1.02) << elevation;
    EXPECT_LT(kernel.PeakHigh, footprint.PeakLow - 0.15) << "the kernel blurs the folds";
  }
}

// The caustic does not depend on how closely the camera frames it: zoomed in 2 and 4
// times on the floor's centre, the photons follow the view (FOCUS_SEEN) and the
// caustic triangles stay close to the exact solution. Measured relative L2 of
// screen-space triangles, sun at 60 degrees: 0.40 % (2 m of floor in view, above),
// 0.99 % (1 m, and the same beside the idle mirror) and 0.69 % (0.5 m); aimed at the
// whole sheet instead (FOCUS_SPECULAR), 32.3 % and 35.4 %. With a square light view
// (before): 0.52, 0.61 and 0.68 %; the rectangle's finer lattice across the crests
// meets the folds at other places, and the 1 m view reads 0.99 %. (With 512 facets
// across the sheet: 2.4 % and 3.4 %, where pixels of 2 mm showed its 1.2 cm facets
// against the exact sinusoid.) The caustic maps' triangles read the same (0.99 and
// 0.69 %): they go to the camera's view; in the map's finest level they read 21.0 and
// 18.6 %, the fold column drawn narrower and higher than the exact. Bounds just above.
TEST(WaterSheet, CausticDoesNotDependOnTheZoom)
{
  const struct
  {
    double ViewHalf, Bound;
  } zooms[] = { { 0.5, 0.012 }, { 0.25, 0.009 } };
  for (const auto& zoom : zooms)
  {
    SheetFrame frame("screen-space", zoom.ViewHalf);
    const auto seen = frame.Compare(60.0, 1);
    frame.Pass->GetLightBuffers()->SetFocus(vtkCausticsLightBuffers::FOCUS_SPECULAR);
    const auto whole = frame.Compare(60.0, 1);
    const double width = 2.0 * zoom.ViewHalf;
    EXPECT_LT(seen.RelativeL2, zoom.Bound) << "floor " << width << " m wide in view";
    EXPECT_NEAR(seen.Flux, 1.0, 0.005) << "floor " << width << " m wide in view";
    EXPECT_LT(seen.RelativeL2, 0.5 * whole.RelativeL2) << "floor " << width << " m wide in view";
    std::cout << "screen-space triangles, sun at 60 degrees, " << width
              << " m of floor in view: relative L2 " << 100.0 * seen.RelativeL2 << " %, flux "
              << seen.Flux << "; aimed at the whole sheet " << 100.0 * whole.RelativeL2 << " %\n";
    if (zoom.ViewHalf == 0.5)
    {
      // A second specular mesh whose light goes nowhere in view leaves the water's
      // photons where they were (caustics::PhotonFocusBounds narrows each sheet).
      frame.Pass->GetLightBuffers()->SetFocus(vtkCausticsLightBuffers::FOCUS_SEEN);
      frame.AddIdleMirror();
      const auto beside = frame.Compare(60.0, 1);
      EXPECT_LT(beside.RelativeL2, zoom.Bound) << "beside an idle mirror";
      EXPECT_NEAR(beside.Flux, 1.0, 0.005) << "beside an idle mirror";
      std::cout << "  beside a mirror that lights nothing in view: relative L2 "
                << 100.0 * beside.RelativeL2 << " %, flux " << beside.Flux << "\n";
    }
    // The caustic maps' triangles go to the camera's view too.
    SheetFrame maps("caustic-maps", zoom.ViewHalf);
    const auto mapped = maps.Compare(60.0, 1);
    EXPECT_LT(mapped.RelativeL2, zoom.Bound) << "caustic maps, floor " << width << " m wide";
    EXPECT_NEAR(mapped.Flux, 1.0, 0.005) << "caustic maps, floor " << width << " m wide";
    std::cout << "caustic-maps triangles, " << width << " m of floor in view: relative L2 "
              << 100.0 * mapped.RelativeL2 << " %, flux " << mapped.Flux << "\n";
  }
}

namespace
{
constexpr double WallFace = -0.55, WallHeight = 0.8; // the wall's face away from the sun

/** x (m from the wall's far face) of the floor under pixel column `column`. */
double BehindTheWall(int column)
{
  return -FloorHalf + (column + 0.5) * 2.0 * FloorHalf / Size - WallFace;
}

/** Flat water (index 1.33, Height up, its normal up) over the floor, and a sun
 * `elevation` degrees up travelling towards +x. The water's actor is returned. */
vtkActor* AddFlatWaterUnderTheSun(vtkRenderer* renderer, double elevation)
{
  vtkNew<vtkPlaneSource> surface;
  surface->SetOrigin(-SheetHalf, Height, SheetHalf);
  surface->SetPoint1(SheetHalf, Height, SheetHalf);
  surface->SetPoint2(-SheetHalf, Height, -SheetHalf);
  surface->Update();
  auto water = MakeActor(surface->GetOutput());
  vtkCausticsMaterial::MakeGlass(water->GetProperty(), WaterIndex);
  renderer->AddActor(water);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  const double e = elevation * M_PI / 180.0;
  sun->SetPosition(-std::cos(e), std::sin(e), 0.0);
  sun->SetFocalPoint(0, 0, 0);
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);
  return water;
}

/**
 * The caustic irradiance of the floor (2 FloorHalf wide) seen from straight above by
 * `technique` (Photons per side, Size^2 pixels), `configure` applied to its pass
 * first; null on failure.
 */
vtkSmartPointer<vtkImageData> CausticFromAbove(vtkRenderer* renderer, const char* technique,
  const std::function<void(vtkCausticsRenderPass*)>& configure = {})
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetPosition(0, 5, 0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, -1); // x to the right
  camera->SetParallelScale(FloorHalf);
  camera->SetClippingRange(1, 10);
  auto pass = vtkCausticsTechniques::Create(technique);
  pass->SetLightBufferResolution(Photons);
  pass->KeepBuffersOn();
  if (configure)
  {
    configure(pass);
  }
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(Size, Size);
  window->AddRenderer(renderer);
  window->Render();
  auto image = vtkSmartPointer<vtkImageData>::New();
  const bool read = pass->ReadBuffer("CausticIrradiance", image);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return read ? image : nullptr;
}

/**
 * Floor irradiance under flat water (index 1.33, 1 m up) with a wall 0.8 m tall
 * standing in it, the sun 50 degrees up travelling towards +x, seen from straight
 * above by `technique`: the mean caustic irradiance of each pixel column over
 * |z| < 0.5 m (empty on failure). `hidden`: the caustic maps' HiddenReceivers;
 * `store`: the frame keeps the distance impostors' caustic store (the camera view
 * reads it), which takes the photons no receiver layer lands; off, the camera view
 * traces in screen space alone and no photon is stored. `triangles`: caustic
 * triangles (the camera's view) instead of the map's splats.
 */
std::vector<double> FloorBehindTheWall(
  const char* technique, bool hidden, bool store = true, bool triangles = false)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  renderer->AddActor(MakeFloor(FloorHalf));
  vtkNew<vtkCubeSource> wall;
  wall->SetBounds(WallFace - 0.1, WallFace, 0.0, WallHeight, -FloorHalf, FloorHalf);
  wall->Update();
  renderer->AddActor(MakeActor(wall->GetOutput()));
  AddFlatWaterUnderTheSun(renderer, 50.0);
  auto image = CausticFromAbove(renderer, technique,
    [hidden, store, triangles](vtkCausticsRenderPass* pass)
    {
      if (auto* maps = vtkCausticsHierarchicalCausticMapPass::SafeDownCast(pass))
      {
        maps->SetHiddenReceivers(hidden);
        maps->SetReconstruction(triangles ? 1 : 0);
      }
      if (!store)
      {
        pass->SetCameraViewMethod(vtkCausticsRenderPass::SCREEN_SPACE);
      }
    });
  std::vector<double> columns;
  if (image)
  {
    vtkDataArray* irradiance = image->GetPointData()->GetArray(0);
    const double pixel = 2.0 * FloorHalf / Size;
    columns.assign(Size, 0.0);
    int rows = 0;
    for (int y = 0; y < Size; ++y)
    {
      const double z = -FloorHalf + (y + 0.5) * pixel;
      if (std::abs(z) >= 0.5)
      {
        continue;
      }
      ++rows;
      for (int x = 0; x < Size; ++x)
      {
        columns[x] += irradiance->GetComponent(y * Size + x, 0);
      }
    }
    for (double& column : columns)
    {
      column /= rows;
    }
  }
  return columns;
}

/**
 * The floor's irradiance under clear flat water, the sun (1 W/m^2) 50 degrees up:
 * sin 50 degrees x T(40 degrees), the unpolarized Fresnel transmittance at 40 degrees
 * of incidence. `cosRefracted`: the cosine of the refracted ray's angle to the vertical.
 */
double UnderFlatWaterAt50Degrees(double& cosRefracted)
{
  const double cosI = std::cos(40.0 * M_PI / 180.0);
  const double cosT = std::sqrt(1.0 - (1.0 - cosI * cosI) / (WaterIndex * WaterIndex));
  const double rs = std::pow((cosI - WaterIndex * cosT) / (cosI + WaterIndex * cosT), 2);
  const double rp = std::pow((WaterIndex * cosI - cosT) / (WaterIndex * cosI + cosT), 2);
  cosRefracted = cosT;
  return std::sin(50.0 * M_PI / 180.0) * (1.0 - 0.5 * (rs + rp));
}

/** The mean of `columns` over the floor from `from` to `to` (m behind the wall). */
double MeanBehindTheWall(const std::vector<double>& columns, double from, double to)
{
  double sum = 0.0;
  int count = 0;
  for (int x = 0; x < static_cast<int>(columns.size()); ++x)
  {
    if (BehindTheWall(x) >= from && BehindTheWall(x) <= to)
    {
      sum += columns[x];
      ++count;
    }
  }
  return count > 0 ? sum / count : -1.0;
}
}

// The floor just behind a wall standing in water is hidden from the sun by the wall,
// yet the water bends light onto it: beyond the wall's refracted shadow (0.8 m x
// tan 28.9 degrees = 0.441 m from its far face) and within its straight one (0.8 m x
// tan 40 degrees = 0.671 m), the light's own view sees the wall, not the floor. Flat
// water passes a uniform irradiance, sin 50 degrees x T(40 degrees), to the whole floor
// beyond the refracted shadow. The caustic maps' hidden receivers' map holds that
// strip; without it the strip's photons go to the distance impostors' caustic store,
// whose estimate the final render reads there, and without the store too the strip
// stays dark. The kernels blur the shadow's edge over
// about 8 cm each side (their radius at this photon spacing). Measured: strip 0.749,
// across the strip's far edge 0.748, open floor 0.748 (exact 0.748), the shadow's
// edge (where the floor first gets half) 0.452 m, in the shadow 0, the strip without the
// map 0.675 (the store's coarser estimate, its shadow edge spread over its read
// window), without the store too 0. The edge lies 1-2 cm late: photons that pass the wall's top corner within the
// trace's tolerance (two map texels, about 2 cm here) land on the wall's top. Before
// the hidden map's splats took the photons beside its edge (their kernels reach across
// it), the strip dipped to 0.52 along that edge; before the kernels left out
// neighbours on parallel planes (the wall's top), the shadow's edge was smeared 15 cm
// into the strip.
TEST(WaterSheet, FloorHiddenByAWallGetsTheRefractedLight)
{
  double cosT;
  const double exact = UnderFlatWaterAt50Degrees(cosT);
  const double edge = 0.441, straight = 0.671, blur = 0.08;
  const auto with = FloorBehindTheWall("caustic-maps", true);
  const auto stored = FloorBehindTheWall("caustic-maps", false);
  const auto without = FloorBehindTheWall("caustic-maps", false, false);
  ASSERT_EQ(with.size(), static_cast<std::size_t>(Size));
  ASSERT_EQ(stored.size(), static_cast<std::size_t>(Size));
  ASSERT_EQ(without.size(), static_cast<std::size_t>(Size));
  const double strip = MeanBehindTheWall(with, edge + blur, straight - 0.01);
  const double across = MeanBehindTheWall(with, straight - 0.05, straight + 0.05);
  const double open = MeanBehindTheWall(with, straight + 0.05, 1.4);
  const double shadow = MeanBehindTheWall(with, 0.03, edge - blur);
  const double fromStore = MeanBehindTheWall(stored, edge + blur, straight - 0.01);
  const double dark = MeanBehindTheWall(without, edge + blur, straight - 0.01);
  // Where the floor behind the wall first gets half the light.
  double half = -1.0;
  for (int x = 0; x < Size && half < 0.0; ++x)
  {
    half = BehindTheWall(x) > 0.0 && with[x] >= 0.5 * exact ? BehindTheWall(x) : -1.0;
  }
  std::cout << "floor behind the wall, exact " << exact << " W/m^2: hidden strip " << strip
            << ", across its far edge " << across << ", open floor " << open
            << ", in the shadow " << shadow << ", the shadow's edge at " << half
            << " m (exact " << edge << "), the strip without the hidden receivers' map "
            << fromStore << " (the caustic store's), without the store too " << dark << "\n";
  EXPECT_NEAR(strip / exact, 1.0, 0.02);
  EXPECT_NEAR(across / exact, 1.0, 0.02);
  EXPECT_NEAR(open / exact, 1.0, 0.02);
  EXPECT_NEAR(half, edge, 0.03);
  EXPECT_LT(shadow, 0.01 * exact);
  EXPECT_NEAR(fromStore / exact, 0.9, 0.1) << "the store takes the strip's photons";
  EXPECT_LT(dark, 0.01 * exact) << "the strip must need the hidden receivers' map or the store";
  // Caustic triangles go to the camera's view, the hidden receivers' photons too.
  const auto triangles = FloorBehindTheWall("caustic-maps", true, true, true);
  ASSERT_EQ(triangles.size(), static_cast<std::size_t>(Size));
  const double triangleStrip = MeanBehindTheWall(triangles, edge + blur, straight - 0.01);
  const double triangleOpen = MeanBehindTheWall(triangles, straight + 0.05, 1.4);
  const double triangleShadow = MeanBehindTheWall(triangles, 0.03, edge - blur);
  std::cout << "caustic triangles: hidden strip " << triangleStrip << ", open floor "
            << triangleOpen << ", in the shadow " << triangleShadow << "\n";
  EXPECT_NEAR(triangleStrip / exact, 1.0, 0.02);
  EXPECT_NEAR(triangleOpen / exact, 1.0, 0.02);
  EXPECT_LT(triangleShadow, 0.01 * exact);
}

// Water that absorbs (Beer-Lambert, 0.5, 0.2 and 0.05 1/m per channel): flat and 1 m
// over the floor, the sun 50 degrees up. Under it the floor gets sin 50 degrees x
// T(40 degrees) x exp(-sigma L), L = 1 m / cos 28.9 degrees the refracted ray's path in
// the water, in every channel. The water is an open refractor (one sheet, no exit
// face): the caustic maps, cascaded and the impostors measured absorption from an
// entry to an exit and took none here (1.25 times the reference's flux under the
// pool's absorbing water); screen-space did. Measured, every channel over the exact:
// screen-space 1.0000, caustic maps 0.9994, cascaded 1.0013, impostors 1.0000; before,
// the red channel of the three 1.769, 1.773, 1.770 (exp(sigma L), none absorbed).
TEST(WaterSheet, AbsorbingWaterDimsTheFloorAsBeerLambert)
{
  double cosT;
  const double clear = UnderFlatWaterAt50Degrees(cosT);
  const double sigma[3] = { 0.5, 0.2, 0.05 };
  for (const char* technique : { "screen-space", "caustic-maps", "cascaded", "impostors" })
  {
    SCOPED_TRACE(technique);
    vtkNew<vtkOpenGLRenderer> renderer;
    renderer->AddActor(MakeFloor(FloorHalf));
    vtkActor* water = AddFlatWaterUnderTheSun(renderer, 50.0);
    vtkCausticsMaterial::SetAttenuation(water->GetProperty(), sigma);
    auto image = CausticFromAbove(renderer, technique);
    ASSERT_TRUE(image);
    vtkDataArray* irradiance = image->GetPointData()->GetArray(0);
    double mean[3] = { 0.0, 0.0, 0.0 };
    int count = 0;
    const double pixel = 2.0 * FloorHalf / Size;
    for (int y = 0; y < Size; ++y)
    {
      for (int x = 0; x < Size; ++x)
      {
        if (std::abs(-FloorHalf + (x + 0.5) * pixel) < 0.5 &&
          std::abs(-FloorHalf + (y + 0.5) * pixel) < 0.5)
        {
          for (int c = 0; c < 3; ++c)
          {
            mean[c] += irradiance->GetComponent(y * Size + x, c);
          }
          ++count;
        }
      }
    }
    std::cout << technique << ", the floor under absorbing water over the exact:";
    for (int c = 0; c < 3; ++c)
    {
      const double exact = clear * std::exp(-sigma[c] * Height / cosT);
      std::cout << " " << mean[c] / count / exact;
      EXPECT_NEAR(mean[c] / count / exact, 1.0, 0.02) << "channel " << c;
    }
    std::cout << "\n";
  }
}
