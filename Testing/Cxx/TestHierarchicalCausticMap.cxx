// Hierarchical caustic maps (001_7c07a484f7a872bb.txt) on the built-in scenes:
// - the photon buffer lands refracted photons where an exact trace through the
//   sphere says, and accounts for every watt it is given;
// - the traversal processes few photons beyond the valid ones and never changes
//   the picture (flat and hierarchical gathers agree), clustering keeps the flux;
// - the multi-resolution map keeps each photon's flux, coarse splats are counted,
//   and its result does not depend on the map's resolution (filtered to the image);
// - the final render adds the lights, and a glass ball of IOR 1 passes the light
//   unchanged;
// - counters, parameters and graphics resources behave.
#include "TestHierarchicalCausticMapUtilities.h"

#include "vtkCausticsCausticMap.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsPhotonBuffer.h"
#include "vtkCausticsPhotonBufferHierarchy.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkProperty.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

using hcmtest::Array;
using hcmtest::Frame;

namespace
{
const double BallCentre = 3.0; // the built-in ball lens: radius 1 m centred 3 m above the floor

/** Fresnel's laws for unpolarized light (independent of the module's optics). */
double Reflectance(double thetaI, double etaI, double etaT)
{
  if (thetaI < 1e-9)
  {
    const double r = (etaI - etaT) / (etaI + etaT);
    return r * r;
  }
  const double sinT = etaI / etaT * std::sin(thetaI);
  if (sinT >= 1.0)
  {
    return 1.0;
  }
  const double thetaT = std::asin(sinT);
  const double s = std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT);
  const double p = std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT);
  return 0.5 * (s * s + p * p);
}

/**
 * Exact trace of the vertical ray at distance b from the axis through the unit
 * sphere of index n, in its meridional plane: where it lands on the floor (distance
 * from the axis) and its two-interface transmittance.
 */
void TraceSphere(double b, double n, double& landing, double& transmittance)
{
  const double cosI = std::sqrt(1.0 - b * b);
  const double eta = 1.0 / n;
  const double cosT = std::sqrt(1.0 - eta * eta * b * b);
  const double k = eta * cosI - cosT;
  const double d1r = k * b, d1y = -eta + k * cosI; // inside, normal (b, cosI)
  const double t = -2.0 * (b * d1r + cosI * d1y);
  const double pr = b + t * d1r, py = cosI + t * d1y; // exit, relative to the centre
  const double cosI2 = d1r * pr + d1y * py;
  const double k2 = n * cosI2 - std::sqrt(std::max(0.0, 1.0 - n * n * (1.0 - cosI2 * cosI2)));
  const double dr = n * d1r - k2 * pr, dy = n * d1y - k2 * py;
  const double s = -(BallCentre + py) / dy;
  landing = pr + s * dr;
  const double thetaI = std::asin(b), thetaT = std::asin(eta * b);
  transmittance = (1.0 - Reflectance(thetaI, 1.0, n)) * (1.0 - Reflectance(thetaT, n, 1.0));
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

vtkLight* FirstLight(vtkRenderer* renderer)
{
  renderer->GetLights()->InitTraversal();
  return renderer->GetLights()->GetNextItem();
}
}

namespace
{
/**
 * Sum of the Epanechnikov kernel of radius r (pixels) over the pixel centres of a
 * unit lattice, centred at (ox, oy) in its pixel: 1 where the midpoint rule is exact.
 */
double LatticeSum(double r, double ox, double oy)
{
  double sum = 0.0;
  for (int y = -20; y <= 20; ++y)
  {
    for (int x = -20; x <= 20; ++x)
    {
      const double d2 = (x - ox) * (x - ox) + (y - oy) * (y - oy);
      sum += d2 < r * r ? 2.0 / (M_PI * r * r) * (1.0 - d2 / (r * r)) : 0.0;
    }
  }
  return sum;
}
}

