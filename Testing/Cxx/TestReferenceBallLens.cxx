// The reference against the optics of a glass sphere (the built-in "ball-lens"
// scene: radius 1 m centred 3 m above a square floor, light straight down, 1 W/m^2):
// - the paraxial focus lies at n R / (2 (n - 1)) from the centre, and every photon
//   crosses the axis where an exact analytic trace through the sphere says;
// - the flux reaching the floor through exactly two refractions equals the incident
//   irradiance times the two-interface Fresnel transmittance integrated over the
//   aperture (computed here by quadrature of the exact sphere);
// - with IOR 1 the sphere vanishes: direct + caustic irradiance equals the direct
//   irradiance of the scene without it, for directional, point and spot lights.
#include "TestReferenceUtilities.h"

#include "vtkActorCollection.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkInformation.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using reftest::Pi;

namespace
{
const double CentreHeight = 3.0; // the built-in ball's centre, radius 1

/** Half the side of the (square, centred) floor, read from the scene. */
double FloorHalf(const caustics::SceneData& scene)
{
  double half = 0.0;
  for (const auto& mesh : scene.Meshes)
  {
    if (mesh.name == "floor")
    {
      for (std::size_t k = 0; k < mesh.positions.size(); k += 3)
      {
        half = std::max(half,
          static_cast<double>(
            std::max(std::abs(mesh.positions[k]), std::abs(mesh.positions[k + 2]))));
      }
    }
  }
  return half;
}

/** A ray leaving the unit sphere after two refractions, in its meridional plane. */
struct SphereExit
{
  double rho, y;        ///< exit point: distance from the axis, height
  double dRho, dy;      ///< exit direction
  double transmittance; ///< T1 T2 (Fresnel's laws)
};

/** Exact trace of the vertical ray at distance b from the axis through the sphere. */
SphereExit TraceSphere(double b, double n)
{
  const double cosI = std::sqrt(1.0 - b * b);
  // Entry: normal (b, cosI), ray (0, -1); Snell with eta = 1 / n.
  const double eta = 1.0 / n;
  const double cosT = std::sqrt(1.0 - eta * eta * b * b);
  const double k = eta * cosI - cosT;
  const double d1r = k * b, d1y = -eta + k * cosI;
  // Chord to the second intersection with the unit sphere.
  const double t = -2.0 * (b * d1r + cosI * d1y);
  const double pr = b + t * d1r, py = cosI + t * d1y; // relative to the centre
  // Exit: normal facing the ray is -(pr, py); the internal angle equals the
  // refracted one (cosT), and Snell gives back cos = cosI outside.
  const double cosI2 = d1r * pr + d1y * py;
  const double k2 = n * cosI2 - std::sqrt(std::max(0.0, 1.0 - n * n * (1.0 - cosI2 * cosI2)));
  SphereExit exit;
  exit.rho = pr;
  exit.y = CentreHeight + py;
  exit.dRho = n * d1r - k2 * pr;
  exit.dy = n * d1y - k2 * py;
  const double thetaI = std::asin(b), thetaT = std::asin(eta * b);
  exit.transmittance =
    (1.0 - reftest::FresnelLaws(thetaI, 1.0, n)) * (1.0 - reftest::FresnelLaws(thetaT, n, 1.0));
  return exit;
}

/** Distance from the centre to where the exit ray crosses the axis. */
double AxisCrossing(const SphereExit& exit)
{
  const double s = -exit.rho / exit.dRho;
  return CentreHeight - (exit.y + s * exit.dy);
}

vtkActor* FindActor(vtkRenderer* renderer, const std::string& name)
{
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    if (vtkCausticsMaterial::GetName(actor) == name)
    {
      return actor;
    }
  }
  return nullptr;
}

struct BallLens
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  BallLens(double tessellation, double ior)
  {
    this->scene->SetTessellation(tessellation);
    this->scene->SetRefractiveIndex(ior);
    EXPECT_TRUE(this->scene->Populate(this->renderer));
  }
};
}

