// Cascaded image-space photon tracing (vtkCausticsCascadedPhotonPass,
// 002_97e66a5090de9b07.txt) against the CPU reference renderer
// (vtkCausticsReferenceRenderer, cached; docs/accuracy.md metrics) at 256^2 pixels and
// the pass's defaults (65536 photons per light and frame from 256^2 light-buffer
// texels). The estimator is jittered: each frame is a fresh estimate, so the
// caustic irradiance of Frames consecutive frames is averaged first (what a temporal
// filter would do). The denoiser (on by default) is off in these comparisons: the
// figures are the raw estimate's; the Denoised* tests measure what a user sees. Each
// bound is the figure reached (printed, and in docs/technique-cascaded.md) plus a
// small margin for the reference's noise.
#include "TestReferenceUtilities.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsSVGFDenoiser.h"
#include "vtkCausticsTechniques.h"

#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
constexpr int Frames = 4;

/** A scene rendered by the cascaded pass (Frames frames averaged) and by the reference. */
struct Comparison
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkCausticsCascadedPhotonPass> Pass;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkImageData> Caustic;
  vtkNew<vtkCausticsErrorMetrics> Metrics;
  vtkSmartPointer<vtkCausticsReferenceRenderer> Reference;

  Comparison()
  {
    this->Pass->DenoiseOff(); // the raw estimate (see CompareDenoised)
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(256, 256);
    this->Window->AddRenderer(this->Renderer);
    this->Metrics->SetArrayName("CausticIrradiance");
    this->Metrics->SetMaskArrayName("ReceiverMask");
    this->Metrics->SetAreaArrayName("PixelArea");
  }
  ~Comparison()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  bool Populate(const char* scene)
  {
    vtkNew<vtkCausticsBuiltinScene> builtin;
    builtin->SetSceneName(scene);
    return builtin->Populate(this->Renderer);
  }
  /** Averages the caustic irradiance of `frames` frames into Caustic. */
  bool RenderFrames(int frames = Frames)
  {
    vtkDataArray* sum = nullptr;
    for (int frame = 0; frame < frames; ++frame)
    {
      this->Window->Render();
      vtkNew<vtkImageData> image;
      if (!this->Pass->GetLastFrameHadCaustics() ||
        !this->Pass->ReadBuffer("CausticIrradiance", image))
      {
        std::cerr << "frame " << frame << ": no caustics\n";
        return false;
      }
      if (frame == 0)
      {
        this->Caustic->DeepCopy(image);
        sum = this->Caustic->GetPointData()->GetArray("CausticIrradiance");
        continue;
      }
      vtkDataArray* add = image->GetPointData()->GetArray("CausticIrradiance");
      for (vtkIdType i = 0; i < sum->GetNumberOfValues(); ++i)
      {
        sum->SetVariantValue(
          i, sum->GetVariantValue(i).ToDouble() + add->GetVariantValue(i).ToDouble());
      }
    }
    for (vtkIdType i = 0; sum && i < sum->GetNumberOfValues(); ++i)
    {
      sum->SetVariantValue(i, sum->GetVariantValue(i).ToDouble() / frames);
    }
    return sum != nullptr;
  }
  /** The reference for the renderer as it is (cached by the reference renderer). */
  bool Compare(const char* what, bool throughRefractors, vtkIdType photons = 4000000)
  {
    this->Reference = vtkSmartPointer<vtkCausticsReferenceRenderer>::New();
    this->Reference->SetInputRenderer(this->Renderer);
    this->Reference->SetImageSize(256, 256);
    this->Reference->SetPhotonsPerLight(photons);
    this->Reference->SetCameraSeesRefractors(!throughRefractors);
    if (!this->Reference->Update())
    {
      std::cerr << this->Reference->GetLastError() << "\n";
      return false;
    }
    const bool ok = this->Metrics->Compute(this->Caustic, this->Reference->GetOutput());
    std::cout << what << ": " << this->Metrics->GetSummary() << "\n";
    return ok;
  }
};
}

