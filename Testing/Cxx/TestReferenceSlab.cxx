// The reference against a flat glass slab (2 m x 0.2 m x 2 m, n = 1.5, 1 m above the
// floor) lit at 40 degrees from the vertical:
// - every photon through the top and bottom faces leaves parallel to the light,
//   displaced sideways by Snell's law: t sin(i) (1 - cos(i) / sqrt(n^2 - sin^2(i)));
// - under the slab the caustic irradiance is E cos(i) T^2 (1 + R^2 + R^4 + R^6)
//   (Fresnel's laws; two to eight specular events), and the estimate converges to
//   it as the photon count grows.
#include "TestReferenceUtilities.h"

#include "vtkCubeSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using reftest::Pi;

namespace
{
const double N = 1.5;
const double Incidence = 40.0 * Pi / 180.0;
const double Irradiance = 2.0;                    // W/m^2 on a surface facing the light
const double Bottom = 1.0, Top = 1.2, Half = 1.0; // slab: |x|, |z| <= 1, 1 <= y <= 1.2

struct Slab
{
  vtkNew<vtkRenderer> renderer;
  Slab()
  {
    this->renderer->AddActor(reftest::Floor(5.0));
    vtkNew<vtkCubeSource> cube;
    cube->SetBounds(-Half, Half, Bottom, Top, -Half, Half);
    cube->Update();
    auto slab = reftest::MakeActor(cube->GetOutput(), "slab");
    vtkCausticsMaterial::MakeGlass(slab->GetProperty(), N);
    this->renderer->AddActor(slab);
    this->renderer->AddLight(
      reftest::Directional(std::sin(Incidence), -std::cos(Incidence), 0.0, Irradiance));
    // Low camera looking under the slab at the floor it lights.
    const double eye[3] = { 0.9, 0.9, 3.0 }, focal[3] = { 0.9, 0.0, 0.0 }, up[3] = { 0, 1, 0 };
    reftest::SetCamera(this->renderer, eye, focal, up, 45.0);
  }
};

/** Horizontal shift, inside the slab, between the entry and exit points. */
double InsideShift()
{
  const double sinT = std::sin(Incidence) / N;
  return (Top - Bottom) * sinT / std::sqrt(1.0 - sinT * sinT);
}

/**
 * Where the light reaching floor point x entered the top face (x coordinate), if it
 * came straight through: back along the light to the bottom face, then along the
 * refracted direction to the top.
 */
double EntryX(double x)
{
  return x - Bottom * std::tan(Incidence) - InsideShift();
}

/** Expected caustic irradiance under the slab, paths of 2 to 8 specular events. */
double ExpectedIrradiance()
{
  const double r = reftest::FresnelLaws(Incidence, 1.0, N);
  const double t = 1.0 - r;
  return Irradiance * std::cos(Incidence) * t * t * (1.0 + r * r + r * r * r * r + std::pow(r, 6));
}

/**
 * Floor pixels that receive every path (up to three extra round trips inside, each
 * shifting the exit by 2 x InsideShift) at least `margin` from the slab's edges.
 */
bool InUniformRegion(double x, double z, double margin)
{
  const double entry = EntryX(x);
  return entry - 3.0 * 2.0 * InsideShift() >= -Half + margin &&
    entry + InsideShift() <= Half - margin && std::abs(z) <= Half - margin;
}
}

TEST(ReferenceSlab, PhotonsAreDisplacedBySnellsLaw)
{
  Slab slab;
  auto reference = reftest::MakeReference(slab.renderer, 16, 16, 100000);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  const double light[3] = { std::sin(Incidence), -std::cos(Incidence), 0.0 };
  const double thickness = Top - Bottom;
  const double expected = thickness * std::sin(Incidence) *
    (1.0 - std::cos(Incidence) / std::sqrt(N * N - std::sin(Incidence) * std::sin(Incidence)));
  int checked = 0;
  double worstShift = 0.0, worstAngle = 0.0;
  for (const auto& p : reference->GetPhotons())
  {
    // Entered the top face, and (by Snell) leaves through the bottom face.
    const double entry = p.firstHit[0];
    if (p.events != 2 || std::abs(p.firstHit[1] - Top) > 1e-4 ||
      entry + InsideShift() > Half - 1e-3 || std::abs(p.firstHit[2]) > Half - 1e-3)
    {
      continue;
    }
    ++checked;
    // Parallel to the incident light...
    const double cross[3] = { p.direction[1] * light[2] - p.direction[2] * light[1],
      p.direction[2] * light[0] - p.direction[0] * light[2],
      p.direction[0] * light[1] - p.direction[1] * light[0] };
    worstAngle = std::max(
      worstAngle, std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]));
    // ... and displaced: distance between the incident line through the entry point
    // and the outgoing line through the deposit.
    double gap[3], along = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      gap[c] = p.position[c] - p.firstHit[c];
      along += gap[c] * light[c];
    }
    double shift2 = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      shift2 += std::pow(gap[c] - along * light[c], 2);
    }
    worstShift = std::max(worstShift, std::abs(std::sqrt(shift2) - expected));
  }
  std::cout << checked << " photons, Snell displacement " << expected << " m, worst error "
            << worstShift << " m, worst direction error " << worstAngle << " rad\n";
  EXPECT_GT(checked, 40000);
  // Records are floats: positions within a few metres carry ~5e-7 m of rounding,
  // directions ~1e-7.
  EXPECT_LT(worstShift, 1e-5);
  EXPECT_LT(worstAngle, 1e-6);
}

