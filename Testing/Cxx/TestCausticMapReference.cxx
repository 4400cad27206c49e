// Hierarchical caustic maps against the CPU reference renderer
// (vtkCausticsReferenceRenderer, docs/reference.md) with the metrics of
// docs/accuracy.md: 256^2 images, 1024^2 photons per light on the GPU (default
// settings otherwise), 10^6 reference photons, receiver pixels only (the
// reference's ReceiverMask), fluxes weighted by the reference's PixelArea.
//
// Bounds are set just above what the technique reaches here (printed by the
// tests, listed in docs/technique-caustic-maps.md), so that they fail if it
// regresses. The reference is noisy itself: each test also prints the relative L2
// between two reference renders with different seeds (ball lens 0.88 %, pool
// 0.68 %, ring 0.78 %, bunny 4.5 %), i.e. each render carries 1/sqrt(2) of that; the bounds
// leave room for that and for float differences between GPUs, nothing more.
#include "TestHierarchicalCausticMapUtilities.h"

#include "vtkCamera.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsSceneData.h"

#include "vtkLight.h"
#include "vtkLightCollection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <iostream>

namespace
{
/** Metrics of the caustic irradiance on the reference's receiver pixels, by area. */
void OnReceivers(vtkCausticsErrorMetrics* metrics)
{
  metrics->SetArrayName("CausticIrradiance");
  metrics->SetMaskArrayName("ReceiverMask");
  metrics->SetAreaArrayName("PixelArea");
}

/**
 * Renders `scene` on the GPU and with the reference; returns the metrics. With
 * throughRefractors off, the reference's camera rays pass refractors (the pool's
 * floor under the water), as the technique's output does. `change` edits the scene
 * first (may be empty).
 */
bool Compare(const char* scene, vtkCausticsErrorMetrics* metrics, bool throughRefractors = false,
  const std::function<void(vtkRenderer*)>& change = {})
{
  hcmtest::Frame f(scene, 1024, 256);
  if (!f.Populated)
  {
    return false;
  }
  if (change)
  {
    change(f.Renderer);
  }
  f.Render();
  auto caustic = f.Buffer("CausticIrradiance");
  if (!caustic)
  {
    return false;
  }
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(f.Renderer);
  reference->SetImageSize(256, 256);
  reference->SetPhotonsPerLight(1000000);
  reference->SetCameraSeesRefractors(!throughRefractors);
  reference->UseCacheOff(); // 2 s on two cores: always this code's answer
  if (!reference->Update())
  {
    std::cerr << reference->GetLastError() << "\n";
    return false;
  }
  OnReceivers(metrics);
  const bool ok = metrics->Compute(caustic, reference->GetOutput());
  std::cout << scene << ": " << metrics->GetSummary() << "\n";
  // The reference's own noise: the same render with another seed.
  vtkNew<vtkCausticsReferenceRenderer> other;
  other->SetInputRenderer(f.Renderer);
  other->SetImageSize(256, 256);
  other->SetPhotonsPerLight(1000000);
  other->SetSeed(2);
  other->SetCameraSeesRefractors(!throughRefractors);
  other->UseCacheOff();
  vtkNew<vtkCausticsErrorMetrics> noise;
  noise->SetMaskArrayName("ReceiverMask");
  noise->SetAreaArrayName("PixelArea");
  if (other->Update() && noise->Compute(other->GetOutput(), reference->GetOutput()))
  {
    std::cout << scene << " reference, seed 2 against seed 1: " << noise->GetSummary() << "\n";
  }
  return ok;
}
}

TEST(CausticMapReference, BallLens)
{
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(Compare("ball-lens", metrics));
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  // Measured: relative L2 1.08 %, flux ratio 0.9972, peak 1 px off (the issue asks
  // for at most 15 % and 3 %).
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.015);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.01);
  EXPECT_LE(metrics->GetPeakPositionError(), 2.0);
}

TEST(CausticMapReference, PoolFloor)
{
  // The floor under the waves: the water is an open refractor (one sheet), so the
  // photons stay in the water after refracting in and go on to the floor. Reached
  // here: relL2 8.29 %, flux 0.9973 (8.18 % and 1.0029 before the reference's estimate
  // held up to a receiver's end and the kernels gave the floor what they lost on the
  // walls at its edges: both had lost 1-3 % along the walls, docs/reference.md).
  // The floor along the sunlit wall is hidden from
  // the sun's caustic map by the wall while refraction bends photons onto it: the
  // hidden receivers' map holds it (HiddenReceivers); without it 19.7 % and flux
  // 0.968, that strip's 3 % missing (docs/technique-caustic-maps.md). Before open
  // refractors were handled, the water acted as a zero-thickness slab: relL2 50 %.
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(Compare("pool", metrics, true));
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.085);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.005);
}

