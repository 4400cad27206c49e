// The receiver's caustic irradiance must not depend on how the camera frames the
// scene (issue 13, "camera independence"), nor hold only for the suns the other tests
// have (EverySurfaceTechniqueUnderEverySun). A glass ball under a tilted sun (a
// scene the other tests do not have) is seen from a sweep of cameras, and every
// surface technique (screen-space, caustic maps, cascaded, impostors) is compared
// with the CPU reference of the same view, which
// traces in world space and so is framing-independent by construction:
// - zoom from the whole scene to the caustic alone, the ball off-screen;
// - orthographic and perspective projections;
// - near/far ratios 10 to 1e5;
// - elevations 10 to 90 degrees at four azimuths.
// The bounds (per technique, below) are the worst figure reached over the sweep
// plus a margin for the reference's noise and rasterization differences. Each
// view renders its reference once (1 M photons, 128^2 pixels: about 1 s).
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int ImageSize = 128;
constexpr double Pi = 3.14159265358979323846;

/** One camera of the sweep. */
struct View
{
  std::string Name;
  double Position[3];
  double Focal[3];
  double ViewAngle = 30.0;      // degrees; perspective only
  double ParallelScale = 0.0;   // > 0: orthographic
  double Near = 0.0, Far = 0.0; // clipping range (m); 0: fit to the scene
  double Azimuth = 0.0;         // degrees; orients "up" when looking straight down
};

/** The caustic's centre: the tilted sun's focus through the ball, near the origin. */
const double Caustic[3] = { 0.6, 0.0, 0.4 };

View Orbit(double elevation, double azimuth, double distance)
{
  const double e = elevation * Pi / 180.0, a = azimuth * Pi / 180.0;
  View v;
  v.Name = "elevation " + std::to_string(static_cast<int>(elevation)) + ", azimuth " +
    std::to_string(static_cast<int>(azimuth));
  v.Position[0] = Caustic[0] + distance * std::cos(e) * std::sin(a);
  v.Position[1] = Caustic[1] + distance * std::sin(e);
  v.Position[2] = Caustic[2] + distance * std::cos(e) * std::cos(a);
  std::copy(Caustic, Caustic + 3, v.Focal);
  v.ViewAngle = 40.0;
  v.Azimuth = azimuth;
  return v;
}

std::vector<View> Sweep()
{
  std::vector<View> views;
  // Zoom: from the whole scene to the caustic alone (the ball leaves the frame
  // at about 25 degrees).
  for (double angle : { 40.0, 25.0, 15.0, 8.0 })
  {
    View v{ "zoom " + std::to_string(static_cast<int>(angle)) + " degrees", { 0.0, 5.657, 5.657 },
      { Caustic[0], Caustic[1], Caustic[2] } };
    v.ViewAngle = angle;
    views.push_back(v);
  }
  // Orthographic: the whole ball, then the caustic alone.
  for (double scale : { 4.0, 1.2 })
  {
    View v{ "orthographic, scale " + std::to_string(scale).substr(0, 3), { 0.0, 5.657, 5.657 },
      { Caustic[0], Caustic[1], Caustic[2] } };
    v.ParallelScale = scale;
    views.push_back(v);
  }
  // Clipping ranges from tight (near/far 10) to far past the scene (1e5); the
  // scene lies between 2 m and 15 m from the camera.
  const double ranges[3][2] = { { 2.0, 20.0 }, { 0.02, 20.0 }, { 0.001, 100.0 } };
  for (const auto& range : ranges)
  {
    View v{ "near/far " + std::to_string(static_cast<int>(range[1] / range[0] + 0.5)),
      { 0.0, 5.657, 5.657 }, { Caustic[0], Caustic[1], Caustic[2] } };
    v.Near = range[0];
    v.Far = range[1];
    views.push_back(v);
  }
  for (double elevation : { 10.0, 30.0, 60.0, 90.0 })
  {
    for (double azimuth : { 0.0, 90.0, 180.0, 270.0 })
    {
      views.push_back(Orbit(elevation, azimuth, 7.0));
    }
  }
  return views;
}