TEST(ReferenceBallLens, ParaxialFocusAndSphericalAberration)
{
  const double n = 1.5;
  BallLens lens(4.0, n); // 512 x 256 facets
  auto reference = reftest::MakeReference(lens.renderer, 32, 32, 250000);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();

  // Axis crossing of every photon refracted exactly twice, against its impact
  // parameter b (first hit's distance from the axis). Rays from a directional light
  // along the axis are meridional: they meet the axis.
  std::vector<double> bs, crossings;
  double worst = 0.0, worstB = 0.0;
  for (const auto& p : reference->GetPhotons())
  {
    if (p.events != 2)
    {
      continue;
    }
    const double b = std::hypot(p.firstHit[0], p.firstHit[2]);
    const double dxz = std::hypot(p.direction[0], p.direction[2]);
    if (b > 0.9 || dxz < 1e-9)
    {
      continue;
    }
    const double s =
      (p.position[0] * p.direction[0] + p.position[2] * p.direction[2]) / (dxz * dxz);
    const double miss =
      std::hypot(p.position[0] - s * p.direction[0], p.position[2] - s * p.direction[2]);
    EXPECT_LT(miss, 1e-3) << "a meridional ray misses the axis";
    const double crossing = CentreHeight - (p.position[1] - s * p.direction[1]);
    const double error = std::abs(crossing - AxisCrossing(TraceSphere(b, n)));
    if (error > worst)
    {
      worst = error;
      worstB = b;
    }
    if (b < 0.35)
    {
      bs.push_back(b);
      crossings.push_back(crossing);
    }
  }
  ASSERT_GT(bs.size(), 10000u);

  // Paraxial focus: least-squares fit crossing = f0 + c1 b^2 + c2 b^4 (spherical
  // aberration is even in b), normal equations in double.
  double m[3][4] = { { 0 } };
  for (std::size_t k = 0; k < bs.size(); ++k)
  {
    const double b2 = bs[k] * bs[k], basis[3] = { 1.0, b2, b2 * b2 };
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        m[r][c] += basis[r] * basis[c];
      }
      m[r][3] += basis[r] * crossings[k];
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    for (int r = c + 1; r < 3; ++r)
    {
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 4; ++k)
      {
        m[r][k] -= f * m[c][k];
      }
    }
  }
  double coef[3];
  for (int r = 2; r >= 0; --r)
  {
    coef[r] = m[r][3];
    for (int c = r + 1; c < 3; ++c)
    {
      coef[r] -= m[r][c] * coef[c];
    }
    coef[r] /= m[r][r];
  }
  const double paraxial = n * 1.0 / (2.0 * (n - 1.0));
  // Tolerance from the tessellation: facets of at most ~0.0174 rad across (the
  // diagonal of a 2 pi / 512 x pi / 255 quad) lie up to 1 - cos(0.0087) = 3.8e-5 m
  // inside the sphere; interpolated normals are exact (radial) on a sphere, so the
  // two refraction points alone move, each shifting the focus by about
  // n / (2 (n - 1)) x 3.8e-5 = 1.1e-4 m. 5e-4 m bounds both with margin.
  EXPECT_NEAR(coef[0], paraxial, 5e-4)
    << "paraxial focus " << coef[0] << " m from the centre, expected " << paraxial;
  std::cout << "paraxial focus " << coef[0] << " m from the centre (expected " << paraxial
            << ", error " << coef[0] - paraxial << " m); worst photon crossing error " << worst
            << " m at b = " << worstB << "\n";
  // Every photon up to b = 0.9 crosses where the exact sphere says. The crossing's
  // sensitivity to the facet sag grows with b (to ~30x at b = 0.9, from the
  // derivative of the analytic crossing): 30 x 1.1e-4 m.
  EXPECT_LT(worst, 3.5e-3);
}