TEST(CascadedPhotonPass, IsRegistered)
{
  auto pass = vtkCausticsTechniques::Create("cascaded");
  ASSERT_NE(pass, nullptr);
  EXPECT_TRUE(pass->IsA("vtkCausticsCascadedPhotonPass"));
}

// Reached (llvmpipe, 4 frames): flux ratio 1.0033, relative L2 0.230 (the issue's
// 10 % is for the denoised estimate; the raw one is splat noise: 0.37 in one frame,
// 0.18 in 16). Bounds: flux within the 3 %, relative L2 0.25.
TEST(CascadedPhotonPass, BallLensMatchesReference)
{
  Comparison c;
  ASSERT_TRUE(c.Populate("ball-lens"));
  ASSERT_TRUE(c.RenderFrames());
  ASSERT_TRUE(c.Compare("ball lens", false));
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.25);
  // Where the photons' light went: the cascade follows nearly all of it here
  // (reached: 0.2 % of what reached a receiver lost, none absorbed).
  caustics::PhotonStatistics photons;
  ASSERT_TRUE(c.Pass->GetLastFramePhotonStatistics(photons));
  std::cout << "ball lens photon light: " << photons.FluxIn << " W, landed "
            << photons.FluxHits / photons.FluxIn << ", left the views "
            << photons.FluxEscaped / photons.FluxIn << ", lost " << photons.LostShareBound()
            << " of what reached receivers\n";
  EXPECT_GT(photons.Photons, 0);
  EXPECT_LT(photons.LostShareBound(), 0.01);
  // Every photon ends once: the fates add up to the light traced (the roulette's
  // per-photon factors average out within a few tenths of a percent).
  EXPECT_NEAR(
    (photons.FluxHits + photons.FluxEscaped + photons.FluxLostInside) / photons.FluxIn, 1.0, 0.01);
}

namespace
{
/** The pass's default, SVGF on (docs/denoising.md), after Frames frames of a still
 * view: the last frame alone, not an average, against the reference. */
void CompareDenoised(Comparison& c, const char* scene, const char* what, bool throughRefractors)
{
  c.Pass->DenoiseOn();
  ASSERT_TRUE(c.Populate(scene));
  ASSERT_TRUE(c.RenderFrames(Frames - 1));
  ASSERT_TRUE(c.RenderFrames(1));
  ASSERT_TRUE(c.Compare(what, throughRefractors));
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
}
}

// What a user sees. The issue asks for flux within 3 % and relative L2 at most 10 %.
// Reached: flux ratio 1.0028, relative L2 0.0558 (the raw average of the same four
// frames: 1.0033, 0.230). Bounds: the 3 %, L2 just past the reached.
TEST(CascadedPhotonPass, DenoisedBallLensMatchesReference)
{
  Comparison c;
  CompareDenoised(c, "ball-lens", "ball lens, denoised", false);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.06);
}

// The pool's sharp caustic network after denoising: the spatial filter must not blur
// it (KernelSpacings 4 did: 0.134). Reached: flux ratio 0.9947, relative L2 0.0571
// (the reference's own noise is about 0.04). Before the splats kept their flux at a
// receiver's end (docs/accuracy.md, "Kernels at a receiver's end"): 0.9885 and 0.0673;
// against the reference before its estimate held up to one (docs/reference.md): 0.9983
// and 0.0473, when both lost the light along the floor's and walls' corners. Bounds:
// the 3 %, L2 just past the reached.
TEST(CascadedPhotonPass, DenoisedPoolFloorMatchesReference)
{
  Comparison c;
  CompareDenoised(c, "pool", "pool, denoised", true);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.06);
}