void PlaceCamera(vtkRenderer* renderer, const View& v)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(v.Position);
  camera->SetFocalPoint(v.Focal);
  const double dx = v.Focal[0] - v.Position[0], dz = v.Focal[2] - v.Position[2];
  // Looking straight down, "up" is along the ground, turned by the azimuth.
  if (std::abs(dx) + std::abs(dz) < 1e-6)
  {
    const double a = v.Azimuth * Pi / 180.0;
    camera->SetViewUp(-std::sin(a), 0.0, -std::cos(a));
  }
  else
  {
    camera->SetViewUp(0.0, 1.0, 0.0);
  }
  camera->SetParallelProjection(v.ParallelScale > 0.0);
  if (v.ParallelScale > 0.0)
  {
    camera->SetParallelScale(v.ParallelScale);
  }
  camera->SetViewAngle(v.ViewAngle);
  camera->OrthogonalizeViewUp();
  if (v.Far > 0.0)
  {
    camera->SetClippingRange(v.Near, v.Far);
  }
  else
  {
    renderer->ResetCameraClippingRange();
  }
}

/**
 * The ball lens under a sun tilted off the vertical (the built-in one is vertical):
 * travelling along `direction`, or by default along (0.2, -1, 0.133), which moves the
 * caustic to about (0.6, 0, 0.4).
 */
void TiltTheSun(vtkRenderer* renderer, const double* direction = nullptr)
{
  vtkLight* sun = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  ASSERT_NE(sun, nullptr);
  const double tilted[3] = { 0.2, -1.0, 0.133 };
  const double* d = direction ? direction : tilted;
  sun->SetPosition(-d[0], -d[1], -d[2]);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
}

struct Figures
{
  double RelativeL2 = 0.0;
  double FluxRatio = 0.0;
  bool Fitted = false;
};

/** A surface technique and its bounds over the sweep. */
struct Technique
{
  std::string Name;
  double RelativeL2Bound;
  double FluxBound;
  double WorstL2 = 0.0;
  double WorstFlux = 0.0;
};

/** The scene in one view: its reference, then each technique against it. */
class ViewComparison
{
public:
  /** `sun`: the direction the sun's light travels; nullptr: TiltTheSun()'s. */
  explicit ViewComparison(const View& v, const double* sun = nullptr)
  {
    this->Scene->SetSceneName("ball-lens");
    EXPECT_TRUE(this->Scene->Populate(this->Renderer)) << this->Scene->GetLastError();
    TiltTheSun(this->Renderer, sun);
    PlaceCamera(this->Renderer, v);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(ImageSize, ImageSize);
    this->Window->AddRenderer(this->Renderer);
    this->Reference->SetInputRenderer(this->Renderer);
    this->Reference->SetImageSize(ImageSize, ImageSize);
    this->Reference->SetPhotonsPerLight(1000000);
    EXPECT_TRUE(this->Reference->Update()) << this->Reference->GetLastError();
  }

  Figures Compare(const std::string& technique)
  {
    vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
    this->Renderer->SetPass(pass);
    this->Window->Render();
    Figures figures;
    vtkNew<vtkImageData> caustic;
    EXPECT_TRUE(pass->GetLastFrameHadCaustics());
    EXPECT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic));
    if (auto* ssp = vtkCausticsScreenSpacePhotonPass::SafeDownCast(pass))
    {
      figures.Fitted = ssp->GetLastTraceViewFitted();
    }
    vtkNew<vtkCausticsErrorMetrics> metrics;
    metrics->SetMaskArrayName("ReceiverMask");
    metrics->SetAreaArrayName("PixelArea");
    EXPECT_TRUE(metrics->Compute(caustic, this->Reference->GetOutput())) << metrics->GetLastError();
    EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
    figures.RelativeL2 = metrics->GetRelativeL2Error();
    figures.FluxRatio = metrics->GetFluxRatio();
    this->Renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(this->Window);
    return figures;
  }

  /** Compares each technique, checks its bounds and keeps its worst figures. */
  void CheckEach(std::vector<Technique>& techniques, const std::string& view)
  {
    for (Technique& t : techniques)
    {
      const Figures f = this->Compare(t.Name);
      std::cout << t.Name << ", " << view << ": relative L2 " << f.RelativeL2 << ", flux ratio "
                << f.FluxRatio << (f.Fitted ? " (fitted trace view)" : "") << "\n";
      EXPECT_LT(f.RelativeL2, t.RelativeL2Bound) << t.Name;
      EXPECT_NEAR(f.FluxRatio, 1.0, t.FluxBound) << t.Name;
      t.WorstL2 = std::max(t.WorstL2, f.RelativeL2);
      t.WorstFlux = std::max(t.WorstFlux, std::abs(f.FluxRatio - 1.0));
    }
  }

private:
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsReferenceRenderer> Reference;
};

/** Each technique's worst figures over a sweep. */
void PrintWorst(const std::vector<Technique>& techniques)
{
  for (const Technique& t : techniques)
  {
    std::cout << t.Name << ": worst relative L2 " << t.WorstL2 << ", worst flux error "
              << t.WorstFlux << "\n";
  }
}
}