TEST(ReferenceSlab, IrradianceUnderTheSlabMatchesFresnel)
{
  Slab slab;
  auto reference = reftest::MakeReference(slab.renderer, 96, 96, 400000);
  reference->SetKernelRadius(0.05);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkImageData* image = reference->GetOutput();
  const double expected = ExpectedIrradiance();
  double sum = 0.0, worst = 0.0;
  int count = 0;
  for (int j = 0; j < 96; ++j)
  {
    for (int i = 0; i < 96; ++i)
    {
      const double x = reftest::At(image, "Position", i, j, 0);
      const double z = reftest::At(image, "Position", i, j, 2);
      if (reftest::At(image, "ReceiverMask", i, j) == 0.0 || !InUniformRegion(x, z, 0.06))
      {
        continue;
      }
      EXPECT_EQ(reftest::At(image, "DirectIrradiance", i, j, 0), 0.0) << "the slab's shadow";
      for (int c = 0; c < 3; ++c)
      {
        const double value = reftest::At(image, "CausticIrradiance", i, j, c);
        worst = std::max(worst, std::abs(value / expected - 1.0));
        sum += value;
        ++count;
      }
    }
  }
  ASSERT_GT(count, 300);
  const double mean = sum / count;
  std::cout << count / 3 << " pixels under the slab: mean " << mean << " W/m^2, expected "
            << expected << " (relative error " << mean / expected - 1.0 << "), worst pixel "
            << worst << "\n";
  // Mean: 0.2% (a flux error, e.g. a missing cosine or Fresnel factor, is > 1%).
  EXPECT_NEAR(mean / expected, 1.0, 0.002);
  // Each pixel: a kernel of radius 5 cm holds E cos(i) pi r^2 / flux-per-photon ~ 2000
  // photons; 4 Poisson deviations of the Epanechnikov estimate, 4 sqrt(4 / (3 m)), bound
  // the (stratified, smaller) noise: 10%.
  EXPECT_LT(worst, 0.10);
}

TEST(ReferenceSlab, EstimateConvergesWithPhotonCount)
{
  Slab slab;
  const double expected = ExpectedIrradiance();
  std::vector<double> errors;
  for (vtkIdType photons : { 10000, 40000, 160000, 640000 })
  {
    auto reference = reftest::MakeReference(slab.renderer, 64, 64, photons);
    reference->SetKernelRadius(0.05);
    ASSERT_TRUE(reference->Update()) << reference->GetLastError();
    vtkImageData* image = reference->GetOutput();
    double sum2 = 0.0;
    int count = 0;
    for (int j = 0; j < 64; ++j)
    {
      for (int i = 0; i < 64; ++i)
      {
        const double x = reftest::At(image, "Position", i, j, 0);
        const double z = reftest::At(image, "Position", i, j, 2);
        if (reftest::At(image, "ReceiverMask", i, j) != 0.0 && InUniformRegion(x, z, 0.06))
        {
          sum2 += std::pow(reftest::At(image, "CausticIrradiance", i, j, 1) / expected - 1.0, 2);
          ++count;
        }
      }
    }
    ASSERT_GT(count, 100);
    errors.push_back(std::sqrt(sum2 / count));
    std::cout << photons << " photons: RMS relative error " << errors.back() << "\n";
  }
  // Four times the photons: Monte Carlo noise halves (jittered strata do better). 0.7
  // leaves room for the roulette noise of the faint internal reflections.
  for (std::size_t k = 1; k < errors.size(); ++k)
  {
    EXPECT_LT(errors[k], 0.7 * errors[k - 1]) << "from step " << k - 1 << " to " << k;
  }
}