TEST(CausticMapReference, Ring)
{
  // The nephroid of a silver ring: one reflection per photon here, where the
  // reference also follows the grazing multiple reflections along the far wall
  // (a bright crescent the caustic map lacks) and blocks photons that the ring
  // itself shadows after their reflection. Measured: relative L2 8.64 %, flux
  // ratio 0.9986, peak on the same pixel (8.69 % with the paper's max-distance
  // spacing, MaxDistanceFraction 1: at 1024^2 photons the kernels are one camera pixel
  // footprint, MinimumCameraSplatRadius, either way; 21.2 % in an older version, 24.0 %
  // with the map in the sun's own view, 33 degrees above the floor, before
  // MinimumMapIncidence).
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(Compare("ring", metrics));
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.09);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.005);
  EXPECT_LE(metrics->GetPeakPositionError(), 2.0);
}

// The ring at the default 256^2 photons: the nephroid's photons are squeezed across
// its arms and spread along them, and Eq. 2's max distance (the paper's) made each
// kernel as wide as the long axis, blurring the arms across. The spacing is now the
// beam's mean width (MaxDistanceFraction 0.5). Measured: relative L2 9.38 %, flux
// 1.0000; with the max distance 25.0 %, flux 0.9982 (against a 4 * 10^6-photon
// reference, 9.35 % and 25.0 %).
TEST(CausticMapReference, RingAtTheDefaultPhotons)
{
  hcmtest::Frame f("ring", 256, 256);
  ASSERT_TRUE(f.Populated);
  f.Render();
  auto caustic = f.Buffer("CausticIrradiance");
  f.Pass->SetMaxDistanceFraction(1.0);
  f.Render();
  auto paper = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(caustic && paper);
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(f.Renderer);
  reference->SetImageSize(256, 256);
  reference->SetPhotonsPerLight(1000000);
  reference->UseCacheOff();
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkNew<vtkCausticsErrorMetrics> metrics, maxDistance;
  OnReceivers(metrics);
  OnReceivers(maxDistance);
  ASSERT_TRUE(metrics->Compute(caustic, reference->GetOutput()));
  ASSERT_TRUE(maxDistance->Compute(paper, reference->GetOutput()));
  std::cout << "ring, 256^2 photons: " << metrics->GetSummary()
            << "\n  with the max distance: " << maxDistance->GetSummary() << "\n";
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.1);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.005);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.5 * maxDistance->GetRelativeL2Error());
}