// Reached at 128^2 pixels, default settings, the reference at 1 M photons (this
// machine, llvmpipe), worst over the 25 views:
// - screen-space: relative L2 0.070 (zoomed to 8 degrees with the ball off-screen:
//   the fitted trace view spreads its pixels over ball and caustic; the camera's
//   own view gave 2.65 there), flux within 0.7 %. Before the splats were drawn with a
//   guard band (vtkCausticsPhotonSplatter: the GL dropped every photon that landed
//   just outside the view, and the pixels along the borders lost its kernel), 0.092
//   and 2.3 %;
// - caustic maps (traced from the light, framing-independent already): relative
//   L2 0.023, flux within 0.7 %;
// - cascaded: 0.105 (zoomed to 8 degrees), flux within 1.7 % (elevation 10);
// - impostors: 0.062, flux within 0.4 % (0.110 straight down, the ball above its
//   caustic, while neighbours beyond 8 unoccluded spacings did not widen a kernel).
// Bounds: the worst figure plus about 20 % of it for the reference's noise and
// rasterization differences between GPUs.
TEST(CameraIndependence, EverySurfaceTechniqueInEveryView)
{
  std::vector<Technique> techniques = {
    Technique{ "screen-space", 0.085, 0.01 },
    Technique{ "caustic-maps", 0.03, 0.01 },
    Technique{ "cascaded", 0.126, 0.021 },
    Technique{ "impostors", 0.075, 0.006 },
  };
  for (const View& v : Sweep())
  {
    SCOPED_TRACE(v.Name);
    ViewComparison comparison(v);
    comparison.CheckEach(techniques, v.Name);
  }
  PrintWorst(techniques);
}

namespace
{
/** A sun `elevation` degrees above the horizon, from `azimuth` degrees about +y. */
struct Sun
{
  double Elevation;
  double Azimuth;
  double Direction[3]; // the way its light travels
  View Camera;         // looking across at the ball's foot and the caustic
};

std::vector<Sun> SunSweep()
{
  std::vector<Sun> suns;
  for (double elevation : { 40.0, 55.0, 70.0 })
  {
    for (double azimuth : { 30.0, 120.0, 210.0, 300.0 })
    {
      Sun s{ elevation, azimuth, {}, {} };
      const double e = elevation * Pi / 180.0, a = azimuth * Pi / 180.0;
      s.Direction[0] = -std::cos(e) * std::sin(a);
      s.Direction[1] = -std::sin(e);
      s.Direction[2] = -std::cos(e) * std::cos(a);
      // The ray through the ball's centre (0, 3, 0) meets the floor at the caustic's
      // centre; the camera looks at the middle between it and the ball's foot, from
      // 55 degrees up and 120 degrees round from the sun.
      const double reach = 3.0 / std::tan(e);
      const double focal[3] = { -0.5 * reach * std::sin(a), 0.0, -0.5 * reach * std::cos(a) };
      View v = Orbit(55.0, azimuth + 120.0, 10.0);
      for (int c = 0; c < 3; ++c)
      {
        v.Position[c] += focal[c] - Caustic[c];
        v.Focal[c] = focal[c];
      }
      v.ViewAngle = 45.0;
      v.Name = "sun at elevation " + std::to_string(static_cast<int>(elevation)) + ", azimuth " +
        std::to_string(static_cast<int>(azimuth));
      s.Camera = v;
      suns.push_back(s);
    }
  }
  return suns;
}
}

// The same four techniques under suns the other tests do not have: 40 to 70 degrees
// up, from four sides, each seen from a camera that frames the ball and its caustic
// (which moves up to 3.6 m from the ball's foot). Reached at 128^2 pixels, default
// settings, worst over the 12 suns (each at 40 degrees up):
// - screen-space: relative L2 0.053, flux within 0.13 %;
// - caustic maps: 0.036, flux within 0.54 %;
// - cascaded: 0.062, flux within 0.65 %;
// - impostors: 0.048, flux within 0.10 % (0.064 while neighbours beyond 8 unoccluded
//   spacings did not widen a kernel: past the focus its photons printed the grid).
// Bounds: the worst figure plus about 20 %; the flux, a few tenths of a percent more.
// The sun the impostors' own test has, 38 degrees up, reads 7.3 % at 256^2 against a
// sharper reference (technique-distance-impostors.md, "Measured").
TEST(CameraIndependence, EverySurfaceTechniqueUnderEverySun)
{
  std::vector<Technique> techniques = {
    Technique{ "screen-space", 0.064, 0.005 },
    Technique{ "caustic-maps", 0.043, 0.008 },
    Technique{ "cascaded", 0.075, 0.01 },
    Technique{ "impostors", 0.058, 0.005 },
  };
  for (const Sun& sun : SunSweep())
  {
    SCOPED_TRACE(sun.Camera.Name);
    ViewComparison comparison(sun.Camera, sun.Direction);
    comparison.CheckEach(techniques, sun.Camera.Name);
  }
  PrintWorst(techniques);
}

