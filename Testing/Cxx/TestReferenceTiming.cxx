// Timings and convergence of the reference on the built-in ball-lens scene at 256 x 256,
// for docs/reference.md. Disabled in CI (minutes on 2 cores); run them with
//   build-<name>/bin/TestReference --gtest_also_run_disabled_tests
//     --gtest_filter='ReferenceTiming.*'
#include "TestReferenceUtilities.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsMedium.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

namespace
{
vtkSmartPointer<vtkCausticsReferenceRenderer> Render(
  vtkRenderer* renderer, vtkIdType photons, vtkIdType volumePhotons = 100000)
{
  auto reference = reftest::MakeReference(renderer, 256, 256, photons);
  reference->SetVolumePhotonsPerLight(volumePhotons);
  EXPECT_TRUE(reference->Update()) << reference->GetLastError();
  const auto& s = reference->GetStatistics();
  std::printf("%10lld photons: %7.2f s (photons %6.2f, view %6.2f, volume %6.2f), "
              "%lld deposits, %lld beams\n",
    static_cast<long long>(reference->GetNumberOfPhotonsEmitted()), reference->GetWallTime(),
    s.photonSeconds, s.viewSeconds, s.volumeSeconds,
    static_cast<long long>(reference->GetNumberOfPhotonsDeposited()),
    static_cast<long long>(reference->GetNumberOfBeams()));
  return reference;
}

/** Relative L2 difference of CausticIrradiance over receiver pixels. */
double RelativeL2(vtkImageData* test, vtkImageData* truth)
{
  double diff = 0.0, norm = 0.0;
  vtkDataArray* t = test->GetPointData()->GetArray("CausticIrradiance");
  vtkDataArray* r = truth->GetPointData()->GetArray("CausticIrradiance");
  vtkDataArray* mask = truth->GetPointData()->GetArray("ReceiverMask");
  for (vtkIdType p = 0; p < t->GetNumberOfTuples(); ++p)
  {
    if (mask->GetComponent(p, 0) == 0.0)
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      diff += std::pow(t->GetComponent(p, c) - r->GetComponent(p, c), 2);
      norm += std::pow(r->GetComponent(p, c), 2);
    }
  }
  return std::sqrt(diff / norm);
}
}

TEST(ReferenceTiming, DISABLED_BallLens256)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  ASSERT_TRUE(scene->Populate(renderer));
  std::printf("ball-lens, 256 x 256, %u hardware threads, default settings\n",
    std::thread::hardware_concurrency());
  for (vtkIdType photons : { 100000, 1000000, 4000000 })
  {
    Render(renderer, photons);
  }
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.05, 0.05, 0.05);
  medium->SetAbsorptionCoefficient(0.01, 0.01, 0.01);
  medium->SetAnisotropy(0.3);
  vtkCausticsMedium::AttachTo(renderer, medium);
  std::printf("ball-lens in fog (sigma_s 0.05/m, sigma_a 0.01/m, g 0.3), 256 x 256, 1 M "
              "surface photons and 25 k, 100 k (default), 400 k volume photons\n");
  for (vtkIdType volumePhotons : { 25000, 100000, 400000 })
  {
    Render(renderer, 1000000, volumePhotons);
  }
}

TEST(ReferenceTiming, DISABLED_BallLensConvergence)
{
  // Caustic irradiance at N photons against 16 M photons, same kernel rule (2 pixel
  // footprints): the error falls as the photon count grows.
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  ASSERT_TRUE(scene->Populate(renderer));
  auto truth = Render(renderer, 16000000);
  std::printf("relative L2 error of CausticIrradiance against 16 M photons:\n");
  for (vtkIdType photons : { 62500, 250000, 1000000, 4000000 })
  {
    auto test = Render(renderer, photons);
    std::printf("  %8lld photons: %.4f\n", static_cast<long long>(photons),
      RelativeL2(test->GetOutput(), truth->GetOutput()));
  }
}