TEST(Kernels, WhyTheyAreNormalizedAndHowWideTheyAre)
{
  // 1. One splat sampled at pixel centres: the midpoint rule's error against the
  //    kernel's integral (1), over sub-pixel positions of its centre. Above 4 %
  //    at the 1.5-pixel minimum radius: the vertex shader normalizes kernels
  //    narrower than 4 pixels over the centres they cover.
  double worst[3] = { 0, 0, 0 };
  const double radii[3] = { 1.5, 2.0, 4.0 };
  for (int k = 0; k < 3; ++k)
  {
    for (double ox = 0.0; ox <= 0.5; ox += 0.05)
    {
      for (double oy = 0.0; oy <= 0.5; oy += 0.05)
      {
        worst[k] = std::max(worst[k], std::abs(LatticeSum(radii[k], ox, oy) - 1.0));
      }
    }
    std::cout << "kernel of " << radii[k] << " px: midpoint rule off by up to "
              << 100.0 * worst[k] << " %\n";
  }
  EXPECT_GT(worst[0], 0.04);
  EXPECT_LT(worst[2], 0.011);
  // 2. Many splats of a regular photon grid (spacing 1), radius R: the ripple of
  //    their sum, peak to peak over the mean, is what SplatScale trades against
  //    blur; the default 2 keeps it under 10 %, 1.5 does not.
  const double scales[] = { 1.0, 1.5, 2.0, 2.5, 3.0 };
  double ripple[5];
  for (int k = 0; k < 5; ++k)
  {
    double low = 1e30, high = 0.0;
    for (double px = 0.0; px <= 1.0; px += 0.1)
    {
      for (double py = 0.0; py <= 1.0; py += 0.1)
      {
        const double value = LatticeSum(scales[k], px, py);
        low = std::min(low, value);
        high = std::max(high, value);
      }
    }
    ripple[k] = high - low; // the mean is 1
    std::cout << "SplatScale " << scales[k] << ": ripple " << 100.0 * ripple[k] << " %\n";
  }
  EXPECT_GT(ripple[1], 0.10);
  EXPECT_LT(ripple[2], 0.10);
}

TEST(PhotonBuffer, LandsWhereTheSphereRefracts)
{
  Frame f("ball-lens", 512);
  f.Render();
  ASSERT_TRUE(f.Pass->GetLightTraced(0));
  vtkNew<vtkImageData> photons;
  ASSERT_TRUE(f.Pass->ReadPhotonBuffer(0, photons));
  auto entry = f.Buffer("LightPosition:0");
  ASSERT_NE(entry, nullptr);
  vtkDataArray* hit = Array(photons, "HitPosition");
  vtkDataArray* flux = Array(photons, "HitFlux");
  vtkDataArray* first = Array(entry);
  const int n = 512;
  // Rows 0..n-1: photons refracted at their first hit (the emitter's first branch).
  std::vector<double> errors;
  double transmitted = 0.0, expected = 0.0, incident = 0.0;
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(n) * n; ++i)
  {
    const double x = first->GetComponent(i, 0), z = first->GetComponent(i, 2);
    const double b = std::hypot(x, z);
    if (first->GetComponent(i, 3) < 0.0 || first->GetComponent(i, 1) < BallCentre || b >= 1.0)
    {
      continue; // not the ball's upper half, seen from the light
    }
    double landing, transmittance;
    TraceSphere(b, 1.5, landing, transmittance);
    // The light's texel flux: 1 W/m^2 x texel area, the same for every texel.
    const double texelFlux = flux->GetComponent(i, 3) * 1.0;
    incident += texelFlux;
    expected += texelFlux * transmittance;
    if (hit->GetComponent(i, 3) > 0.0)
    {
      transmitted += flux->GetComponent(i, 0);
      if (b < 0.9)
      {
        const double signedLanding =
          (hit->GetComponent(i, 0) * x + hit->GetComponent(i, 2) * z) / b;
        errors.push_back(std::abs(signedLanding - landing));
      }
    }
  }
  ASSERT_GT(errors.size(), 50000u);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  const double p99 = errors[errors.size() * 99 / 100];
  std::cout << "landing error: median " << median << " m, 99th percentile " << p99 << " m\n";
  // The exit normal is interpolated between back-layer texels 2 x 1.73 m / 512 =
  // 6.8 mm apart (the light buffers frame the ball's bounding box); an error of a
  // tenth of that spacing in the exit point tilts the radial normal by 0.7 mrad,
  // and 1.5 to 3 m of flight turn it into ~2 mm on the floor: 2 mm for the median,
  // 1 cm for the tail at b < 0.9 where the landing moves fastest with b.
  EXPECT_LT(median, 2e-3);
  EXPECT_LT(p99, 1e-2);
  // Flux landed from the refracted branch = incident x T1 T2, photon by photon;
  // the photons lost inside (grazing entries) and the rounding of the texel
  // coverage at the rim weigh less than 0.5 % (T is small where they are).
  EXPECT_NEAR(transmitted / expected, 1.0, 5e-3);
  EXPECT_GT(expected / incident, 0.85);
}