// Against each pixel's mean irradiance (the reference's pixel-footprint estimate, no
// kernel: docs/reference.md), the ring's nephroid at the default 256^2 photons, 128^2
// pixels: caustic triangles, drawn in the camera's view, keep its sharp arms and cusp,
// which the splats' kernels (at least a pixel footprint, two photon spacings) blur.
// Measured: triangles 5.1 %, splats 15.8 %, flux 1.001 both (the same with 1.6e7
// reference photons: the 4e6 here are converged); screen-space 7.9 % and 24.9 %
// (scripts/scene-variant.py --scene ring --size 128 --reference-kernel pixel
// --reference-photons 4e6 [--reconstruction triangles]).
TEST(CausticMapReference, RingTrianglesMatchEachPixelsMean)
{
  hcmtest::Frame f("ring", 256, 128);
  ASSERT_TRUE(f.Populated);
  f.Render();
  auto splats = f.Buffer("CausticIrradiance");
  f.Pass->SetReconstructionToTriangles();
  f.Render();
  auto triangles = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(splats && triangles);
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(f.Renderer);
  reference->SetImageSize(128, 128);
  reference->SetPhotonsPerLight(4000000);
  reference->PixelFootprintEstimateOn();
  reference->UseCacheOff();
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkNew<vtkCausticsErrorMetrics> splatMetrics, triangleMetrics;
  OnReceivers(splatMetrics);
  OnReceivers(triangleMetrics);
  ASSERT_TRUE(splatMetrics->Compute(splats, reference->GetOutput()));
  ASSERT_TRUE(triangleMetrics->Compute(triangles, reference->GetOutput()));
  std::cout << "ring against each pixel's mean: triangles " << triangleMetrics->GetSummary()
            << "\n  splats " << splatMetrics->GetSummary() << "\n";
  EXPECT_EQ(triangleMetrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(triangleMetrics->GetRelativeL2Error(), 0.06);
  EXPECT_NEAR(triangleMetrics->GetFluxRatio(), 1.0, 0.005);
  EXPECT_NEAR(splatMetrics->GetFluxRatio(), 1.0, 0.005);
  EXPECT_LT(triangleMetrics->GetRelativeL2Error(), 0.5 * splatMetrics->GetRelativeL2Error());
}

TEST(CausticMapReference, Bunny)
{
  // A glass bunny under a spot light in a Cornell box: the bunny is not a convex
  // solid, so photons inside leave through its triangles (the camera view's
  // hierarchy), and the part reflected back inside at an exit goes on inside by
  // Russian roulette; the caustic map sees only the spot's cone, and the light
  // reflected onto the ceiling and the upper walls lands in the caustic store
  // (ReceiversTheMapDoesNotSeeTakeTheStore below); a photon that left does not meet
  // the bunny again, and photons trapped inside after 8 interfaces are dropped.
  // Measured: relative L2 47.8 %, flux ratio 1.020, peak 1 px off: the walls now keep
  // the light their kernels lost at the box's corners, and the reference counts the
  // light along them (docs/reference.md); what is over is the floor (1.053 of it,
  // ReceiversTheMapDoesNotSeeTakeTheStore). Before both, 47.8 % and 0.963. Before the store,
  // 49.4 % and 0.866; before the roulette too, 49.7 % and 0.780; with the refractor
  // taken as the slab between its front and back faces seen from the light, 53.8 %
  // and 0.652 (59.8 % before the splats' floor of one camera pixel footprint,
  // MinimumCameraSplatRadius).
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(Compare("bunny", metrics));
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.49);
  EXPECT_GT(metrics->GetFluxRatio(), 0.95);
  EXPECT_LT(metrics->GetFluxRatio(), 1.03);
}

namespace
{
/** The reference of a 256^2 frame `f` (10^6 photons), its camera rays passing the
 * refractors as the caustic buffer's G-buffer does; null (and a failure) on error. */
vtkSmartPointer<vtkImageData> ReferenceThroughRefractors(hcmtest::Frame& f)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(f.Renderer);
  reference->SetImageSize(256, 256);
  reference->SetPhotonsPerLight(1000000);
  reference->CameraSeesRefractorsOff();
  if (!reference->Update())
  {
    ADD_FAILURE() << reference->GetLastError();
    return nullptr;
  }
  return reference->GetOutput();
}

/** Flux (W, summed over RGB) of `irradiance` on the reference's receiver pixels whose
 * normal has a component along `axis` beyond `threshold` (signed). */
double FluxWhereNormal(
  vtkDataArray* irradiance, vtkImageData* reference, int axis, double threshold)
{
  vtkDataArray* mask = hcmtest::Array(reference, "ReceiverMask");
  vtkDataArray* normal = hcmtest::Array(reference, "Normal");
  vtkDataArray* area = hcmtest::Array(reference, "PixelArea");
  double flux = 0.0;
  for (vtkIdType i = 0; i < mask->GetNumberOfTuples(); ++i)
  {
    const double n = normal->GetComponent(i, axis);
    if (mask->GetComponent(i, 0) > 0.0 && (threshold < 0.0 ? n < threshold : n > threshold))
    {
      for (int c = 0; c < 3; ++c)
      {
        flux += irradiance->GetComponent(i, c) * area->GetComponent(i, 0);
      }
    }
  }
  return flux;
}
}

