// God-rays of screen-space photon tracing (§3.2 of 000_54cf099eeccf42d9.txt, in
// physical units: lines of in-scattered radiance, W/(m^2 sr), blurred by a
// normalized Gaussian) against the reference renderer's volume caustic (photon
// beams with an exact beam radiance estimate, docs/reference.md): the ball lens in
// a homogeneous medium (sigma_s 0.05/m, sigma_a 0.01/m, isotropic). Compared over
// every pixel, without areas (radiance: the flux ratio is the ratio of the mean
// radiances, i.e. of the light scattered towards the camera).
#include "vtkCausticsAirlight.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpacePhotonPass.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

TEST(ScreenSpaceGodRays, MatchReferenceVolumeCaustic)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  ASSERT_TRUE(scene->Populate(renderer));
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.05, 0.05, 0.05);
  medium->SetAbsorptionCoefficient(0.01, 0.01, 0.01);
  vtkCausticsMedium::AttachTo(renderer, medium);
  vtkNew<vtkCausticsScreenSpacePhotonPass> pass;
  pass->GetAirlight()->EnabledOff(); // the volume caustic alone (the airlight: TestAirlight)
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(256, 256);
  window->AddRenderer(renderer);
  window->Render();
  ASSERT_TRUE(pass->GetLastFrameHadCaustics());
  vtkNew<vtkImageData> volume;
  ASSERT_TRUE(pass->ReadBuffer("VolumeRadiance", volume));
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetPhotonsPerLight(100000);
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetArrayName("VolumeRadiance");
  // The GPU's array is "VolumeRadiance"; the reference's volume caustic alone:
  vtkImageData* ref = reference->GetOutput();
  vtkNew<vtkImageData> target;
  target->ShallowCopy(ref);
  vtkDataArray* caustic = ref->GetPointData()->GetArray("VolumeCausticRadiance");
  ASSERT_NE(caustic, nullptr);
  vtkSmartPointer<vtkDataArray> copy;
  copy.TakeReference(caustic->NewInstance());
  copy->DeepCopy(caustic);
  copy->SetName("VolumeRadiance");
  target->GetPointData()->RemoveArray("VolumeRadiance");
  target->GetPointData()->AddArray(copy);
  ASSERT_TRUE(metrics->Compute(volume, target));
  std::cout << "god-rays: " << metrics->GetSummary() << "\n";
  // Reached: mean radiance ratio 0.992, relative L2 0.225, peak 2.2 px. The
  // per-pixel error is dominated by the two different kernels (a 1.5 px Gaussian
  // in screen space against 1.5 pixel footprints across each beam) and the
  // reference's 100 000 volume photons. Bounds: 2% on the mean (0.8% + the
  // reference's noise), 0.30 relative L2, 4 px on the peak.
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 0.02);
  EXPECT_LT(metrics->GetRelativeL2Error(), 0.30);
  EXPECT_LE(metrics->GetPeakPositionError(), 4.0);

  // Without a medium (or with god-rays off) there is no volume radiance at all.
  pass->GodRaysOff();
  window->Render();
  vtkNew<vtkImageData> none;
  pass->GlobalWarningDisplayOff();
  EXPECT_FALSE(pass->ReadBuffer("VolumeRadiance", none));
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}

// An absorption-only medium dims the caustic like any other extinction: it was
// ignored (no attenuation at all) until some scattering was set, when 1e-6/m of
// scattering suddenly attenuated the caustic 13-fold; and the caustic maps ignored
// media altogether. Now sigma_a = 1/m alone and sigma_s = 1e-6/m beside it give the
// same caustic, dimmer than without a medium, and both techniques lose the same
// share of it (the photons' air paths are the same light).
double CausticSum(vtkCausticsRenderPass* pass, double scattering, double absorption)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  EXPECT_TRUE(scene->Populate(renderer));
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(scattering, scattering, scattering);
  medium->SetAbsorptionCoefficient(absorption, absorption, absorption);
  if (scattering + absorption > 0.0)
  {
    vtkCausticsMedium::AttachTo(renderer, medium);
  }
  renderer->SetPass(pass);
  pass->KeepBuffersOn();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(128, 128);
  window->AddRenderer(renderer);
  window->Render();
  EXPECT_TRUE(pass->GetLastFrameHadCaustics());
  vtkNew<vtkImageData> caustic;
  EXPECT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic));
  vtkDataArray* values = caustic->GetPointData()->GetArray(0);
  double sum = 0.0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    sum += values->GetComponent(i, 0);
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return sum;
}