TEST(PhotonBuffer, AccountsForEveryWatt)
{
  Frame f("ball-lens", 256);
  // A tinted glass (Beer-Lambert, 1/m) so that absorption is part of the balance.
  vtkActor* ball = FindActor(f.Renderer, "glass ball");
  ASSERT_NE(ball, nullptr);
  const double attenuation[3] = { 0.1, 0.2, 0.4 };
  vtkCausticsMaterial::SetAttenuation(ball->GetProperty(), attenuation);
  f.Render();
  vtkCausticsHierarchicalCausticMapPass::Counters c;
  ASSERT_TRUE(f.Pass->GetCounters(0, c));
  EXPECT_GT(c.FluxAbsorbed, 0.0);
  EXPECT_GT(c.FluxInternalReflection, 0.0);
  const double balance = c.FluxHits + c.FluxLostInside + c.FluxEscaped + c.FluxStored +
    c.FluxInternalReflection + c.FluxAbsorbed;
  // Fixed-point sums: each term of each photon is rounded to 2^-20 of the largest
  // texel flux; even if every rounding went one way, six terms of photons that
  // carry no less than 1 % of that bound err by 6 x 0.5 / 2^20 / 0.01 = 2.9e-4 at
  // worst; 1e-4 relative holds for the ball lens, whose photons carry 4 to 96 %.
  EXPECT_NEAR(balance / c.FluxIn, 1.0, 1e-4);
  EXPECT_EQ(c.Photons, c.Hits + c.LostInside + c.Escaped + c.Stored);
  // The emitter's photons carry the flux that reached the ball (pi R^2 x 1 W/m^2
  // per channel, three channels): within the texel coverage of the disk's rim.
  EXPECT_NEAR(c.FluxIn / (3.0 * M_PI), 1.0, 5e-3);
  // The technique-independent reader (vtkCausticsRenderPass) gives the same counts:
  // one light here.
  caustics::PhotonStatistics photons;
  ASSERT_TRUE(f.Pass->GetLastFramePhotonStatistics(photons));
  EXPECT_EQ(photons.Photons, c.Photons);
  EXPECT_EQ(photons.FluxIn, c.FluxIn);
  EXPECT_EQ(photons.FluxLostInside, c.FluxLostInside);
  EXPECT_EQ(photons.FluxInternalReflection, c.FluxInternalReflection);
  EXPECT_LT(photons.LostShareBound(), 0.01);
}

