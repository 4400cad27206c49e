// The CPU technique (vtkCausticsProgressivePhotonPass, "cpu-progressive"): it is
// known by name once registered, its estimate converges to the reference's while
// nothing moves, it starts again when anything changes, and it stops tracing at
// MaximumFrames. A frame renders no light buffers.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsDeviceLimits.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsProgressivePhotonPass.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkDataArray.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace
{
struct CPUFrame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  vtkNew<vtkCausticsProgressivePhotonPass> Pass;

  explicit CPUFrame(int size)
  {
    EXPECT_TRUE(this->Scene->Populate(this->Renderer));
    this->Pass->SetLightBufferResolution(96); // 9216 photons a frame
    this->Pass->KeepBuffersOn();
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
  }
  ~CPUFrame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }

  vtkSmartPointer<vtkImageData> Caustic()
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    EXPECT_TRUE(this->Pass->ReadBuffer("CausticIrradiance", image));
    return image;
  }
};

/** Relative L2 and flux ratio of `image` against the reference of the frame's scene. */
void Compare(vtkRenderer* renderer, vtkImageData* image, int size, double& l2, double& flux)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(size, size);
  reference->SetPhotonsPerLight(2000000);
  reference->CameraSeesRefractorsOff(); // the opaque surfaces, as the passes' buffers
  ASSERT_TRUE(reference->Update()) << reference->GetLastError();
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetArrayName("CausticIrradiance");
  metrics->SetMaskArrayName("ReceiverMask");
  metrics->SetAreaArrayName("PixelArea");
  ASSERT_TRUE(metrics->Compute(image, reference->GetOutput()));
  l2 = metrics->GetRelativeL2Error();
  flux = metrics->GetFluxRatio();
}
}

TEST(ProgressivePhotonPass, IsKnownByNameOnceRegistered)
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique();
  vtkCausticsProgressivePhotonPass::RegisterTechnique(); // twice: still one entry
  const auto names = vtkCausticsTechniques::GetNames();
  EXPECT_EQ(std::count(names.begin(), names.end(), "cpu-progressive"), 1);
  EXPECT_TRUE(vtkCausticsProgressivePhotonPass::SafeDownCast(
    vtkCausticsTechniques::Create("cpu-progressive")));
  EXPECT_NE(vtkCausticsTechniques::Describe().find("cpu-progressive: "), std::string::npos);
}

// Sixteen frames of 9216 photons: the estimate of 147456, whose noise is a quarter
// of one frame's; the kernel is the reference's, so nothing but noise separates them.
TEST(ProgressivePhotonPass, ConvergesWhileStillAndStartsAgainOnAnyChange)
{
  const int size = 96;
  CPUFrame f(size);
  f.Window->Render();
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 1);
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedPhotons(), 96 * 96);
  vtkCausticsTimings* timings = f.Pass->GetTimings();
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    EXPECT_FALSE(std::string(timings->GetStageName(i)) == "light buffers" && timings->GetStageRan(i))
      << "traced on the CPU: no light buffers";
  }
  double first = 0.0, firstFlux = 0.0;
  Compare(f.Renderer, f.Caustic(), size, first, firstFlux);
  for (int frame = 2; frame <= 16; ++frame)
  {
    f.Window->Render();
  }
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 16);
  double sixteen = 0.0, flux = 0.0;
  Compare(f.Renderer, f.Caustic(), size, sixteen, flux);
  std::cout << "relative L2 after 1 frame " << first << ", after 16 " << sixteen << "; flux "
            << firstFlux << ", " << flux << "\n";
  EXPECT_LT(sixteen, 0.4 * first);
  EXPECT_NEAR(flux, 1.0, 0.02);

  // The camera moves: the next frame starts again.
  f.Renderer->GetActiveCamera()->Azimuth(5.0);
  f.Window->Render();
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 1);
  f.Window->Render();
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 2);
  // The light changes.
  auto* sun = vtkLight::SafeDownCast(f.Renderer->GetLights()->GetItemAsObject(0));
  sun->SetIntensity(2.0);
  f.Window->Render();
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 1);
  // A user's restart.
  f.Pass->Restart();
  f.Window->Render();
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 1);
}

TEST(ProgressivePhotonPass, StopsTracingAtMaximumFramesAndKeepsTheEstimate)
{
  CPUFrame f(64);
  f.Pass->SetMaximumFrames(2);
  for (int frame = 0; frame < 4; ++frame)
  {
    f.Window->Render();
  }
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 2);
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedPhotons(), 2 * 96 * 96);
  vtkCausticsTimings* timings = f.Pass->GetTimings();
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    EXPECT_FALSE(
      std::string(timings->GetStageName(i)) == "cpu photon tracing" && timings->GetStageRan(i))
      << "converged: nothing traced";
  }
  double total = 0.0;
  vtkSmartPointer<vtkImageData> caustic = f.Caustic();
  for (vtkIdType p = 0; p < 64 * 64; ++p)
  {
    total += caustic->GetPointData()->GetArray(0)->GetComponent(p, 0);
  }
  EXPECT_GT(total, 0.0) << "the estimate stays on screen";

  // Not progressive: every frame one independent estimate (a new seed), so a
  // still scene shows the estimate's own noise, with the same expected flux.
  f.Pass->ProgressiveOff();
  f.Window->Render();
  vtkSmartPointer<vtkImageData> first = f.Caustic();
  f.Window->Render();
  EXPECT_EQ(f.Pass->GetNumberOfAccumulatedFrames(), 1);
  vtkSmartPointer<vtkImageData> second = f.Caustic();
  double sumFirst = 0.0, sumSecond = 0.0, differing = 0.0;
  for (vtkIdType p = 0; p < 64 * 64; ++p)
  {
    const double a = first->GetPointData()->GetArray(0)->GetComponent(p, 0);
    const double b = second->GetPointData()->GetArray(0)->GetComponent(p, 0);
    sumFirst += a;
    sumSecond += b;
    differing += a != b ? 1.0 : 0.0;
  }
  EXPECT_GT(differing, 0.0) << "two frames of a still scene drew the same photons";
  EXPECT_NEAR(sumSecond / sumFirst, 1.0, 0.05);
}

// "best" without a GPU (docs/benchmarks.md, "Which technique is best"): the CPU
// technique for mirrors, open water and concave glass, caustic maps for a convex
// refractor alone; not in a scattering medium (its volume caustic is not measured
// against the GPU's). With a GPU, the GPU rule.
TEST(ProgressivePhotonPass, BestTakesItWithoutAGPU)
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique();
  for (const auto& [name, gpu, cpu] : std::vector<std::array<std::string, 3>>{
         { "ball-lens", "caustic-maps", "caustic-maps" },
         { "pool", "caustic-maps", "cpu-progressive" }, { "ring", "screen-space", "cpu-progressive" },
         { "bunny", "caustic-maps", "cpu-progressive" },
         { "underwater", "caustic-maps", "caustic-maps" } })
  {
    vtkNew<vtkOpenGLRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetSize(32, 32);
    window->AddRenderer(renderer);
    vtkNew<vtkCausticsBuiltinScene> scene;
    scene->SetSceneName(name.c_str());
    ASSERT_TRUE(scene->Populate(renderer));
    const bool software = caustics::gl::IsSoftwareOpenGL(window);
    EXPECT_EQ(vtkCausticsTechniques::GetBestNameFor(renderer), software ? cpu : gpu) << name;
  }
}