TEST(ScreenSpaceGodRays, AbsorptionAloneAttenuates)
{
  vtkNew<vtkCausticsScreenSpacePhotonPass> screenSpace;
  vtkNew<vtkCausticsHierarchicalCausticMapPass> causticMaps;
  double kept[2];
  int k = 0;
  for (vtkCausticsRenderPass* pass : { static_cast<vtkCausticsRenderPass*>(screenSpace),
         static_cast<vtkCausticsRenderPass*>(causticMaps) })
  {
    const double clear = CausticSum(pass, 0.0, 0.0);
    const double absorbing = CausticSum(pass, 0.0, 1.0);
    const double almost = CausticSum(pass, 1e-6, 1.0);
    std::cout << pass->GetClassName() << " caustic sum: clear " << clear << ", sigma_a 1/m "
              << absorbing << ", + sigma_s 1e-6/m " << almost << "\n";
    ASSERT_GT(clear, 0.0);
    EXPECT_LT(absorbing, 0.9 * clear);
    EXPECT_NEAR(absorbing / almost, 1.0, 1e-3);
    kept[k++] = absorbing / clear;
  }
  EXPECT_NEAR(kept[1] / kept[0], 1.0, 0.05);
}

// Issue 18: direct light reaches a surface through the medium, attenuated by it,
// as the reference's DirectIrradiance has it (inside the medium's box, the scene's
// bounds). Ball lens, vertical sun, sigma_a = 0.1/m: the floor is 4 m below the
// box's top, so a lit floor point keeps exp(-0.4) = 0.670 of the clear value.
TEST(ScreenSpaceGodRays, DirectLightIsAttenuatedByTheMedium)
{
  double mean[2] = { 0.0, 0.0 }, reference = 0.0;
  for (int absorbing = 0; absorbing < 2; ++absorbing)
  {
    vtkNew<vtkOpenGLRenderer> renderer;
    vtkNew<vtkCausticsBuiltinScene> scene;
    ASSERT_TRUE(scene->Populate(renderer));
    vtkNew<vtkCausticsMedium> medium;
    medium->SetAbsorptionCoefficient(0.1, 0.1, 0.1);
    if (absorbing)
    {
      vtkCausticsMedium::AttachTo(renderer, medium);
    }
    vtkNew<vtkCausticsRenderPass> pass;
    pass->KeepBuffersOn();
    pass->ComputeDirectIrradianceOn();
    renderer->SetPass(pass);
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(128, 128);
    window->AddRenderer(renderer);
    window->Render();
    vtkNew<vtkImageData> direct;
    ASSERT_TRUE(pass->ReadBuffer("DirectIrradiance", direct));
    vtkNew<vtkCausticsReferenceRenderer> truth;
    truth->SetInputRenderer(renderer);
    truth->SetImageSize(128, 128);
    truth->SetPhotonsPerLight(10000);
    ASSERT_TRUE(truth->Update()) << truth->GetLastError();
    vtkDataArray* gpu = direct->GetPointData()->GetArray(0);
    vtkDataArray* cpu = truth->GetOutput()->GetPointData()->GetArray("DirectIrradiance");
    vtkDataArray* mask = truth->GetOutput()->GetPointData()->GetArray("ReceiverMask");
    // Lit floor pixels (away from the ball's shadow and its edge).
    double sum = 0.0, sumReference = 0.0;
    int count = 0;
    for (vtkIdType i = 0; i < gpu->GetNumberOfTuples(); ++i)
    {
      if (mask->GetComponent(i, 0) > 0.5 && cpu->GetComponent(i, 0) > 0.5 &&
        gpu->GetComponent(i, 0) > 0.5)
      {
        sum += gpu->GetComponent(i, 0);
        sumReference += cpu->GetComponent(i, 0);
        ++count;
      }
    }
    ASSERT_GT(count, 1000);
    mean[absorbing] = sum / count;
    reference = sumReference / count;
    std::cout << (absorbing ? "sigma_a 0.1/m" : "clear") << ": direct irradiance on lit floor "
              << mean[absorbing] << " W/m^2, reference " << reference << "\n";
    EXPECT_NEAR(mean[absorbing] / reference, 1.0, 0.01);
    renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(window);
  }
  EXPECT_NEAR(mean[1] / mean[0], std::exp(-0.4), 0.01);
}