TEST(ReferenceSlab, UndersideOfTheFloorStaysDark)
{
  // Seen from below, the floor's underside is a receiver too; photons that arrived
  // from above (their normal faces up) must not light it, nor must the sun.
  Slab slab;
  const double eye[3] = { 0.9, -3.0, 0.1 }, focal[3] = { 0.9, 0.0, 0.0 }, up[3] = { 0, 0, 1 };
  reftest::SetCamera(slab.renderer, eye, focal, up, 60.0);
  auto reference = reftest::MakeReference(slab.renderer, 48, 48, 100000);
  reference->SetKernelRadius(0.05);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkImageData* image = reference->GetOutput();
  int seen = 0;
  for (int j = 0; j < 48; ++j)
  {
    for (int i = 0; i < 48; ++i)
    {
      if (reftest::At(image, "ReceiverMask", i, j) == 0.0)
      {
        continue;
      }
      ++seen;
      EXPECT_LT(reftest::At(image, "Normal", i, j, 1), 0.0) << "the normal faces the camera";
      EXPECT_EQ(reftest::At(image, "CausticIrradiance", i, j, 0), 0.0);
      EXPECT_EQ(reftest::At(image, "DirectIrradiance", i, j, 0), 0.0);
    }
  }
  EXPECT_GT(seen, 1000);
  EXPECT_GT(reference->GetNumberOfPhotonsDeposited(), 50000) << "photons are there, above";
}

TEST(ReferenceSlab, EstimateHoldsUpToTheReceiversEnd)
{
  // The slab under a vertical sun over a floor 1 m wide, all of it under the slab: the
  // floor's caustic irradiance is E T^2 (1 + R^2 + R^4 + R^6) everywhere, up to its
  // edges. A gather kernel across an edge holds photons from its covered part only; the
  // estimate is divided by that share (docs/reference.md), else the band within one
  // radius of the edge read about 0.7 of the value and the corners less.
  vtkNew<vtkRenderer> renderer;
  const double floorHalf = 0.5;
  renderer->AddActor(reftest::Floor(floorHalf));
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-Half, Half, Bottom, Top, -Half, Half);
  cube->Update();
  auto slab = reftest::MakeActor(cube->GetOutput(), "slab");
  vtkCausticsMaterial::MakeGlass(slab->GetProperty(), N);
  renderer->AddActor(slab);
  renderer->AddLight(reftest::Directional(0.0, -1.0, 0.0, Irradiance));
  // Below the slab, beside it, looking down at the whole floor.
  const double eye[3] = { 0.3, 0.8, 1.5 }, focal[3] = { 0.0, 0.0, 0.0 }, up[3] = { 0, 1, 0 };
  reftest::SetCamera(renderer, eye, focal, up, 50.0);
  auto reference = reftest::MakeReference(renderer, 128, 128, 400000);
  const double radius = 0.05;
  reference->SetKernelRadius(radius);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkImageData* image = reference->GetOutput();
  const double r = reftest::FresnelLaws(0.0, 1.0, N), t = 1.0 - r;
  const double expected = Irradiance * t * t * (1.0 + r * r + std::pow(r, 4) + std::pow(r, 6));
  // By the distance to the nearest edge: within r/2 of it, between r/2 and r, beyond.
  double sum[3] = { 0.0, 0.0, 0.0 };
  int count[3] = { 0, 0, 0 };
  int corners = 0;
  double cornerSum = 0.0;
  for (int j = 0; j < 128; ++j)
  {
    for (int i = 0; i < 128; ++i)
    {
      if (reftest::At(image, "ReceiverMask", i, j) == 0.0)
      {
        continue;
      }
      const double x = std::abs(reftest::At(image, "Position", i, j, 0));
      const double z = std::abs(reftest::At(image, "Position", i, j, 2));
      const double edge = floorHalf - std::max(x, z);
      const int band = edge < 0.5 * radius ? 0 : (edge < radius ? 1 : 2);
      const double value = reftest::At(image, "CausticIrradiance", i, j, 1);
      sum[band] += value;
      ++count[band];
      if (floorHalf - std::min(x, z) < 0.5 * radius)
      {
        cornerSum += value;
        ++corners;
      }
    }
  }
  ASSERT_GT(count[0], 200);
  ASSERT_GT(count[2], 2000);
  ASSERT_GT(corners, 4);
  const double edgeBand = sum[0] / count[0] / expected, nearBand = sum[1] / count[1] / expected,
               inside = sum[2] / count[2] / expected, corner = cornerSum / corners / expected;
  std::cout << "of the exact irradiance: within r/2 of an edge " << edgeBand << " (" << count[0]
            << " pixels), r/2 to r " << nearBand << ", inside " << inside << ", corners "
            << corner << " (" << corners << ")\n";
  EXPECT_NEAR(inside, 1.0, 0.01);
  EXPECT_NEAR(nearBand, 1.0, 0.02);
  EXPECT_NEAR(edgeBand, 1.0, 0.03);
  EXPECT_NEAR(corner, 1.0, 0.1);
}