TEST(CausticMapReference, ReceiversTheMapDoesNotSeeTakeTheStore)
{
  // The bunny's Cornell box: the spot in the ceiling lights the floor, and the glass
  // reflects and refracts its light onto the ceiling and the upper walls, which the
  // caustic map's view (aimed down the spot's cone) does not hold. Their photons go to
  // the distance impostors' caustic store, and the final render reads it at the
  // receivers the map does not see (vtkCausticsCausticMap::ApplyStore). Measured
  // against the reference: ceiling 1.017 of its flux, walls 0.948 (back 0.879), floor
  // 1.053. Without the store the ceiling had none. The walls, which the map sees
  // obliquely and whose kernels meet the floor, the ceiling and each other, read 0.846
  // (back 0.74) before each splat deposited its whole flux on the receivers it reaches
  // (KernelDeposit, vtkCausticsSplatCoverage.glsl). The floor is 5 % over with splats
  // and 0.7 % over with caustic triangles from the same photons (not explained yet).
  hcmtest::Frame f("bunny", 1024, 256);
  ASSERT_TRUE(f.Populated);
  f.Render();
  auto caustic = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(caustic);
  vtkCausticsHierarchicalCausticMapPass::Counters counters;
  ASSERT_TRUE(f.Pass->GetCounters(0, counters));
  EXPECT_GT(counters.Stored, 0);
  vtkSmartPointer<vtkImageData> truth = ReferenceThroughRefractors(f);
  ASSERT_TRUE(truth);
  vtkDataArray* ours = hcmtest::Array(caustic);
  vtkDataArray* exact = hcmtest::Array(truth, "CausticIrradiance");
  const double ceiling =
    FluxWhereNormal(ours, truth, 1, -0.9) / FluxWhereNormal(exact, truth, 1, -0.9);
  // The red, green and back walls.
  const int axes[3] = { 0, 0, 2 };
  const double sides[3] = { 0.9, -0.9, 0.9 };
  double wallsOurs = 0.0, wallsExact = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    wallsOurs += FluxWhereNormal(ours, truth, axes[k], sides[k]);
    wallsExact += FluxWhereNormal(exact, truth, axes[k], sides[k]);
  }
  const double walls = wallsOurs / wallsExact;
  const double floor =
    FluxWhereNormal(ours, truth, 1, 0.9) / FluxWhereNormal(exact, truth, 1, 0.9);
  const double back =
    FluxWhereNormal(ours, truth, 2, 0.9) / FluxWhereNormal(exact, truth, 2, 0.9);
  std::cout << "bunny's box: ceiling " << ceiling << " of the reference's flux, walls " << walls
            << " (back " << back << "), floor " << floor << "; " << counters.Stored
            << " photons went to the caustic store\n";
  EXPECT_NEAR(ceiling, 1.0, 0.1);
  EXPECT_GT(walls, 0.92);
  EXPECT_LT(walls, 1.05);
}

TEST(CausticMapReference, CameraOutsideTheBoxSeesItsWallsUnlit)
{
  // The bunny's Cornell box seen from outside, beyond its green wall (x = 1): the
  // camera sees that wall's outside, which no light of the box reaches. The final
  // render showed the map's caustic of the wall's inside there (the flux 1.083 of the
  // reference's; 1.031 without it, relative L2 22.2 %): it now shows a receiver's light
  // only on the side the map's view sees.
  hcmtest::Frame f("bunny", 1024, 256);
  ASSERT_TRUE(f.Populated);
  vtkCamera* camera = f.Renderer->GetActiveCamera();
  camera->SetPosition(1.6, 1.2, 2.5);
  camera->SetFocalPoint(0.0, 0.4, 0.0);
  f.Renderer->ResetCameraClippingRange();
  f.Render();
  auto caustic = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(caustic);
  vtkSmartPointer<vtkImageData> truth = ReferenceThroughRefractors(f);
  ASSERT_TRUE(truth);
  vtkDataArray* ours = hcmtest::Array(caustic);
  vtkDataArray* position = hcmtest::Array(truth, "Position");
  vtkDataArray* mask = hcmtest::Array(truth, "ReceiverMask");
  int outside = 0;
  double lit = 0.0;
  for (vtkIdType i = 0; i < mask->GetNumberOfTuples(); ++i)
  {
    if (mask->GetComponent(i, 0) > 0.0 && position->GetComponent(i, 0) > 0.999)
    {
      ++outside;
      lit += ours->GetComponent(i, 0) + ours->GetComponent(i, 1) + ours->GetComponent(i, 2);
    }
  }
  vtkNew<vtkCausticsErrorMetrics> metrics;
  OnReceivers(metrics);
  ASSERT_TRUE(metrics->Compute(caustic, truth));
  std::cout << "bunny's box from outside: " << metrics->GetSummary() << "; " << outside
            << " pixels of the green wall's outside, caustic sum " << lit << "\n";
  EXPECT_GT(outside, 2000);
  EXPECT_EQ(lit, 0.0);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.05);
}