// A first frame, as every frame is where the light moves (the pool's waves, a light
// sweeping: each history restarts). SVGF's spatial variance of the 7x7 neighbours
// takes the pool's fine caustic network for noise and the a-trous filter blurs it;
// the photons' own variance (the squared difference of the estimates of the frame's
// two halves of photons, CausticsDeposit) does not.
// Reached (llvmpipe): photon variance relative L2 0.0832, spatial 0.231 (0.360 of
// it), the raw frame 0.0862 (with the sum of squared deposits, the Poisson variance
// used before, the photon-variance frame was 0.133). Before the splats kept their flux
// at a receiver's end: 0.089, 0.233 (0.382), 0.094; against the reference before its
// estimate held up to one: 0.0776, 0.233 (0.334), 0.077. Bounds: just past the
// reached.
TEST(CascadedPhotonPass, DenoisedFirstFrameKeepsTheFineCaustic)
{
  enum Variant
  {
    PHOTON_VARIANCE,
    SPATIAL_VARIANCE,
    RAW
  };
  const char* names[] = { "pool, first frame, photon variance",
    "pool, first frame, spatial variance", "pool, first frame, raw" };
  double l2[3] = { 0.0, 0.0, 0.0 };
  for (int variant = PHOTON_VARIANCE; variant <= RAW; ++variant)
  {
    Comparison c;
    c.Pass->SetDenoise(variant != RAW);
    c.Pass->GetDenoiser()->SetPhotonVariance(variant == PHOTON_VARIANCE);
    ASSERT_TRUE(c.Populate("pool"));
    ASSERT_TRUE(c.RenderFrames(1));
    ASSERT_TRUE(c.Compare(names[variant], true));
    EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
    EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
    l2[variant] = c.Metrics->GetRelativeL2Error();
  }
  std::cout << "photon variance " << l2[PHOTON_VARIANCE] << ", spatial "
            << l2[SPATIAL_VARIANCE] << " (" << l2[PHOTON_VARIANCE] / l2[SPATIAL_VARIANCE]
            << " of it), raw " << l2[RAW] << "\n";
  EXPECT_LT(l2[PHOTON_VARIANCE], 0.087);
  EXPECT_LT(l2[PHOTON_VARIANCE], 0.38 * l2[SPATIAL_VARIANCE]);
  EXPECT_LT(l2[PHOTON_VARIANCE], 1.03 * l2[RAW]);
}

// Where the denoiser's flux goes on the still ball lens: the whole denoiser, its
// temporal part alone (no a-trous), and the raw last frame (not run by default:
// --gtest_also_run_disabled_tests; figures in docs/denoising.md).
TEST(CascadedPhotonPass, DISABLED_DenoiserFluxByPart)
{
  const char* names[] = { "denoised", "denoised without a-trous (temporal only)",
    "raw, the last frame" };
  for (int part = 0; part < 3; ++part)
  {
    Comparison c;
    c.Pass->SetDenoise(part < 2);
    c.Pass->GetDenoiser()->SetAtrousIterations(part == 0 ? 5 : 0);
    ASSERT_TRUE(c.Populate("ball-lens"));
    ASSERT_TRUE(c.RenderFrames(Frames - 1));
    ASSERT_TRUE(c.RenderFrames(1));
    ASSERT_TRUE(c.Compare(names[part], false));
  }
}

TEST(CascadedPhotonPass, PoolFloorMatchesReference)
{
  // The floor under the water: the reference's camera rays pass the water, as the
  // opaque G-buffer does. Reached: flux ratio 0.9950, relative L2 0.0580 (the
  // reference's own noise at 4 M photons is about 0.04 there,
  // TestScreenSpaceAccuracy). Before the splats kept their flux at a receiver's end
  // (docs/accuracy.md), 0.9888 and 0.0691, 59 % of the squared error on the one-pixel
  // lines along the floor's and walls' corners, where the splats read 0.58 of the
  // reference; 0.9986 and 0.045 against the reference before its estimate held up to
  // one, which lost the same light. Bounds: flux within 3 %, relative L2 0.062.
  Comparison c;
  ASSERT_TRUE(c.Populate("pool"));
  ASSERT_TRUE(c.RenderFrames());
  ASSERT_TRUE(c.Compare("pool", true));
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.062);
}