namespace
{
/**
 * The caustic irradiance of a built-in scene seen through a camera narrowed to
 * `viewAngle` degrees, with a silver square 1 m wide facing up at x = `mirrorX`
 * (none at 0), from `technique`'s first frame (empty on failure).
 */
std::vector<float> CausticBesideAMirror(
  const char* scene, double viewAngle, double mirrorX, const std::string& technique)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> builtin;
  builtin->SetSceneName(scene);
  EXPECT_TRUE(builtin->Populate(renderer)) << builtin->GetLastError();
  if (mirrorX != 0.0)
  {
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(mirrorX, 0.5, -0.5);
    plane->SetPoint1(mirrorX + 1.0, 0.5, -0.5);
    plane->SetPoint2(mirrorX, 0.5, 0.5);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(plane->GetOutputPort());
    vtkNew<vtkActor> mirror;
    mirror->SetMapper(mapper);
    const double n[3] = { 0.155, 0.117, 0.138 }, k[3] = { 4.83, 3.12, 2.15 };
    vtkCausticsMaterial::MakeMirror(mirror->GetProperty(), n, k);
    renderer->AddActor(mirror);
  }
  renderer->GetActiveCamera()->SetViewAngle(viewAngle);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(ImageSize, ImageSize);
  window->AddRenderer(renderer);
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
  pass->SetLightBufferResolution(128);
  renderer->SetPass(pass);
  window->Render();
  vtkNew<vtkImageData> caustic;
  EXPECT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic));
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  vtkDataArray* values = caustic->GetPointData()->GetArray("CausticIrradiance");
  std::vector<float> irradiance;
  for (vtkIdType i = 0; values && i < values->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      irradiance.push_back(static_cast<float>(values->GetComponent(i, c)));
    }
  }
  return irradiance;
}

/** Relative L2 of `b` against `a` (1 when either is empty or their sizes differ). */
double RelativeDifference(const std::vector<float>& a, const std::vector<float>& b)
{
  if (a.empty() || a.size() != b.size())
  {
    return 1.0;
  }
  double difference = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    difference += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    norm += double(a[i]) * a[i];
  }
  return norm > 0.0 ? std::sqrt(difference / norm) : 1.0;
}
}

// A mirror that sends its light to the sky, far from a camera zoomed in on the
// caustic, changes nothing, wherever it stands. Before the photon frusta's focus
// (LightView::focus) was read by the stages after them, it moved the caustic maps'
// receiver-incidence ray onto the pool's wall (its view turned: the zoomed pool's
// caustic changed by 3.8 %), and it stretched screen-space's fitted trace view and
// tolerance over empty space (the zoomed ball lens changed by 20 % with the mirror at
// 12 m, 50 % at 30 m).
TEST(CameraIndependence, AnIdleMirrorFarAwayChangesNothing)
{
  for (const char* technique : { "screen-space", "caustic-maps" })
  {
    SCOPED_TRACE(technique);
    // The pool's water is a sheet: its photons are aimed at the part whose light the
    // camera sees, with or without the mirror (which lights nothing in view).
    const auto alone = CausticBesideAMirror("pool", 8.0, 0.0, technique);
    const auto beside = CausticBesideAMirror("pool", 8.0, 30.0, technique);
    EXPECT_LT(RelativeDifference(alone, beside), 1e-3) << "pool, mirror at 30 m";
    // The ball's stray light may reach the mirror, which sends it up and away: only
    // the ball is aimed at, wherever the mirror stands.
    const auto near = CausticBesideAMirror("ball-lens", 12.0, 12.0, technique);
    const auto far = CausticBesideAMirror("ball-lens", 12.0, 30.0, technique);
    EXPECT_LT(RelativeDifference(near, far), 1e-3) << "ball lens, mirror at 12 m and 30 m";
    std::cout << technique << ": pool with and without the mirror differ by "
              << 100.0 * RelativeDifference(alone, beside)
              << " %; the ball lens with it at 12 m and 30 m by "
              << 100.0 * RelativeDifference(near, far) << " %\n";
  }
}