TEST(Hierarchy, ProcessesFewPhotonsBeyondTheValidOnes)
{
  Frame f("ball-lens", 1024);
  f.Pass->SetClusterMode(vtkCausticsHierarchicalCausticMapPass::CLUSTER_NONE);
  f.Render();
  vtkCausticsHierarchicalCausticMapPass::Counters c;
  ASSERT_TRUE(f.Pass->GetCounters(0, c));
  // 1024 wide from a 16-node start: levels 6 .. 0.
  EXPECT_EQ(c.StartLevel, 6);
  EXPECT_EQ(c.Processed[6], 16 * 32);
  // The gather meets exactly the photons the photon buffer landed.
  EXPECT_EQ(c.Valid, c.Hits);
  EXPECT_GT(c.Valid, 300000);
  // Every valid photon is splatted once (no clustering, coarse splats kept).
  EXPECT_EQ(c.Splats[0] + c.Splats[1] + c.Splats[2] + c.Splats[3], c.Valid);
  // The paper's claim, measured: all levels together process fewer than twice
  // the valid photons (a flat gather processes all 1024 x 2048).
  std::cout << "processed " << c.TotalProcessed << " for " << c.Valid << " valid photons ("
            << static_cast<double>(c.TotalProcessed) / c.Valid << "x)\n";
  EXPECT_LE(c.TotalProcessed, 2 * c.Valid);
  EXPECT_EQ(f.Pass->GetNumberOfProcessedPhotons(0), c.TotalProcessed);
  EXPECT_EQ(f.Pass->GetNumberOfValidPhotons(0), c.Valid);

  f.Pass->SetGatherMode(vtkCausticsHierarchicalCausticMapPass::GATHER_FLAT);
  f.Render();
  ASSERT_TRUE(f.Pass->GetCounters(0, c));
  EXPECT_EQ(c.TotalProcessed, 1024 * 2048);
  EXPECT_EQ(c.Valid, c.Hits);
}

TEST(Hierarchy, DoesNotChangeThePicture)
{
  Frame f("ball-lens", 1024);
  f.Pass->SetGatherMode(vtkCausticsHierarchicalCausticMapPass::GATHER_FLAT);
  f.Render();
  auto flat = f.Buffer("CausticIrradiance");
  ASSERT_NE(flat, nullptr);
  ASSERT_GT(hcmtest::Total(Array(flat)), 0.0);

  f.Pass->SetGatherMode(vtkCausticsHierarchicalCausticMapPass::GATHER_HIERARCHICAL);
  const int modes[] = { vtkCausticsHierarchicalCausticMapPass::CLUSTER_NONE,
    vtkCausticsHierarchicalCausticMapPass::CLUSTER_LAST_LEVEL,
    vtkCausticsHierarchicalCausticMapPass::CLUSTER_ALL_LEVELS };
  for (int mode : modes)
  {
    f.Pass->SetClusterMode(mode);
    f.Render();
    auto hierarchical = f.Buffer("CausticIrradiance");
    ASSERT_NE(hierarchical, nullptr);
    vtkCausticsHierarchicalCausticMapPass::Counters c;
    ASSERT_TRUE(f.Pass->GetCounters(0, c));
    const double error = hcmtest::RelativeL2(Array(hierarchical), Array(flat));
    std::cout << "cluster mode " << mode << ": " << c.Clusters << " clusters of "
              << c.ClusteredPhotons << " photons, relative L2 to the flat gather " << error << "\n";
    if (mode == vtkCausticsHierarchicalCausticMapPass::CLUSTER_NONE)
    {
      // The same splats in another order: only float summation order differs.
      EXPECT_LT(error, 1e-5);
      EXPECT_EQ(c.Clusters, 0);
    }
    else
    {
      // A cluster's photons land in one texel of the finest level and are drawn
      // as one kernel of the smallest radius at their centroid instead of one
      // each (their own radii are that smallest one too: they are less than a
      // texel apart): the picture moves by less than a texel where photons
      // converge. Measured 0.16 % (last level) and 0.32 % (all levels); the
      // issue's bound is 1 %.
      EXPECT_GT(c.Clusters, 0);
      EXPECT_LT(error, 0.01);
      // Splats: the unclustered photons plus one per cluster.
      EXPECT_EQ(c.Splats[0] + c.Splats[1] + c.Splats[2] + c.Splats[3],
        c.Valid - c.ClusteredPhotons + c.Clusters);
    }
    if (mode == vtkCausticsHierarchicalCausticMapPass::CLUSTER_ALL_LEVELS)
    {
      // Testing every level finds at least the clusters of the last level.
      EXPECT_GE(c.ClusteredPhotons, 4 * c.Clusters);
    }
  }
}