TEST(CascadedPhotonPass, BallLensFromAnotherView)
{
  // A view the scene's default does not use: lower, turned and closer. Reached:
  // flux ratio 0.9975, relative L2 0.233. Bounds: 3 %, 0.25.
  Comparison c;
  ASSERT_TRUE(c.Populate("ball-lens"));
  vtkCamera* camera = c.Renderer->GetActiveCamera();
  camera->Azimuth(50.0);
  camera->Elevation(-12.0);
  camera->Dolly(1.3);
  camera->OrthogonalizeViewUp();
  c.Renderer->ResetCameraClippingRange();
  ASSERT_TRUE(c.RenderFrames());
  ASSERT_TRUE(c.Compare("ball lens, another view", false));
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.25);
}

TEST(CascadedPhotonPass, BallLensInAMedium)
{
  // A homogeneous scattering medium (0.1 /m) filling the scene: the way from the
  // light to the ball and from the ball to the floor takes its share (the reference
  // follows the same medium). Reached: flux ratio 1.0011, relative L2 0.216 (against
  // 1 M reference photons, which take 50 s with the medium). Bounds: 3 %, 0.23.
  Comparison c;
  ASSERT_TRUE(c.Populate("ball-lens"));
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.1, 0.1, 0.1);
  vtkCausticsMedium::AttachTo(c.Renderer, medium);
  ASSERT_TRUE(c.RenderFrames());
  ASSERT_TRUE(c.Compare("ball lens in a medium", false, 1000000));
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.23);
}

namespace
{
/**
 * Fig. 5 of the paper: a 45 degree mirror under a vertical sun sends its light
 * sideways onto a wall 1.5 m away, outside the light's view (aimed at the mirror,
 * 0.28 m in half width). Camera on the wall and the mirror.
 */
void MirrorAndWall(vtkRenderer* renderer)
{
  vtkNew<vtkPlaneSource> mirror;
  mirror->SetOrigin(-0.1414, 1.1414, -0.2);
  mirror->SetPoint1(0.1414, 0.8586, -0.2);
  mirror->SetPoint2(-0.1414, 1.1414, 0.2);
  mirror->Update();
  auto mirrorActor = reftest::MakeActor(mirror->GetOutput(), "mirror");
  vtkCausticsMaterial::SetRole(mirrorActor, vtkCausticsMaterial::ROLE_REFLECTOR);
  const double n[3] = { 0.16, 0.14, 0.13 }, k[3] = { 3.9, 3.2, 2.4 }; // silver-like
  vtkCausticsMaterial::SetComplexIOR(mirrorActor->GetProperty(), n, k);
  renderer->AddActor(mirrorActor);
  vtkNew<vtkPlaneSource> wall; // x = 1.5, facing -x
  wall->SetOrigin(1.5, 0.0, 1.0);
  wall->SetPoint1(1.5, 0.0, -1.0);
  wall->SetPoint2(1.5, 2.0, 1.0);
  wall->Update();
  auto wallActor = reftest::MakeActor(wall->GetOutput(), "wall");
  wallActor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  renderer->AddActor(wallActor);
  renderer->AddActor(reftest::Floor(2.0));
  renderer->AddLight(reftest::Directional(0.0, -1.0, 0.0, 2.0));
  const double position[3] = { -0.6, 1.4, 3.2 }, focal[3] = { 0.9, 0.9, 0.0 },
               up[3] = { 0.0, 1.0, 0.0 };
  reftest::SetCamera(renderer, position, focal, up, 40.0);
}
}

