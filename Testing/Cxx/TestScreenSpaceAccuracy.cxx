// Screen-space photon tracing (vtkCausticsScreenSpacePhotonPass) against the CPU
// reference renderer (vtkCausticsReferenceRenderer, docs/reference.md) with the
// metrics of docs/accuracy.md, at 256^2 pixels and the pass's default settings
// (256^2 light-buffer texels per light, 8 layers, 3 bounces):
// - ball lens: total caustic flux, relative L2 error of the caustic irradiance,
//   caustic peak position;
// - pool: relative L2 error of the floor's caustic irradiance under the water (the
//   reference's camera rays pass through the water, as the opaque G-buffer does);
// - shadow rays traced in screen space (§5, Fig. 11) against the reference's
//   shadows: fraction of receiver pixels classified differently.
// The figures reached are printed; each bound is the figure reached plus a margin
// for the reference's noise and for rasterization differences between GPUs.
#include "TestReferenceUtilities.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsScreenSpaceRefraction.h"

#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
/** A built-in scene, its screen-space caustics and its reference. */
struct Comparison
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  vtkNew<vtkCausticsScreenSpacePhotonPass> Pass;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkImageData> Caustic;
  vtkNew<vtkCausticsReferenceRenderer> Reference;
  vtkNew<vtkCausticsErrorMetrics> Metrics;

  Comparison(const char* scene, vtkIdType photons, bool throughRefractors,
    int traceView = vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_AUTOMATIC,
    int exactSpecular = vtkCausticsScreenSpaceRefraction::EXACT_AUTOMATIC)
  {
    this->Scene->SetSceneName(scene);
    EXPECT_TRUE(this->Scene->Populate(this->Renderer)) << this->Scene->GetLastError();
    this->Pass->SetTraceView(traceView);
    this->Pass->GetScreenSpaceRefraction()->SetExactSpecularGeometry(exactSpecular);
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(256, 256);
    this->Window->AddRenderer(this->Renderer);
    this->Window->Render();
    EXPECT_TRUE(this->Pass->GetLastFrameHadCaustics());
    EXPECT_TRUE(this->Pass->ReadBuffer("CausticIrradiance", this->Caustic));
    this->Reference->SetInputRenderer(this->Renderer);
    this->Reference->SetImageSize(256, 256);
    this->Reference->SetPhotonsPerLight(photons);
    this->Reference->SetCameraSeesRefractors(!throughRefractors);
    EXPECT_TRUE(this->Reference->Update()) << this->Reference->GetLastError();
    this->Metrics->SetMaskArrayName("ReceiverMask");
    this->Metrics->SetAreaArrayName("PixelArea");
  }
  ~Comparison()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  bool Compare()
  {
    const bool ok = this->Metrics->Compute(this->Caustic, this->Reference->GetOutput());
    std::cout << this->Scene->GetSceneName() << ": " << this->Metrics->GetSummary() << "\n";
    return ok;
  }
};
}

// Reached (this machine, llvmpipe): flux ratio 0.995, relative L2 0.050, peak 2 px.
// The reference's own noise at 4 M photons is ~0.3% in relative L2 (docs/reference.md:
// 0.62% at 1 M, falling as 1/sqrt(N)). Bounds: flux within 1.5% (the 3% of the issue
// tightened: 0.5% reached + 1% for GPU differences), relative L2 0.07 (0.05 + 0.02),
// peak 2 px (the bound; reached 2 px: one pixel of quantization on each axis).
TEST(ScreenSpaceAccuracy, BallLensMatchesReference)
{
  Comparison c("ball-lens", 4000000, false);
  ASSERT_TRUE(c.Compare());
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.015);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.07);
  EXPECT_LE(c.Metrics->GetPeakPositionError(), 2.0);
  // Where the photons' light went (docs/accuracy.md, "Light a technique cannot
  // follow"). Reached: 87.7 % landed, 11.2 % left the view, 1.1 % lost at the bounce
  // limit (1.2 % of what landed or was lost). Clear glass keeps every photon's flux
  // (one Fresnel branch, chosen by its probability): the fates add up exactly, but
  // for the counters' rounding.
  caustics::PhotonStatistics photons;
  ASSERT_TRUE(c.Pass->GetLastFramePhotonStatistics(photons));
  EXPECT_GT(photons.Photons, 0);
  EXPECT_NEAR(
    (photons.FluxHits + photons.FluxEscaped + photons.FluxLostInside) / photons.FluxIn, 1.0, 1e-3);
  EXPECT_LT(photons.LostShareBound(), 0.02);
}