TEST(Pyramid, KeepsEveryPhotonsFlux)
{
  // The ball lens's map looks straight down at the floor: a map texel of width w
  // covers w^2 of floor, so flux = sum over texels of E w^2, level by level.
  Frame f("ball-lens", 512);
  const int splatModes[] = { vtkCausticsHierarchicalCausticMapPass::SPLAT_CONSTANT,
    vtkCausticsHierarchicalCausticMapPass::SPLAT_VARYING_SINGLE,
    vtkCausticsHierarchicalCausticMapPass::SPLAT_VARYING_MULTIRES };
  for (int mode : splatModes)
  {
    f.Pass->SetSplatMode(mode);
    f.Render();
    vtkCausticsHierarchicalCausticMapPass::Counters c;
    ASSERT_TRUE(f.Pass->GetCounters(0, c));
    ASSERT_NE(f.Pass->GetMapView(0), nullptr);
    const caustics::LightView view = *f.Pass->GetMapView(0);
    double mapped = 0.0, splatted = 0.0;
    const int levels = f.Pass->GetCausticMap(0)->GetNumberOfLevels();
    EXPECT_EQ(
      levels, mode == vtkCausticsHierarchicalCausticMapPass::SPLAT_VARYING_MULTIRES ? 4 : 1);
    for (int j = 0; j < levels; ++j)
    {
      vtkNew<vtkImageData> map;
      ASSERT_TRUE(f.Pass->ReadCausticMap(0, j, map));
      const double texel = 2.0 * view.halfExtent / f.Pass->GetCausticMap(0)->GetLevelResolution(j);
      mapped += hcmtest::Total(Array(map)) * texel * texel;
      splatted += c.SplatFlux[j];
    }
    EXPECT_EQ(c.CoarseFluxFraction > 0.0, c.CoarseSplats > 0);
    EXPECT_DOUBLE_EQ(c.DroppedFluxFraction, 0.0); // coarse splats go to level 3
    std::cout << "splat mode " << mode << ": map flux " << mapped << " W, splatted " << splatted
              << " W, landed " << c.FluxHits << " W\n";
    // Nothing is lost between the photon buffer and the splat lists (fixed-point
    // sums, 1e-4 as in PhotonBuffer.AccountsForEveryWatt).
    EXPECT_NEAR(splatted / c.FluxHits, 1.0, 1e-4);
    // Kernels narrower than 4 pixels are normalized over the pixel centres they
    // cover (exact); wider ones rely on the midpoint rule, within 1 % per splat at
    // 4 pixels and far less beyond, of either sign. Kernel mass beyond the floor's
    // edge is lost; there is none here. Measured -0.01 % (constant), -0.18 %
    // (varying, single map), -0.25 % (multi-resolution): 0.5 %.
    EXPECT_NEAR(mapped / splatted, 1.0, 5e-3);
  }
}