TEST(CascadedPhotonPass, PhotonsLeavingTheLightViewReachTheCamera)
{
  double cascade = 0.0;
  for (bool cameraStage : { true, false })
  {
    Comparison c;
    MirrorAndWall(c.Renderer);
    c.Pass->SetCameraStage(cameraStage);
    ASSERT_TRUE(c.RenderFrames());
    ASSERT_TRUE(
      c.Compare(cameraStage ? "mirror and wall, cascade" : "mirror and wall, light view only",
        false, 1000000));
    EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
    // The pass says how much of its caustic may be missing: the light lost on paths
    // it cannot follow, over what landed or was lost (LostShareBound).
    caustics::PhotonStatistics photons;
    ASSERT_TRUE(c.Pass->GetLastFramePhotonStatistics(photons));
    std::cout << "  lost, at most this share of the caustic: " << photons.LostShareBound() << "\n";
    if (cameraStage)
    {
      // Reached: flux ratio 1.0053 (relative L2 0.083); nothing lost.
      cascade = c.Metrics->GetFluxRatio();
      EXPECT_GE(cascade, 0.95);
      EXPECT_LT(cascade, 1.03);
      EXPECT_LT(photons.LostShareBound(), 0.01);
    }
    else
    {
      // The light's view alone loses the wall's caustic: reached 0 (all of it), and
      // says so (the bound covers what is missing).
      EXPECT_LT(c.Metrics->GetFluxRatio(), 0.05);
      EXPECT_LT(c.Metrics->GetFluxRatio(), cascade - 0.5);
      EXPECT_GE(photons.LostShareBound(), 1.0 - c.Metrics->GetFluxRatio() - 0.02);
    }
  }
}

namespace
{
/** The built-in bunny's Cornell box with the bunny turned into a silver mirror. */
bool MirrorBunny(Comparison& c)
{
  if (!c.Populate("bunny"))
  {
    return false;
  }
  vtkActorCollection* actors = c.Renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    if (vtkCausticsMaterial::GetName(actor) == "glass bunny")
    {
      vtkCausticsMaterial::SetRole(actor, vtkCausticsMaterial::ROLE_REFLECTOR);
      const double n[3] = { 0.16, 0.14, 0.13 }, k[3] = { 3.9, 3.2, 2.4 }; // silver-like
      vtkCausticsMaterial::SetComplexIOR(actor->GetProperty(), n, k);
      return true;
    }
  }
  return false;
}
}

// The spot's light that a mirror bunny reflects from faces the camera does not see
// reaches the walls and the floor the camera does see. Marching on from such hidden
// starts (MarchHiddenStarts, the default) keeps it; the paper's rejection (Fig. 7)
// loses it, and the pass's statistics say so (the bound covers what is missing).
TEST(CascadedPhotonPass, MarchesOnFromStartsTheCameraDoesNotSee)
{
  double flux[2] = { 0.0, 0.0 }, error[2] = { 0.0, 0.0 };
  for (bool march : { false, true })
  {
    Comparison c;
    ASSERT_TRUE(MirrorBunny(c));
    c.Pass->SetMarchHiddenStarts(march);
    ASSERT_TRUE(c.RenderFrames());
    ASSERT_TRUE(c.Compare(march ? "mirror bunny, hidden starts marched on"
                                : "mirror bunny, hidden starts dropped (Fig. 7)",
      false, 1000000));
    EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
    caustics::PhotonStatistics photons;
    ASSERT_TRUE(c.Pass->GetLastFramePhotonStatistics(photons));
    std::cout << "  lost, at most this share of the caustic: " << photons.LostShareBound() << "\n";
    flux[march] = c.Metrics->GetFluxRatio();
    error[march] = c.Metrics->GetRelativeL2Error();
    EXPECT_GE(photons.LostShareBound(), 1.0 - flux[march] - 0.02);
  }
  // Reached (4 frames, 10^6 reference photons): dropped 0.944 and 0.548 (bound 0.084),
  // marched on 0.982 and 0.512 (bound 0.010). The rest of the error is the mirror's
  // fine folds, a few photons per pixel on the walls (docs/technique-cascaded.md).
  EXPECT_GT(flux[1], flux[0] + 0.02);
  EXPECT_NEAR(flux[1], 1.0, 0.03);
  EXPECT_LT(error[1], error[0]);
  EXPECT_LT(error[1], 0.53);
}