// Reached: relative L2 0.041 on the floor under the water (flux ratio 0.995); 0.046
// before the first-hit reduction tested the receivers around the row's hit (photons
// ending on the floor along a wall's foot landed on the wall), 0.062 and 0.988 before
// the splats kept their flux at a receiver's end (docs/accuracy.md), 0.023 and 0.998
// against the reference before its estimate held up to one, which lost the same light
// along the floor's and walls' corners. The reference at 4 M photons has ~4% noise
// there (docs/benchmarks.md: 8.4% at 1 M, 2.4% at 10 M photons against 20 M), part of
// what is reached; bound 0.05 (the issue asked for 0.20).
TEST(ScreenSpaceAccuracy, PoolFloorMatchesReference)
{
  Comparison c("pool", 4000000, true);
  ASSERT_TRUE(c.Compare());
  EXPECT_EQ(c.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(c.Metrics->GetRelativeL2Error(), 0.05);
  EXPECT_NEAR(c.Metrics->GetFluxRatio(), 1.0, 0.03);
}

// The glass bunny (not a convex solid): photons inside it go from triangle to triangle
// (vtkCausticsSpecularHierarchy, as the camera view traces it) instead of through the
// refractor layers of the trace view, which lose its ears and hollows and every exit
// off the screen; inside, up to the reference's 8 events a path. Reached: relative L2
// 36.1 %, flux 1.013 (36.2 % and 0.988 before the splats kept their flux at the box's
// corners and along the image's border); through the layers 53.0 % and 0.667. Bounds
// just above; the layers must stay measurably worse (a trace that stops working fails
// it).
TEST(ScreenSpaceAccuracy, ConcaveGlassTracedAsTriangles)
{
  Comparison traced("bunny", 1000000, false);
  ASSERT_TRUE(traced.Compare());
  Comparison layers("bunny", 1000000, false,
    vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_AUTOMATIC,
    vtkCausticsScreenSpaceRefraction::EXACT_OFF);
  ASSERT_TRUE(layers.Compare());
  EXPECT_EQ(traced.Metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_LT(traced.Metrics->GetRelativeL2Error(), 0.365);
  EXPECT_NEAR(traced.Metrics->GetFluxRatio(), 1.0, 0.015);
  EXPECT_LT(traced.Metrics->GetRelativeL2Error(), 0.75 * layers.Metrics->GetRelativeL2Error());
}

// §5, Fig. 11: for every receiver pixel, a shadow ray towards the light traced in
// screen space through the layered depth image, against the reference's direct
// irradiance (every mesh, glass included, casts shadows there): a pixel is in the
// reference's shadow when it gets less than half of the irradiance the light would
// give it unshadowed.
TEST(ScreenSpaceAccuracy, ShadowRaysMatchReferenceShadows)
{
  // Reached in the camera's view (the paper's): ball lens 0.11%, ring 0.75%,
  // bunny 0.40% (errors sit on the shadows' edges, one pixel wide). Bounds: about
  // 1.5x the figure reached, at least 0.3%.
  // The default view of the ball lens cuts the top of the ball, so by default the
  // frame traces in the fitted view (vtkCausticsTraceView.h), which looks half-way
  // to the light: shadow rays, which run along the light, are then shorter on
  // screen. Reached there: 1.13% (ring and bunny: their views hold every specular
  // actor, so the camera's). Bound 1.5%.
  struct Case
  {
    const char* Scene;
    int TraceView;
    double Bound;
  };
  const int camera = vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_CAMERA;
  const int automatic = vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_AUTOMATIC;
  for (const Case& test : { Case{ "ball-lens", camera, 0.003 }, Case{ "ring", camera, 0.012 },
         Case{ "bunny", camera, 0.006 }, Case{ "ball-lens", automatic, 0.015 } })
  {
    const char* scene = test.Scene;
    Comparison c(scene, 10000, false, test.TraceView);
    vtkNew<vtkImageData> shadow;
    ASSERT_TRUE(c.Pass->TraceShadowRays(0, shadow));
    vtkDataArray* traced = shadow->GetPointData()->GetArray("Shadow");
    vtkImageData* reference = c.Reference->GetOutput();
    vtkDataArray* direct = reference->GetPointData()->GetArray("DirectIrradiance");
    vtkDataArray* mask = reference->GetPointData()->GetArray("ReceiverMask");
    vtkDataArray* position = reference->GetPointData()->GetArray("Position");
    vtkDataArray* normal = reference->GetPointData()->GetArray("Normal");
    const caustics::Light& light = c.Reference->GetScene().Lights[0];
    // The irradiance the light would give each pixel unshadowed (cosine, 1/r^2,
    // spot falloff): pixels it cannot light (outside the spot's cone, facing away)
    // are not judged, nor those lit at less than 1% of the brightest (grazing).
    std::vector<double> unshadowed(direct->GetNumberOfTuples(), 0.0);
    double brightest = 0.0;
    for (vtkIdType i = 0; i < direct->GetNumberOfTuples(); ++i)
    {
      double p[3], n[3], towards[3], distance2 = 1.0;
      position->GetTuple(i, p);
      normal->GetTuple(i, n);
      for (int k = 0; k < 3; ++k)
      {
        towards[k] = light.type == caustics::Light::Type::Directional ? -light.direction[k]
                                                                      : light.position[k] - p[k];
      }
      if (light.type != caustics::Light::Type::Directional)
      {
        distance2 = towards[0] * towards[0] + towards[1] * towards[1] + towards[2] * towards[2];
        for (double& v : towards)
        {
          v /= std::sqrt(distance2);
        }
      }
      const double cosine = n[0] * towards[0] + n[1] * towards[1] + n[2] * towards[2];
      double spot = 1.0;
      if (light.type == caustics::Light::Type::Spot)
      {
        spot = light.SpotFactor(-(towards[0] * light.direction[0] +
          towards[1] * light.direction[1] + towards[2] * light.direction[2]));
      }
      unshadowed[i] = std::max(0.0, cosine) * spot / distance2;
      brightest = std::max(brightest, unshadowed[i]);
    }
    int judged = 0, wrong = 0, shadowed = 0;
    for (vtkIdType i = 0; i < direct->GetNumberOfTuples(); ++i)
    {
      if (mask->GetComponent(i, 0) == 0.0 || traced->GetComponent(i, 0) < 0.0 ||
        unshadowed[i] < 0.01 * brightest)
      {
        continue;
      }
      // Shadowed: less than half of the unshadowed irradiance reaches the pixel.
      const double scale = light.radiometric[0];
      const bool referenceShadowed = direct->GetComponent(i, 0) < 0.5 * scale * unshadowed[i];
      ++judged;
      shadowed += referenceShadowed ? 1 : 0;
      wrong += referenceShadowed != (traced->GetComponent(i, 0) > 0.5) ? 1 : 0;
    }
    const double fraction = static_cast<double>(wrong) / std::max(judged, 1);
    std::cout << scene << (c.Pass->GetLastTraceViewFitted() ? " (fitted view)" : "")
              << ": shadow rays misclassify " << wrong << " of " << judged
              << " receiver pixels (" << 100.0 * fraction << " %), " << shadowed
              << " in the reference's shadow\n";
    ASSERT_GT(judged, 10000);
    EXPECT_GT(shadowed, 100) << "the scene must cast a shadow for the test to mean anything";
    EXPECT_LT(fraction, test.Bound) << scene;
  }
}

// A ray that passes just beyond a receiver's end meets the tangent plane of the
// receiver's last pixels within a sample's reach, and used to land there, on nothing:
// photons piled up along every end the light passes. Scene (none of the built-in
// ones): a 2 m floor and a 1 m back wall along its far edge under a 10 cm glass slab,
// sun along (-0.35, -1, -0.45), seen from (0.6, 1, 2.2) towards (-0.3, 0.2, -0.5)
// through 40 degrees, so that the wall's top edge is in view with nothing behind it.
// The wall's four top pixel rows against the reference, in the fitted trace view (the
// slab reaches past the camera's view) and in the camera's own. Reached: 0.975 and
// 1.000, the top row 1.07 and 1.10; 1.38 and 1.19 before, the top row 1.76 and 1.41.
// Bounds: 6 % for the four rows, 15 % for the top one.
TEST(ScreenSpaceAccuracy, NoLightPastAReceiversEnd)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  renderer->AddActor(reftest::Floor(1.0));
  vtkNew<vtkPlaneSource> wallPlane;
  wallPlane->SetOrigin(-1, 0, -1);
  wallPlane->SetPoint1(1, 0, -1);
  wallPlane->SetPoint2(-1, 1, -1); // normal +z, towards the camera
  wallPlane->Update();
  auto wall = reftest::MakeActor(wallPlane->GetOutput(), "back wall");
  wall->GetProperty()->SetColor(0.8, 0.8, 0.8);
  renderer->AddActor(wall);
  vtkNew<vtkCubeSource> slabBox;
  slabBox->SetBounds(-2, 2, 1.2, 1.3, -2, 2);
  vtkNew<vtkTriangleFilter> slabTriangles;
  slabTriangles->SetInputConnection(slabBox->GetOutputPort());
  slabTriangles->Update();
  auto slab = reftest::MakeActor(slabTriangles->GetOutput(), "slab");
  vtkCausticsMaterial::MakeGlass(slab->GetProperty(), 1.5);
  renderer->AddActor(slab);
  renderer->AddLight(reftest::Directional(-0.35, -1.0, -0.45, 1.0));
  const double eye[3] = { 0.6, 1.0, 2.2 }, focal[3] = { -0.3, 0.2, -0.5 }, up[3] = { 0, 1, 0 };
  reftest::SetCamera(renderer, eye, focal, up, 40.0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(256, 256);
  window->AddRenderer(renderer);
  auto reference = reftest::MakeReference(renderer, 256, 256, 2000000);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkImageData* truth = reference->GetOutput();
  for (int traceView : { vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_AUTOMATIC,
         vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_CAMERA })
  {
    vtkNew<vtkCausticsScreenSpacePhotonPass> pass;
    pass->SetTraceView(traceView);
    renderer->SetPass(pass);
    window->Render();
    vtkNew<vtkImageData> caustic;
    ASSERT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic));
    // Per column, the wall's top row is the highest receiver pixel (j from the bottom).
    double rows[4] = { 0, 0, 0, 0 }, truthRows[4] = { 0, 0, 0, 0 };
    for (int i = 110; i < 240; ++i)
    {
      int top = -1;
      for (int j = 255; j >= 0 && top < 0; --j)
      {
        top = reftest::At(truth, "ReceiverMask", i, j) > 0.5 ? j : -1;
      }
      ASSERT_GE(top, 4) << "column " << i << " shows no wall";
      for (int k = 0; k < 4; ++k)
      {
        rows[k] += reftest::At(caustic, "CausticIrradiance", i, top - k);
        truthRows[k] += reftest::At(truth, "CausticIrradiance", i, top - k);
      }
    }
    const double ratio = (rows[0] + rows[1] + rows[2] + rows[3]) /
      (truthRows[0] + truthRows[1] + truthRows[2] + truthRows[3]);
    std::cout << (pass->GetLastTraceViewFitted() ? "fitted" : "camera")
              << " trace view: the wall's top rows against the reference " << rows[0] / truthRows[0]
              << " " << rows[1] / truthRows[1] << " " << rows[2] / truthRows[2] << " "
              << rows[3] / truthRows[3] << ", together " << ratio << "\n";
    EXPECT_EQ(pass->GetLastTraceViewFitted(),
      traceView == vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_AUTOMATIC);
    // The camera's view, asked for, misses a specular actor here (and warns).
    EXPECT_EQ(pass->GetLastTraceViewMissedSpecular(),
      traceView == vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_CAMERA);
    EXPECT_NEAR(ratio, 1.0, 0.06);
    EXPECT_NEAR(rows[0] / truthRows[0], 1.0, 0.15) << "the top row";
    renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(window);
  }
}