TEST(ReferenceBallLens, TwoRefractionFluxMatchesFresnelIntegral)
{
  const double n = 1.5;
  BallLens lens(4.0, n);
  auto reference = reftest::MakeReference(lens.renderer, 32, 32, 250000);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  const auto& statistics = reference->GetStatistics();
  ASSERT_EQ(statistics.lights.size(), 1u);
  ASSERT_GE(statistics.depositedByEvents.size(), 3u);

  // Exact: E x integral over the aperture of T1 T2, for rays whose exit direction
  // reaches the floor. Midpoint rule, 4000 x 720 nodes: the integrand is
  // smooth but for sqrt-like behaviour at the rim (error ~ h^1.5 = 4e-6) and the
  // floor's edge (a discontinuity in b at fixed phi, error ~ 1 / 4000 of a thin band).
  const int nb = 4000, nphi = 720;
  const double floorHalf = FloorHalf(reference->GetScene());
  ASSERT_GT(floorHalf, 1.0);
  double expected = 0.0;
  for (int i = 0; i < nb; ++i)
  {
    const double b = (i + 0.5) / nb;
    const SphereExit exit = TraceSphere(b, n);
    if (!(exit.dy < 0.0))
    {
      continue;
    }
    const double rhoFloor = exit.rho + (-exit.y / exit.dy) * exit.dRho;
    for (int k = 0; k < nphi; ++k)
    {
      const double phi = (k + 0.5) * 2.0 * Pi / nphi;
      const double x = rhoFloor * std::cos(phi), z = rhoFloor * std::sin(phi);
      if (std::abs(x) <= floorHalf && std::abs(z) <= floorHalf)
      {
        expected += exit.transmittance * b * (1.0 / nb) * (2.0 * Pi / nphi);
      }
    }
  }
  const double irradiance = 1.0;
  expected *= irradiance;
  const double measured = statistics.depositedByEvents[2][0];
  std::cout << "two-refraction flux on the floor " << measured << " W, exact " << expected
            << " W, relative error " << measured / expected - 1.0 << "\n";
  // The brief's tolerance; the facets' aperture deficit is 7e-5 and the stratified
  // emission's error about 1e-4, so this has ample margin.
  EXPECT_NEAR(measured / expected, 1.0, 0.005);
  // The channels agree (grey light, grey glass).
  EXPECT_DOUBLE_EQ(statistics.depositedByEvents[2][1], measured);

  // Bookkeeping: emitted = E x sampled area, which covers the sphere's aperture,
  // and the flux balance closes.
  const auto& light = statistics.lights[0];
  EXPECT_NEAR(light.emitted[0], irradiance * light.emissionMeasure, 1e-9 * light.emitted[0]);
  EXPECT_GE(light.emissionMeasure, Pi);
  const double balance = light.direct[0] + light.deposited[0] + light.escaped[0] +
    light.absorbed[0] + light.bounceLimit[0] + light.roulette[0];
  EXPECT_NEAR(balance, light.emitted[0], 1e-9 * light.emitted[0]);
}