TEST(Pyramid, CoarseSplatsAreCountedAndKept)
{
  const char* scenes[] = { "ball-lens", "ring", "bunny" };
  for (const char* name : scenes)
  {
    Frame f(name, 512);
    ASSERT_TRUE(f.Populated) << f.Scene->GetLastError();
    f.Render();
    vtkCausticsHierarchicalCausticMapPass::Counters kept;
    ASSERT_TRUE(f.Pass->GetCounters(0, kept));
    std::cout << name << ": of the emitted flux, " << 100.0 * kept.FluxHits / kept.FluxIn
              << " % landed, " << 100.0 * kept.FluxStored / kept.FluxIn
              << " % went to the caustic store, " << 100.0 * kept.FluxEscaped / kept.FluxIn
              << " % escaped, "
              << 100.0 * kept.FluxLostInside / kept.FluxIn << " % stayed inside, "
              << 100.0 * kept.FluxInternalReflection / kept.FluxIn
              << " % was reflected back inside at exits\n";
    // By default nothing is dropped: coarse splats go to the coarsest level.
    EXPECT_DOUBLE_EQ(kept.DroppedFluxFraction, 0.0) << name;
    EXPECT_NEAR((kept.SplatFlux[0] + kept.SplatFlux[1] + kept.SplatFlux[2] + kept.SplatFlux[3]) /
        kept.FluxHits,
      1.0, 1e-4)
      << name;
    f.Pass->DropCoarseSplatsOn();
    f.Render();
    vtkCausticsHierarchicalCausticMapPass::Counters dropped;
    ASSERT_TRUE(f.Pass->GetCounters(0, dropped));
    std::cout << name << ": splats needing level 4+: " << dropped.CoarseSplats << ", "
              << 100.0 * dropped.DroppedFluxFraction << " % of the flux\n";
    EXPECT_EQ(dropped.CoarseSplats, kept.CoarseSplats) << name;
    EXPECT_NEAR(dropped.DroppedFluxFraction, kept.CoarseFluxFraction, 1e-6) << name;
    // The paper's choice would lose this flux; docs/technique-caustic-maps.md
    // lists it per scene. It is what the default keeps in level 3 instead.
    EXPECT_GT(dropped.DroppedFluxFraction, 0.0) << name;
    EXPECT_NEAR(
      (dropped.SplatFlux[0] + dropped.SplatFlux[1] + dropped.SplatFlux[2] + dropped.SplatFlux[3]) /
        dropped.FluxHits,
      1.0 - dropped.DroppedFluxFraction, 1e-4)
      << name;
  }
}

TEST(Pyramid, IsFilteredToTheImageNotToTheMap)
{
  // The final render samples the caustic map once per camera pixel. Without the
  // kernels' floor of one camera pixel footprint (MinimumCameraSplatRadius), a finer
  // map keeps detail the image cannot show and it aliases into noise: the picture
  // depends on the map's resolution. With it, it must not (beyond the map texels'
  // own say in the splats' placement and receiver tests).
  Frame f("bunny", 512, 256);
  auto render = [&f](int mapResolution, double floor)
  {
    f.Pass->SetCausticMapResolution(mapResolution);
    f.Pass->SetMinimumCameraSplatRadius(floor);
    f.Render();
    return f.Buffer("CausticIrradiance");
  };
  auto coarse = render(512, 1.0);
  auto fine = render(2048, 1.0);
  auto coarseUnfiltered = render(512, 0.0);
  auto fineUnfiltered = render(2048, 0.0);
  ASSERT_TRUE(coarse && fine && coarseUnfiltered && fineUnfiltered);
  ASSERT_GT(hcmtest::Total(Array(coarse)), 0.0);
  const double filtered = hcmtest::RelativeL2(Array(fine), Array(coarse));
  const double unfiltered = hcmtest::RelativeL2(Array(fineUnfiltered), Array(coarseUnfiltered));
  std::cout << "bunny, map 2048 against map 512: relative L2 " << filtered
            << " with the camera floor, " << unfiltered << " without\n";
  // Measured: 3.0 % with the floor, 78 % without (256^2 image, 512^2 photons).
  EXPECT_LT(filtered, 0.05);
  EXPECT_GT(unfiltered, 5.0 * filtered);
}

TEST(FinalRender, AddsTheLights)
{
  // A second directional light, 30 degrees off the vertical: the frame with both
  // lights is the sum of the frames with each (each has its own photon buffer and
  // caustic map).
  Frame f("ball-lens", 256);
  vtkLight* down = FirstLight(f.Renderer);
  ASSERT_NE(down, nullptr);
  vtkNew<vtkLight> slanted;
  slanted->SetLightTypeToSceneLight();
  slanted->SetPositional(false);
  slanted->SetPosition(std::sin(M_PI / 6.0), std::cos(M_PI / 6.0), 0.0);
  slanted->SetFocalPoint(0, 0, 0);
  slanted->SetIntensity(0.5);
  f.Renderer->AddLight(slanted);
  f.Render();
  ASSERT_EQ(f.Pass->GetNumberOfLights(), 2);
  EXPECT_TRUE(f.Pass->GetLightTraced(0));
  EXPECT_TRUE(f.Pass->GetLightTraced(1));
  auto both = f.Buffer("CausticIrradiance");
  slanted->SwitchOff();
  f.Render();
  auto first = f.Buffer("CausticIrradiance");
  slanted->SwitchOn();
  down->SwitchOff();
  f.Render();
  auto second = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(both && first && second);
  vtkNew<vtkFloatArray> sum;
  sum->DeepCopy(Array(first));
  for (vtkIdType i = 0; i < sum->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum->SetComponent(i, c, sum->GetComponent(i, c) + Array(second)->GetComponent(i, c));
    }
  }
  ASSERT_GT(hcmtest::Total(Array(second)), 0.0);
  // Additive blending of float maps: float rounding only.
  EXPECT_LT(hcmtest::RelativeL2(Array(both), sum), 1e-5);
}

