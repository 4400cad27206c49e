// Single scattering in a homogeneous medium against closed forms, for
// Henyey-Greenstein g in {-0.7, 0, 0.7} and per-channel coefficients. A small glass
// plate (0.2 m x 0.05 m x 0.2 m) at the top of the scene turns the straight-down
// directional light into a thin collimated beam; an orthographic camera looks down
// at it at 30 degrees. The medium fills the scene's bounding box.
// - Volume caustic: across the beam's image, sum_i L_i dx = sigma_s p(theta)
//   Phi(y) exp(-sigma_t s_cam) / sin(alpha): the beam's flux Phi(y) = E A T_plate
//   exp(-sigma_t (y_plate - y)) scattered once towards the camera, whatever the beam's
//   profile or the kernel, for a camera ray crossing it at angle alpha.
// - Airlight away from the beam: sigma_s p E int exp(-sigma_t (l_light + l_camera)),
//   integrated in closed form along the straight ray.
#include "TestReferenceUtilities.h"

#include "vtkCausticsMedium.h"
#include "vtkCubeSource.h"

#include <gtest/gtest.h>

#include <cmath>

using reftest::Pi;

namespace
{
const double Irradiance = 3.0;
const double PlateBottom = 2.95, PlateTop = 3.0, PlateHalf = 0.1;
const double Box[6] = { -2, 2, 0, PlateTop, -2, 2 }; // the scene's bounds: the medium
const double SigmaS[3] = { 0.10, 0.20, 0.15 }, SigmaA[3] = { 0.05, 0.0, 0.10 };
const double Look = 30.0 * Pi / 180.0; // camera looks down by this angle

double Phase(double cosTheta, double g)
{
  // Henyey-Greenstein, written out here rather than taken from the reference.
  return (1 - g * g) / (4 * Pi * std::pow(1 + g * g - 2 * g * cosTheta, 1.5));
}

/** Distance along the ray from p in direction d until it leaves the box (p inside). */
double ExitDistance(const double p[3], const double d[3])
{
  double exit = 1e300;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] > 0)
    {
      exit = std::min(exit, (Box[2 * a + 1] - p[a]) / d[a]);
    }
    else if (d[a] < 0)
    {
      exit = std::min(exit, (Box[2 * a] - p[a]) / d[a]);
    }
  }
  return exit;
}

struct Plate
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsMedium> medium;
  Plate(double g)
  {
    this->renderer->AddActor(reftest::Floor(2.0));
    vtkNew<vtkCubeSource> cube;
    cube->SetBounds(-PlateHalf, PlateHalf, PlateBottom, PlateTop, -PlateHalf, PlateHalf);
    cube->Update();
    auto plate = reftest::MakeActor(cube->GetOutput(), "plate");
    vtkCausticsMaterial::MakeGlass(plate->GetProperty(), 1.5);
    this->renderer->AddActor(plate);
    this->renderer->AddLight(reftest::Directional(0, -1, 0, Irradiance));
    this->medium->SetScatteringCoefficient(SigmaS[0], SigmaS[1], SigmaS[2]);
    this->medium->SetAbsorptionCoefficient(SigmaA[0], SigmaA[1], SigmaA[2]);
    this->medium->SetAnisotropy(g);
    vtkCausticsMedium::AttachTo(this->renderer, this->medium);
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetParallelScale(1.1);
    camera->SetFocalPoint(0.0, 1.5, 0.0);
    camera->SetPosition(0.0, 1.5 + 20.0 * std::sin(Look), 20.0 * std::cos(Look));
    camera->SetViewUp(0, 1, 0);
    camera->OrthogonalizeViewUp();
    camera->SetClippingRange(0.1, 100.0);
  }
};
}

class ReferenceMedium : public ::testing::TestWithParam<double>
{
};