namespace
{
/**
 * Renders the ball-lens scene (IOR 1) lit by `light` (nullptr: its own directional
 * light) with the ball and, with the ball's role set to none, without it, and
 * compares direct + caustic irradiance with the direct irradiance alone.
 */
void CheckVanishingSphere(vtkLight* light, const char* label, int minimumExterior)
{
  BallLens lens(1.0, 1.0);
  if (light)
  {
    lens.renderer->RemoveAllLights();
    lens.renderer->AddLight(light);
  }
  auto with = reftest::MakeReference(lens.renderer, 96, 96, 400000);
  ASSERT_TRUE(with->Update()) << with->GetLastError();
  vtkActor* ball = FindActor(lens.renderer, "glass ball");
  ASSERT_NE(ball, nullptr);
  vtkCausticsMaterial::SetRole(ball, vtkCausticsMaterial::ROLE_NONE);
  auto without = reftest::MakeReference(lens.renderer, 96, 96, 1);
  ASSERT_TRUE(without->Update()) << without->GetLastError();
  vtkImageData* a = with->GetOutput();
  vtkImageData* b = without->GetOutput();
  const caustics::Light& source = with->GetScene().Lights.at(0);

  // Largest photon flux: with IOR 1 nothing splits, photons keep what they left with.
  double photonFlux = 0.0;
  for (const auto& p : with->GetPhotons())
  {
    photonFlux = std::max(photonFlux, static_cast<double>(p.flux[1]));
  }
  ASSERT_GT(photonFlux, 0.0);

  const double floorHalf = FloorHalf(with->GetScene());
  double sumWith = 0.0, sumWithout = 0.0, worst = 0.0;
  int interior = 0, exterior = 0;
  for (int j = 0; j < 96; ++j)
  {
    for (int i = 0; i < 96; ++i)
    {
      if (reftest::At(a, "ReceiverMask", i, j) == 0.0 ||
        reftest::At(b, "ReceiverMask", i, j) == 0.0)
      {
        continue;
      }
      const double area = reftest::At(a, "PixelArea", i, j);
      const double total =
        reftest::At(a, "DirectIrradiance", i, j, 1) + reftest::At(a, "CausticIrradiance", i, j, 1);
      const double truth = reftest::At(b, "DirectIrradiance", i, j, 1);
      EXPECT_EQ(reftest::At(b, "CausticIrradiance", i, j, 1), 0.0);
      // Distance from the ball's centre to the line from the floor point towards the
      // light: < 1 in the ball's shadow. Moving the floor point by r moves that line
      // by less than r at the ball, so a margin of r + 1 cm keeps the kernel (radius
      // r = 2 sqrt(area)) off the shadow's edge.
      const double x[3] = { reftest::At(a, "Position", i, j, 0),
        reftest::At(a, "Position", i, j, 1), reftest::At(a, "Position", i, j, 2) };
      double u[3];
      if (source.type == caustics::Light::Type::Directional)
      {
        for (int c = 0; c < 3; ++c)
        {
          u[c] = -source.direction[c];
        }
      }
      else
      {
        const double length = std::sqrt(std::pow(source.position[0] - x[0], 2) +
          std::pow(source.position[1] - x[1], 2) + std::pow(source.position[2] - x[2], 2));
        for (int c = 0; c < 3; ++c)
        {
          u[c] = (source.position[c] - x[c]) / length;
        }
      }
      const double toCentre[3] = { -x[0], CentreHeight - x[1], -x[2] };
      const double along = toCentre[0] * u[0] + toCentre[1] * u[1] + toCentre[2] * u[2];
      const double distance = std::sqrt(std::max(0.0,
        toCentre[0] * toCentre[0] + toCentre[1] * toCentre[1] + toCentre[2] * toCentre[2] -
          along * along));
      const double r = 2.0 * std::sqrt(area);
      // Kernels reaching past the floor's edge lose the part outside it.
      if (std::max(std::abs(x[0]), std::abs(x[2])) < floorHalf - r)
      {
        sumWith += total * area;
        sumWithout += truth * area;
      }
      if (distance < 1.0 - r - 0.01 && truth > 0.05)
      {
        ++interior;
        EXPECT_EQ(reftest::At(a, "DirectIrradiance", i, j, 1), 0.0) << "in the shadow";
        // Poisson's relative deviation of the Epanechnikov estimate with m photons in
        // its disk is sqrt(4 / (3 m)); stratified sampling does better, so 4 of
        // those bound the noise. m >= truth x pi r^2 / (largest photon flux).
        const double photons = truth * Pi * r * r / photonFlux;
        const double deviation = std::abs(total / truth - 1.0);
        worst = std::max(worst, deviation);
        EXPECT_LT(deviation, 4.0 * std::sqrt(4.0 / (3.0 * photons)))
          << label << ": pixel " << i << ", " << j << " total " << total << " truth " << truth;
      }
      else if (distance > 1.0 + r + 0.01)
      {
        ++exterior;
        EXPECT_EQ(reftest::At(a, "CausticIrradiance", i, j, 1), 0.0);
        EXPECT_NEAR(total, truth, 1e-6 * truth);
      }
    }
  }
  EXPECT_GT(interior, 50) << label;
  EXPECT_GE(exterior, minimumExterior) << label;
  std::cout << label << ": " << interior << " shadow pixels, worst relative deviation " << worst
            << "; flux over the floor " << sumWith << " W with the sphere, " << sumWithout
            << " W without\n";
  // Blurring the shadow's edge with a normalized kernel moves flux but keeps it; the
  // noise averages out over thousands of pixels: 0.2%. (Pixels within a kernel of
  // the floor's outer edge are left out: the kernel's part beyond it is lost.)
  EXPECT_NEAR(sumWith / sumWithout, 1.0, 0.002) << label;
}

vtkSmartPointer<vtkLight> Positional(
  double x, double y, double z, double intensity, double outer, double inner)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetPosition(x, y, z);
  light->SetFocalPoint(x, 0, z);
  light->SetConeAngle(outer);
  light->SetIntensity(intensity);
  if (inner >= 0.0)
  {
    vtkNew<vtkInformation> info;
    info->Set(vtkCausticsSceneExtractor::INNER_CONE_ANGLE(), inner);
    light->SetInformation(info);
  }
  return light;
}
}

TEST(ReferenceBallLens, VanishingSphereConservesEnergyDirectional)
{
  CheckVanishingSphere(nullptr, "directional", 1000);
}

TEST(ReferenceBallLens, VanishingSphereConservesEnergyPointAndSpot)
{
  // Point light above the ball, off axis: photons over the cap subtending the ball.
  CheckVanishingSphere(Positional(0.3, 6.0, 0.2, 36.0, 180.0, -1.0), "point", 1000);
  // Point light inside the ball: photons over the whole sphere, one event each.
  CheckVanishingSphere(Positional(0.1, 3.2, -0.1, 9.0, 180.0, -1.0), "point inside", 0);
  // Spot whose falloff varies across the ball (inner 8, outer 30 degrees; the ball
  // subtends 14.5): photons over the cap.
  CheckVanishingSphere(Positional(0.0, 7.0, 0.0, 49.0, 30.0, 8.0), "spot, cap", 1000);
  // Spot narrower than the cap (25 degrees against 42): photons over the spot cone,
  // which the ball's shadow covers entirely.
  CheckVanishingSphere(Positional(0.0, 4.5, 0.0, 20.0, 25.0, 10.0), "spot, cone", 0);
}