TEST(FinalRender, IndexOneLetsTheLightThrough)
{
  // A ball of IOR 1 neither bends nor reflects: the caustic under it is the light
  // itself, 1 W/m^2 on the floor (the reference shows the same, TestReference).
  Frame f(nullptr, 512);
  f.Scene->SetRefractiveIndex(1.0);
  ASSERT_TRUE(f.Scene->Populate(f.Renderer));
  f.Render();
  auto caustic = f.Buffer("CausticIrradiance");
  auto position = f.Buffer("Position");
  ASSERT_TRUE(caustic && position);
  double sum = 0.0;
  int count = 0;
  for (vtkIdType i = 0; i < caustic->GetNumberOfPoints(); ++i)
  {
    const double x = Array(position)->GetComponent(i, 0);
    const double y = Array(position)->GetComponent(i, 1);
    const double z = Array(position)->GetComponent(i, 2);
    // Floor pixels well inside the ball's shadow (the kernel blurs its edge).
    if (Array(position)->GetComponent(i, 3) >= 0.0 && std::abs(y) < 1e-3 && std::hypot(x, z) < 0.8)
    {
      sum += Array(caustic)->GetComponent(i, 0);
      ++count;
    }
  }
  ASSERT_GT(count, 100);
  // Each texel's photon lands under it with the texel's flux; the splats of a
  // regular grid ripple by 8 % peak to peak (SplatScale 2), about +-2 % around the
  // mean at any point, averaged over the disk: 1 %.
  EXPECT_NEAR(sum / count, 1.0, 0.01);
}

TEST(Pass, CountersParametersAndResources)
{
  Frame f("ball-lens", 128);
  vtkCausticsHierarchicalCausticMapPass::Counters c;
  EXPECT_FALSE(f.Pass->GetCounters(0, c)); // no frame yet
  f.Render();
  ASSERT_TRUE(f.Pass->GetCounters(0, c));
  vtkCausticsHierarchicalCausticMapPass::Counters none;
  EXPECT_FALSE(f.Pass->GetCounters(1, none)); // one light only
  EXPECT_EQ(f.Pass->GetNumberOfSplats(0, 0), c.Splats[0]);
  EXPECT_EQ(f.Pass->GetNumberOfClusters(0), c.Clusters);
  EXPECT_DOUBLE_EQ(f.Pass->GetDroppedFluxFraction(0), 0.0);
  vtkNew<vtkImageData> map;
  EXPECT_FALSE(f.Pass->ReadCausticMap(0, 4, map));
  EXPECT_TRUE(f.Pass->ReadCausticMap(0, 3, map));

  // Clamped parameters.
  f.Pass->SetCausticMapResolution(1);
  EXPECT_EQ(f.Pass->GetCausticMapResolution(), 16);
  f.Pass->SetSplatSizeThreshold(1000.0);
  EXPECT_DOUBLE_EQ(f.Pass->GetSplatSizeThreshold(), 64.0);
  f.Pass->SetGatherMode(7);
  EXPECT_EQ(f.Pass->GetGatherMode(), vtkCausticsHierarchicalCausticMapPass::GATHER_HIERARCHICAL);
  f.Pass->SetMinimumCameraSplatRadius(-1.0);
  EXPECT_DOUBLE_EQ(f.Pass->GetMinimumCameraSplatRadius(), 0.0);
  f.Pass->SetMinimumCameraSplatRadius(100.0);
  EXPECT_DOUBLE_EQ(f.Pass->GetMinimumCameraSplatRadius(), 16.0);
  f.Pass->SetMinimumCameraSplatRadius(1.0);

  std::ostringstream printed;
  f.Pass->Print(printed);
  EXPECT_NE(printed.str().find("GatherMode: hierarchical"), std::string::npos);
  EXPECT_NE(printed.str().find("light 0: traced"), std::string::npos);

  // Released resources are re-created by the next frame.
  f.Pass->ReleaseGraphicsResources(f.Window);
  EXPECT_EQ(f.Pass->GetNumberOfLights(), 0);
  EXPECT_EQ(f.Pass->GetPhotonBuffer(0), nullptr);
  f.Pass->SetCausticMapResolution(256);
  // vtkCausticsSceneGeometry re-sends its material table only when the materials
  // change, also after ReleaseGraphicsResources (reported); change one so that the
  // frame after the release has its materials.
  FindActor(f.Renderer, "floor")->GetProperty()->SetColor(0.7, 0.7, 0.7);
  f.Render();
  ASSERT_TRUE(f.Pass->GetCounters(0, c));
  EXPECT_GT(c.Valid, 0);
}