TEST_P(ReferenceMedium, BeamAndAirlightMatchClosedForms)
{
  const double g = GetParam();
  Plate scene(g);
  const int size = 96;
  auto reference = reftest::MakeReference(scene.renderer, size, size, 20000);
  reference->SetVolumePhotonsPerLight(20000);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  const auto& statistics = reference->GetStatistics();
  std::cout << "g " << g << ": " << statistics.beams << " beams; photons "
            << statistics.photonSeconds << " s, view " << statistics.viewSeconds << " s, volume "
            << statistics.volumeSeconds << " s\n";
  vtkImageData* image = reference->GetOutput();
  const caustics::Camera& view = reference->GetScene().View;
  const double pitch = 2.0 * 1.1 / size; // orthographic pixel, m

  // Flux leaving the plate's bottom: normal incidence, paths of 2, 4, 6, 8 events.
  const double r = reftest::FresnelLaws(0.0, 1.0, 1.5), t = 1.0 - r;
  const double area = 4.0 * PlateHalf * PlateHalf;
  const double plateFlux =
    Irradiance * area * t * t * (1 + r * r + std::pow(r, 4) + std::pow(r, 6));
  const double viewDirection[3] = { 0.0, -std::sin(Look), -std::cos(Look) };
  // Light travels (0, -1, 0) and leaves towards the camera along -view: cos = -sin(Look).
  const double cosTheta = -std::sin(Look);
  const double sinAlpha = std::cos(Look); // angle between the camera rays and the beam

  int rows = 0;
  double worstBeam = 0.0, worstAirlight = 0.0;
  for (int j = 0; j < size; ++j)
  {
    caustics::Vec3 origin, direction;
    view.PixelRay(size / 2, j, origin, direction);
    // Where this row's rays cross the beam's axis plane (z = 0).
    const double s = -origin[2] / direction[2];
    const double crossing[3] = { origin[0] + s * direction[0], origin[1] + s * direction[1], 0.0 };
    if (crossing[1] < 0.5 || crossing[1] > 2.6)
    {
      continue; // stay clear of the beam's ends (plate and floor)
    }
    ++rows;
    const double back[3] = { -viewDirection[0], -viewDirection[1], -viewDirection[2] };
    const double toCamera = ExitDistance(crossing, back);
    for (int c = 0; c < 3; ++c)
    {
      const double sigmaT = SigmaS[c] + SigmaA[c];
      const double flux = plateFlux * std::exp(-sigmaT * (PlateBottom - crossing[1]));
      const double expected =
        SigmaS[c] * Phase(cosTheta, g) * flux * std::exp(-sigmaT * toCamera) / sinAlpha;
      double sum = 0.0;
      for (int i = 0; i < size; ++i)
      {
        sum += reftest::At(image, "VolumeCausticRadiance", i, j, c) * pitch;
      }
      // 1% (the brief): the only approximations are the pixel sum of the beam's
      // kernel (beams spread over 9 pixels average it out) and float output.
      worstBeam = std::max(worstBeam, std::abs(sum / expected - 1.0));
      EXPECT_NEAR(sum / expected, 1.0, 0.01)
        << "g " << g << " row " << j << " height " << crossing[1] << " channel " << c;
      if (j % 16 == 0 && c == 0)
      {
        std::cout << "g " << g << ", beam at height " << crossing[1] << ": " << sum
                  << " W/(m sr) across the beam, closed form " << expected << "\n";
      }
    }

    // Airlight on rays 0.7 m to the side of the beam and its shadow.
    const int i = static_cast<int>(std::lround(size / 2 + 0.7 / pitch));
    view.PixelRay(i, j, origin, direction);
    // Entry into the box (the ray comes from outside) and exit: slab clipping.
    double t0 = 0.0, t1 = 1e300;
    for (int a = 0; a < 3; ++a)
    {
      const double ta = (Box[2 * a] - origin[a]) / direction[a];
      const double tb = (Box[2 * a + 1] - origin[a]) / direction[a];
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    ASSERT_LT(t0, t1);
    const double entryHeight = origin[1] + t0 * direction[1];
    // Along the ray, height drops by sin(Look) per metre: light path = (top - y) grows
    // by sin(Look) per metre, camera path by 1.
    for (int c = 0; c < 3; ++c)
    {
      const double sigmaT = SigmaS[c] + SigmaA[c];
      const double rate = sigmaT * (1.0 + std::sin(Look));
      const double expected = SigmaS[c] * Phase(cosTheta, g) * Irradiance *
        std::exp(-sigmaT * (PlateTop - entryHeight)) * (1.0 - std::exp(-rate * (t1 - t0))) / rate;
      const double value = reftest::At(image, "AirlightRadiance", i, j, c);
      // 1%: the jittered march's error on a smooth exponential is far below that.
      worstAirlight = std::max(worstAirlight, std::abs(value / expected - 1.0));
      EXPECT_NEAR(value / expected, 1.0, 0.01) << "airlight, g " << g << " row " << j;
      EXPECT_FLOAT_EQ(reftest::At(image, "VolumeRadiance", i, j, c),
        value + reftest::At(image, "VolumeCausticRadiance", i, j, c));
    }
  }
  EXPECT_GT(rows, 50);
  std::cout << "g " << g << ": worst relative error over " << rows << " rows and 3 channels: beam "
            << worstBeam << ", airlight " << worstAirlight << "\n";

  // Extinction on the way to surfaces. Direct light on the floor away from the
  // plate's shadow crossed the whole medium (3 m); the camera sees it through the
  // medium too; photons through the plate lost exp(-sigma_t 2.95) on the way down.
  int floorPixels = 0;
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      const double x[3] = { reftest::At(image, "Position", i, j, 0),
        reftest::At(image, "Position", i, j, 1), reftest::At(image, "Position", i, j, 2) };
      if (reftest::At(image, "ReceiverMask", i, j) == 0.0 ||
        (std::abs(x[0]) < 0.15 && std::abs(x[2]) < 0.15))
      {
        continue;
      }
      ++floorPixels;
      const double back[3] = { -viewDirection[0], -viewDirection[1], -viewDirection[2] };
      const double toCamera = ExitDistance(x, back);
      for (int c = 0; c < 3; ++c)
      {
        const double sigmaT = SigmaS[c] + SigmaA[c];
        // Float outputs: 1e-5 relative.
        EXPECT_NEAR(reftest::At(image, "DirectIrradiance", i, j, c) /
            (Irradiance * std::exp(-sigmaT * PlateTop)),
          1.0, 1e-5);
        EXPECT_NEAR(
          reftest::At(image, "Transmittance", i, j, c) / std::exp(-sigmaT * toCamera), 1.0, 1e-5);
      }
    }
  }
  EXPECT_GT(floorPixels, 1000);
  const auto& light = statistics.lights.at(0);
  int photons = 0;
  for (const auto& p : reference->GetPhotons())
  {
    if (p.events != 2)
    {
      continue;
    }
    ++photons;
    for (int c = 0; c < 3; ++c)
    {
      const double emitted = light.emitted[c] / light.photonsEmitted;
      const double expected =
        emitted * t * t * std::exp(-(SigmaS[c] + SigmaA[c]) * (PlateBottom - p.position[1]));
      EXPECT_NEAR(p.flux[c] / expected, 1.0, 1e-5);
    }
  }
  EXPECT_GT(photons, 10000);
}

INSTANTIATE_TEST_SUITE_P(Anisotropy, ReferenceMedium, ::testing::Values(-0.7, 0.0, 0.7));