namespace
{
/**
 * A 2 m floor under a flat water surface 6 m wide and 1 m up, the sun from +x and
 * above; the camera under the water, looking at the floor's up-sun edge (x = 1).
 */
void FloorUnderFlatWater(vtkRenderer* renderer)
{
  renderer->AddActor(reftest::Floor(1.0));
  vtkNew<vtkPlaneSource> water; // y = 1, facing up
  water->SetOrigin(-3.0, 1.0, 3.0);
  water->SetPoint1(3.0, 1.0, 3.0);
  water->SetPoint2(-3.0, 1.0, -3.0);
  water->SetResolution(8, 8);
  water->Update();
  auto waterActor = reftest::MakeActor(water->GetOutput(), "water");
  vtkCausticsMaterial::MakeGlass(waterActor->GetProperty(), 1.33);
  renderer->AddActor(waterActor);
  renderer->AddLight(reftest::Directional(-0.5, -1.0, -0.2, 1.0));
  const double position[3] = { 2.3, 0.7, 0.5 }, focal[3] = { 0.4, 0.0, 0.0 },
               up[3] = { 0.0, 1.0, 0.0 };
  reftest::SetCamera(renderer, position, focal, up, 40.0);
}
}

// Under flat water the floor's irradiance is the same everywhere. The light refracted
// into the water is steeper than the sun, so in the light's view a photon landing by
// the floor's up-sun edge passes from the floor's last texels to empty ones between two
// march samples: never behind the floor, it was lost (the march now meets the plane of
// the last texel that showed the floor). Mean irradiance of the floor's last 3 cm over
// its middle's: reached 0.976 (0.902 before). Bound: 0.95.
TEST(CascadedPhotonPass, AFloorsEdgeKeepsItsLight)
{
  Comparison c;
  FloorUnderFlatWater(c.Renderer);
  ASSERT_TRUE(c.RenderFrames());
  vtkNew<vtkImageData> position;
  ASSERT_TRUE(c.Pass->ReadBuffer("Position", position));
  vtkDataArray* where = position->GetPointData()->GetArray(0);
  vtkDataArray* caustic = c.Caustic->GetPointData()->GetArray("CausticIrradiance");
  double edge = 0.0, middle = 0.0;
  int edgePixels = 0, middlePixels = 0;
  for (vtkIdType i = 0; i < where->GetNumberOfTuples(); ++i)
  {
    const double x = where->GetComponent(i, 0), z = where->GetComponent(i, 2);
    if (where->GetComponent(i, 3) < 0.0 || std::abs(z) > 0.9)
    {
      continue;
    }
    if (x >= 0.97)
    {
      edge += caustic->GetComponent(i, 0);
      ++edgePixels;
    }
    else if (std::abs(x) <= 0.5)
    {
      middle += caustic->GetComponent(i, 0);
      ++middlePixels;
    }
  }
  ASSERT_GT(edgePixels, 200);
  ASSERT_GT(middlePixels, 200);
  const double ratio = (edge / edgePixels) / (middle / middlePixels);
  std::cout << "floor under flat water: its last 3 cm read " << ratio << " of its middle ("
            << edgePixels << " and " << middlePixels << " pixels)\n";
  EXPECT_GT(ratio, 0.95);
  EXPECT_LT(ratio, 1.05);
}

// The raw estimate's error against the splat radius and the frames averaged (not run
// by default: --gtest_also_run_disabled_tests; figures in docs/technique-cascaded.md).
TEST(CascadedPhotonPass, DISABLED_KernelSpacingsAndFrames)
{
  for (const char* scene : { "ball-lens", "pool" })
  {
    for (double spacings : { 2.0, 4.0 })
    {
      for (int frames : { 1, 4, 16 })
      {
        Comparison c;
        ASSERT_TRUE(c.Populate(scene));
        c.Pass->SetKernelSpacings(spacings);
        ASSERT_TRUE(c.RenderFrames(frames));
        const std::string what = std::string(scene) + ", KernelSpacings " +
          std::to_string(spacings).substr(0, 3) + ", " + std::to_string(frames) + " frame(s)";
        ASSERT_TRUE(c.Compare(what.c_str(), std::string(scene) == "pool"));
      }
    }
  }
}