TEST(Pass, RedrawsTheLightsLayersWhenAnythingTheyShowChanges)
{
  // The receivers and refractor faces seen from the light are kept while nothing
  // changes. After each change the kept pass must give what a new pass gives on the
  // same scene, and something else than before the change (or the test says nothing).
  Frame kept("ball-lens", 64, 64);
  kept.Render();
  kept.Render(); // the layers are kept from here on
  struct Change
  {
    const char* What;
    std::function<void(vtkRenderer*)> Apply;
  };
  const std::vector<Change> changes = {
    { "a moved actor",
      [](vtkRenderer* r) { FindActor(r, "glass ball")->AddPosition(0.2, 0.3, 0.0); } },
    { "the light's direction",
      [](vtkRenderer* r)
      {
        double p[3];
        FirstLight(r)->GetPosition(p);
        FirstLight(r)->SetPosition(p[0] + 0.3 * std::abs(p[1]), p[1], p[2]);
      } },
    { "the refractor's absorption",
      [](vtkRenderer* r)
      {
        const double perMetre[3] = { 0.5, 0.2, 0.1 };
        vtkCausticsMaterial::SetAttenuation(FindActor(r, "glass ball")->GetProperty(), perMetre);
      } },
    { "the refractor's index",
      [](vtkRenderer* r) { FindActor(r, "glass ball")->GetProperty()->SetBaseIOR(1.33); } },
  };
  std::vector<std::unique_ptr<Frame>> fresh;
  for (const Change& change : changes)
  {
    auto before = kept.Buffer("CausticIrradiance");
    ASSERT_TRUE(before);
    change.Apply(kept.Renderer);
    kept.Render();
    auto after = kept.Buffer("CausticIrradiance");
    // A new pass on the scene as changed so far.
    fresh.emplace_back(new Frame("ball-lens", 64, 64));
    for (const auto& applied : changes)
    {
      applied.Apply(fresh.back()->Renderer);
      if (&applied == &change)
      {
        break;
      }
    }
    fresh.back()->Render();
    auto reference = fresh.back()->Buffer("CausticIrradiance");
    ASSERT_TRUE(after && reference);
    const double changed = hcmtest::RelativeL2(Array(after), Array(before));
    const double fromNew = hcmtest::RelativeL2(Array(after), Array(reference));
    std::cout << change.What << ": relative L2 " << changed << " against the frame before, "
              << fromNew << " against a new pass\n";
    EXPECT_GT(changed, 1e-3) << change.What << " changed nothing";
    EXPECT_LT(fromNew, 1e-6) << change.What;
    fresh.back().reset(); // one GL context at a time
  }
}