TEST(CausticMapReference, GrazingSun)
{
  // The ball lens under a sun 2.9 degrees above the floor and exactly parallel to
  // it: the light's own view sees the floor edge-on, and its caustic map kept 37 %
  // and none of the caustic. The map's view now turns to MinimumMapIncidence (45
  // degrees) about the floor point the light meets. Measured: relative L2 14.3 %
  // and 17.3 %, flux ratio 0.931 and 0.919 (screen-space, at 128^2: 23 % and 35 %).
  // The reference's own noise is large on so faint a caustic: 9.3 % and 9.9 %
  // between two seeds.
  struct Case
  {
    double rise, relL2;
  };
  for (const Case c : { Case{ 0.05, 0.155 }, Case{ 0.0, 0.185 } })
  {
    const double rise = c.rise;
    vtkNew<vtkCausticsErrorMetrics> metrics;
    ASSERT_TRUE(Compare("ball-lens", metrics, false,
      [rise](vtkRenderer* renderer)
      {
        vtkLight* sun = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
        sun->SetFocalPoint(0.0, 0.0, 0.0);
        sun->SetPosition(-1.0, rise, 0.0);
      }));
    EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
    EXPECT_LT(metrics->GetRelativeL2Error(), c.relL2) << rise;
    EXPECT_GT(metrics->GetFluxRatio(), 0.9) << rise;
    EXPECT_LT(metrics->GetFluxRatio(), 1.0) << rise;
  }
}

// A lamp over the ball lens: a point light 6 m up, 3 m above the ball's centre, which
// focuses its light on the floor (a bright spot about two pixels wide at 256^2). The
// lamp is inside the bounding sphere of what the camera sees, so the map's frustum was
// the widest a view takes (75 degrees off axis, aimed at the scene's centre): 512
// texels over 44 m of floor, kernels of 1.5 texels five pixels wide, the focus at a
// fifth of its peak. The frustum now fits the corners of the receivers in view
// (FitPerspective in vtkCausticsSceneData.cxx). Against a reference with a kernel of
// one pixel footprint (the tests' two would halve this focus's peak itself), 256^2
// photons as the default: measured relative L2 19.3 %, flux 0.992, the peak 0.73 of
// the reference's (the map's half width tan 1.04); with the 75-degree frustum 67.9 %,
// 0.994, 0.19 (tan 3.73).
TEST(CausticMapReference, ALampAboveTheScene)
{
  hcmtest::Frame f("ball-lens", 256, 256);
  ASSERT_TRUE(f.Populated);
  f.Renderer->RemoveAllLights();
  vtkNew<vtkLight> lamp;
  lamp->SetLightTypeToSceneLight();
  lamp->SetPositional(true);
  lamp->SetConeAngle(180.0); // a point light, not a spot
  lamp->SetPosition(0.5, 6.0, 0.3);
  lamp->SetFocalPoint(0.0, 0.0, 0.0);
  lamp->SetIntensity(50.0);
  f.Renderer->AddLight(lamp);
  f.Render();
  auto caustic = f.Buffer("CausticIrradiance");
  ASSERT_TRUE(caustic);
  const caustics::LightView* map = f.Pass->GetMapView(0);
  ASSERT_NE(map, nullptr);
  std::cout << "the map's half width: tan " << map->halfExtent << "\n";
  EXPECT_FALSE(map->clamped);
  EXPECT_LT(map->halfExtent, 1.2); // the floor in view from 6 m up, not tan 75 = 3.73

  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(f.Renderer);
  reference->SetImageSize(256, 256);
  reference->SetPhotonsPerLight(4000000);
  reference->SetKernelRadiusPixels(1.0);
  reference->UseCacheOff();
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkNew<vtkCausticsErrorMetrics> metrics;
  OnReceivers(metrics);
  ASSERT_TRUE(metrics->Compute(caustic, reference->GetOutput()));
  vtkDataArray* ours = hcmtest::Array(caustic, "CausticIrradiance");
  vtkDataArray* truth = hcmtest::Array(reference->GetOutput(), "CausticIrradiance");
  double peak = 0.0, truePeak = 0.0;
  for (vtkIdType i = 0; i < truth->GetNumberOfTuples(); ++i)
  {
    peak = std::max(
      peak, ours->GetComponent(i, 0) + ours->GetComponent(i, 1) + ours->GetComponent(i, 2));
    truePeak = std::max(
      truePeak, truth->GetComponent(i, 0) + truth->GetComponent(i, 1) + truth->GetComponent(i, 2));
  }
  std::cout << "a lamp above the ball lens: " << metrics->GetSummary() << "; peak "
            << peak / truePeak << " of the reference's\n";
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.21);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.02);
  EXPECT_GT(peak / truePeak, 0.7);
}
