// Line-based volume caustics (vtkCausticsVolumeLines, 003_653219b45420e98f.txt §4-5)
// fed by the screen-space, caustic-map and cascaded techniques, on the two built-in
// media scenes (smoke-lens: a
// smoke density grid lit through a glass ball; underwater: a plankton density grid
// under the pool's water surface), against the reference renderer's volume caustic
// (photon beams with an exact beam radiance estimate, VolumeCausticRadiance, not the
// airlight): the total (the mean radiance ratio) and the relative L2, one render per
// scene (underwater: the pass's default blur against the reference filtered to the
// same resolution, ReferenceMatchingBlur); and the re-sampled optical depth
// (sub-segments) against the per-fragment march it replaces, with the time of both;
// and no volume stage without a medium.
#include "vtkCausticsAirlight.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsDeviceLimits.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsImpostorPhotonPass.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsVolumeSegmentList.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtk_glew.h" // For glGetInteger64v

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
// 128^2 pixels and photons: a 256^2 smoke-lens frame alone costs more than the
// budget of these tests on llvmpipe.
constexpr int ImageSize = 128;
constexpr int LightBufferResolution = 128;
// The reference spreads each beam with an Epanechnikov kernel of radius 1.5 pixel
// footprints (VolumeKernelRadiusPixels), whose standard deviation per axis is
// 1.5 / sqrt(6) = 0.61 px; the pass's Gaussian gets the same width (its default, 1.5 px,
// is 2.4 times wider: relative L2 0.219 instead of 0.096 on smoke-lens).
const double ReferenceKernelPixels = 1.5;
const double MatchedBlurPixels = ReferenceKernelPixels / std::sqrt(6.0);
// The pass's default Gaussian (vtkCausticsVolumeLines::Finish()).
const double DefaultBlurPixels = 1.5;
// The reference's volume photons: 200 000 for smoke-lens, where the narrow kernel's
// comparison holds (its noise at 128^2: docs/technique-volume-caustics.md). Underwater's
// comparison at 256^2 takes 1 000 000: one seed's noise at the default blur's resolution
// is then 2.3 % (1.9 % with 2 000 000, 4.2 % with 200 000; scripts/volume-error-map.py),
// well under the 10 % of issue 14, for about 15-40 s of reference on 2 cores.
constexpr int ReferenceVolumePhotons = 200000;
constexpr int UnderwaterVolumePhotons = 1000000;

/** A scene's volume radiance from a technique and the time of its volume stages. */
struct VolumeFrame
{
  vtkSmartPointer<vtkImageData> Volume; ///< null when the frame wrote no volume layer
  double GodRayMilliseconds = 0.0;      ///< the volume stages of the second frame (GPU, ms)
  bool StageRan = false;                ///< a volume stage ran in the second frame
};

/**
 * Renders `frames` frames with `pass` (the first compiles the programs: two for a
 * steady timing) and reads the last one's volume layer (with ProgressiveFrames, the
 * pass's mean); the stages whose name contains `stageWord` are the volume stages.
 */
VolumeFrame RenderPassVolume(vtkOpenGLRenderer* renderer, vtkCausticsRenderPass* pass, int size,
  const char* stageWord, int frames = 2)
{
  pass->GetAirlight()->EnabledOff(); // the volume caustic alone (the airlight: TestAirlight)
  pass->KeepBuffersOn();
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  for (int i = 0; i < frames; ++i)
  {
    window->Render();
  }
  VolumeFrame frame;
  frame.Volume = vtkSmartPointer<vtkImageData>::New();
  pass->GlobalWarningDisplayOff(); // no volume layer without a medium
  if (!pass->ReadBuffer("VolumeRadiance", frame.Volume))
  {
    frame.Volume = nullptr;
  }
  pass->GlobalWarningDisplayOn();
  EXPECT_TRUE(pass->GetLastFrameHadCaustics());
  vtkCausticsTimings* timings = pass->GetTimings();
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    if (std::string(timings->GetStageName(i)).find(stageWord) != std::string::npos &&
      timings->GetStageRan(i))
    {
      frame.StageRan = true;
      frame.GodRayMilliseconds += timings->GetStageGPUMilliseconds(i);
    }
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
  return frame;
}

VolumeFrame RenderVolume(vtkOpenGLRenderer* renderer, int subSegments, int size, int photons,
  double blur = 1.5, int frames = 2, int progressive = 1)
{
  vtkNew<vtkCausticsScreenSpacePhotonPass> pass;
  pass->SetLightBufferResolution(photons);
  pass->SetProgressiveFrames(progressive);
  pass->SetVolumeSubSegments(subSegments);
  pass->SetGodRayBlurPixels(blur);
  VolumeFrame frame = RenderPassVolume(renderer, pass, size, "god-ray", frames);
  EXPECT_NE(frame.Volume, nullptr);
  return frame;
}

/**
 * The caustic-map technique's volume layer (photon buffer of photons^2 texels), after
 * one frame (the tests' time budget: a 256^2 smoke-lens frame costs about 30 s), or
 * after `progressive` frames averaged by the pass (ProgressiveFrames).
 */
VolumeFrame RenderCausticMapVolume(
  vtkOpenGLRenderer* renderer, int size, int photons, double blur, int progressive = 1)
{
  vtkNew<vtkCausticsHierarchicalCausticMapPass> pass;
  pass->SetLightBufferResolution(photons);
  pass->SetVolumeBlurPixels(blur);
  pass->SetProgressiveFrames(progressive);
  return RenderPassVolume(renderer, pass, size, "hcm volume", progressive);
}

/**
 * The cascaded technique's volume layer (photons^2 photons from a photons^2 emitter):
 * one frame, or the pass's mean of `frames` (ProgressiveFrames; each frame draws a new
 * sample set).
 */
VolumeFrame RenderCascadedVolume(
  vtkOpenGLRenderer* renderer, int size, int photons, double blur, int frames = 1)
{
  vtkNew<vtkCausticsCascadedPhotonPass> pass;
  pass->SetLightBufferResolution(photons);
  pass->SetNumberOfPhotons(photons * photons);
  pass->SetVolumeBlurPixels(blur);
  pass->DenoiseOff(); // the surface caustic's denoiser: not what is compared
  pass->SetProgressiveFrames(frames);
  return RenderPassVolume(renderer, pass, size, "cascaded volume", frames);
}

/**
 * The Gaussian that brings the reference's volume caustic to the resolution of the
 * pass's with a Gaussian of `passBlur` pixels (0 where the pass's is the finer one).
 * Per axis, the pass's estimate has the variance of its one-pixel line rasterization
 * (a box, 1/12 px^2) plus its Gaussian's; the reference's, its Epanechnikov kernel's
 * (radius^2 / 6). Comparing them at the same variance compares what both estimate, the
 * radiance filtered at one resolution, whatever the scene.
 */
double ReferenceMatchingBlur(double passBlur)
{
  const double gap =
    passBlur * passBlur + 1.0 / 12.0 - ReferenceKernelPixels * ReferenceKernelPixels / 6.0;
  return gap > 0.0 ? std::sqrt(gap) : 0.0;
}

/**
 * `values` (rows of `width`) filtered as vtkCausticsVolumeLinesBlurCS.glsl filters the
 * pass's lines: a separable Gaussian of sigma pixels over ceil(3 sigma) taps, its
 * weights normalized over the taps inside the image.
 */
void BlurLikeThePass(vtkDataArray* values, int width, int height, double sigma)
{
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  if (!(sigma > 0.0) || radius < 1)
  {
    return;
  }
  std::vector<double> weight(2 * radius + 1);
  for (int k = -radius; k <= radius; ++k)
  {
    weight[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
  }
  const int components = values->GetNumberOfComponents();
  std::vector<double> source(static_cast<std::size_t>(width) * height * components);
  for (int axis = 0; axis < 2; ++axis)
  {
    for (std::size_t i = 0; i < source.size(); ++i)
    {
      source[i] = values->GetComponent(i / components, i % components);
    }
    for (int y = 0; y < height; ++y)
    {
      for (int x = 0; x < width; ++x)
      {
        for (int c = 0; c < components; ++c)
        {
          double sum = 0.0, total = 0.0;
          for (int k = -radius; k <= radius; ++k)
          {
            const int qx = axis == 0 ? x + k : x, qy = axis == 0 ? y : y + k;
            if (qx >= 0 && qx < width && qy >= 0 && qy < height)
            {
              total += weight[k + radius];
              sum += weight[k + radius] * source[(qy * width + qx) * components + c];
            }
          }
          values->SetComponent(y * width + x, c, sum / total);
        }
      }
    }
  }
}

/**
 * The reference's volume caustic, renamed VolumeRadiance to compare with the pass's,
 * with `volumePhotons` volume photons, at the resolution of a pass whose Gaussian is
 * `passBlur` pixels (ReferenceMatchingBlur; 0: the reference's own).
 */
vtkSmartPointer<vtkImageData> ReferenceVolumeCaustic(vtkOpenGLRenderer* renderer,
  int size = ImageSize, int volumePhotons = ReferenceVolumePhotons, double passBlur = 0.0)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(size, size);
  reference->SetPhotonsPerLight(10000); // surfaces: not compared here
  reference->SetVolumePhotonsPerLight(volumePhotons);
  reference->SetVolumeKernelRadiusPixels(ReferenceKernelPixels);
  EXPECT_TRUE(reference->Update()) << reference->GetLastError();
  vtkImageData* output = reference->GetOutput();
  auto target = vtkSmartPointer<vtkImageData>::New();
  target->ShallowCopy(output);
  vtkDataArray* caustic = output->GetPointData()->GetArray("VolumeCausticRadiance");
  EXPECT_NE(caustic, nullptr);
  if (caustic)
  {
    vtkSmartPointer<vtkDataArray> copy;
    copy.TakeReference(caustic->NewInstance());
    copy->DeepCopy(caustic);
    copy->SetName("VolumeRadiance");
    BlurLikeThePass(copy, size, size, ReferenceMatchingBlur(passBlur));
    target->GetPointData()->RemoveArray("VolumeRadiance");
    target->GetPointData()->AddArray(copy);
  }
  return target;
}

/** Relative L2 of `a` against `b` over every channel of every pixel. */
double RelativeL2(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetArray(0);
  vtkDataArray* y = b->GetPointData()->GetArray(0);
  double difference = 0.0, norm = 0.0;
  for (vtkIdType i = 0; i < y->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = x->GetComponent(i, c) - y->GetComponent(i, c);
      difference += d * d;
      norm += y->GetComponent(i, c) * y->GetComponent(i, c);
    }
  }
  return std::sqrt(difference / std::max(norm, 1e-300));
}

/** The scene's renderer. */
vtkSmartPointer<vtkOpenGLRenderer> MakeScene(const char* sceneName)
{
  auto renderer = vtkSmartPointer<vtkOpenGLRenderer>::New();
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName(sceneName);
  EXPECT_TRUE(scene->Populate(renderer)) << scene->GetLastError();
  return renderer;
}

/** Which technique feeds the volume stage. */
enum class Technique
{
  ScreenSpace,
  CausticMaps,
  Cascaded
};

/** How a volume layer is compared with the reference's. */
struct Comparison
{
  int Size = ImageSize;                       ///< pixels per side
  int Photons = LightBufferResolution;        ///< photon grid N (N x N)
  int ProgressiveFrames = 1;                  ///< the pass's mean of this many frames
  int ScreenSpaceFrames = 2;                  ///< screen-space: the last of this many frames
  double BlurPixels = MatchedBlurPixels;      ///< the pass's Gaussian
  int VolumePhotons = ReferenceVolumePhotons; ///< the reference's
  bool MatchResolution = false;               ///< the reference filtered to the pass's resolution
};

/** 256^2 pixels and photons, the narrow blur (smoke-lens). */
Comparison At256()
{
  Comparison c;
  c.Size = c.Photons = 256;
  return c;
}

/**
 * Underwater's comparison: 256^2 pixels, the default blur, at the pass's resolution;
 * `photons`^2 photons, the pass's mean of `frames` still frames (ProgressiveFrames).
 */
Comparison Underwater(int photons, int frames = 1)
{
  Comparison c;
  c.Size = 256;
  c.Photons = photons;
  c.ProgressiveFrames = frames;
  c.BlurPixels = DefaultBlurPixels;
  c.VolumePhotons = UnderwaterVolumePhotons;
  c.MatchResolution = true;
  c.ScreenSpaceFrames = 1; // deterministic: a second frame draws the same lines
  return c;
}

/** The volume caustic's mean radiance ratio and relative L2 against the reference. */
vtkCausticsErrorMetrics::Result CompareWithReference(
  const char* sceneName, Technique technique, const Comparison& c)
{
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene(sceneName);
  const char* names[] = { "screen-space", "caustic maps", "cascaded" };
  const int size = c.Size, photons = c.Photons, frames = c.ProgressiveFrames;
  const VolumeFrame lines = technique == Technique::ScreenSpace
    ? RenderVolume(renderer, 8, size, photons, c.BlurPixels,
        std::max(c.ScreenSpaceFrames, c.ProgressiveFrames), c.ProgressiveFrames)
    : technique == Technique::CausticMaps
    ? RenderCausticMapVolume(renderer, size, photons, c.BlurPixels, c.ProgressiveFrames)
    : RenderCascadedVolume(renderer, size, photons, c.BlurPixels, c.ProgressiveFrames);
  EXPECT_TRUE(lines.StageRan) << sceneName;
  vtkSmartPointer<vtkImageData> target =
    ReferenceVolumeCaustic(renderer, size, c.VolumePhotons, c.MatchResolution ? c.BlurPixels : 0.0);
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetArrayName("VolumeRadiance");
  if (!lines.Volume)
  {
    ADD_FAILURE() << sceneName << ", " << names[static_cast<int>(technique)] << ": no volume layer";
    return metrics->GetResult();
  }
  EXPECT_TRUE(metrics->Compute(lines.Volume, target));
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0) << sceneName;
  std::cout << sceneName << " volume caustic (" << names[static_cast<int>(technique)]
            << (frames > 1 ? ", ProgressiveFrames " + std::to_string(frames) : std::string())
            << ") at " << size << "^2, " << photons << "^2 photons, 8 sub-segments, blur "
            << c.BlurPixels << " px, reference " << c.VolumePhotons << " volume photons"
            << (c.MatchResolution ? " at the pass's resolution (+ Gaussian " +
                     std::to_string(ReferenceMatchingBlur(c.BlurPixels)) + " px)"
                                  : std::string())
            << ": " << metrics->GetSummary() << "; volume stages " << lines.GodRayMilliseconds
            << " ms\n  total ratio per channel:";
  for (int c = 0; c < 3; ++c)
  {
    double sum[2] = { 0.0, 0.0 };
    vtkImageData* images[2] = { lines.Volume, target };
    for (int k = 0; k < 2; ++k)
    {
      vtkDataArray* values = images[k]->GetPointData()->GetArray("VolumeRadiance");
      for (vtkIdType i = 0; values && i < values->GetNumberOfTuples(); ++i)
      {
        sum[k] += values->GetComponent(i, c);
      }
    }
    std::cout << " " << sum[0] / std::max(sum[1], 1e-300);
  }
  std::cout << "\n";
  return metrics->GetResult();
}
}

// Reached: mean radiance ratio 0.9988, relative L2 0.096. Bounds just above (the
// 5 % and 10 % of issue 14).
TEST(VolumeLines, SmokeLensMatchesReference)
{
  const auto result = CompareWithReference("smoke-lens", Technique::ScreenSpace, Comparison());
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.005);
  EXPECT_LT(result.RelativeL2Error, 0.10);
}

// The same at issue 14's 256^2 pixels with 256^2 photons, as the caustic maps' and
// cascaded's smoke-lens tests below (one frame: the lines are deterministic). Reached:
// mean radiance ratio 0.9985, relative L2 0.0910 (caustic maps 0.0911, cascaded
// 0.0909); bounds just above.
TEST(VolumeLines, SmokeLensAt256MatchesReference)
{
  Comparison c = At256();
  c.ScreenSpaceFrames = 1;
  const auto result = CompareWithReference("smoke-lens", Technique::ScreenSpace, c);
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.0025);
  EXPECT_LT(result.RelativeL2Error, 0.095);
}

// Underwater: the god rays under the waves, seen by a camera in the murky water (the
// medium fills the refractors), at 256^2 pixels with 256^2 photons (the tests' limit)
// and the default blur, against the reference (1 000 000 volume photons) at the pass's
// resolution (ReferenceMatchingBlur; docs/technique-volume-caustics.md, "Accuracy at
// 256^2"). Reached: mean radiance ratio 0.9983, relative L2 0.168; bounds just above.
// Above issue 14's 10 % for one frame: 256^2 photons leave the lines' own noise, which
// falls with the photons (512^2: 0.99915 and 0.0602, scripts/volume-error-map.py) and
// with ProgressiveFrames (8 frames: 0.0363, the next test).
// Screen-space draws the same photon lines as the caustic maps (the same figures to 5
// digits). Before (128^2, 128^2 photons, the 0.61 px blur against the reference's own
// kernel): 1.0042 and 0.386.
TEST(VolumeLines, UnderwaterMatchesReference)
{
  const auto result = CompareWithReference("underwater", Technique::ScreenSpace, Underwater(256));
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.0025);
  EXPECT_LT(result.RelativeL2Error, 0.17);
}

// The same with ProgressiveFrames 8: the pass averages 8 frames of the still scene, each
// with the light buffers' texel grid moved by a sub-texel offset (R2 sequence: a new,
// stratified set of photon lines). Reached: mean radiance ratio 0.9985, relative L2
// 0.0363 (one frame of 512^2 photons: 0.0602; the reference's own noise is 2.3 %);
// bounds just above. 4 frames: 0.0591 (the caustic maps' test below, the same lines,
// disabled in CI).
TEST(VolumeLines, UnderwaterProgressiveMatchesReference)
{
  const auto result =
    CompareWithReference("underwater", Technique::ScreenSpace, Underwater(256, 8));
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.0025);
  EXPECT_LT(result.RelativeL2Error, 0.04);
}

// The light-side optical depth re-sampled once per segment (8 sub-segments) against
// the per-fragment march it replaces (VolumeSubSegments 0), on the smoke grid at 64^2
// pixels and photons. Reached: 0.13 %; the time of both is printed (loaded 2-core
// llvmpipe: 5.0 s -> 1.06 s for the god-ray stages).
TEST(VolumeLines, SubSegmentsMatchTheMarch)
{
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene("smoke-lens");
  const VolumeFrame lines = RenderVolume(renderer, 8, 64, 64);
  const VolumeFrame marched = RenderVolume(renderer, 0, 64, 64);
  const double difference = RelativeL2(lines.Volume, marched.Volume);
  std::cout << "smoke-lens, 64^2: 8 sub-segments against the per-fragment march: "
            << 100 * difference << " %; god-ray stages " << marched.GodRayMilliseconds
            << " ms (march) -> " << lines.GodRayMilliseconds << " ms\n";
  EXPECT_LT(difference, 0.002);
}

// The caustic-map technique's photon pieces in air (vtkCausticsPhotonBuffer's trace
// appends them) into the same stage, at 256^2 pixels and photons, one frame. Reached:
// mean radiance ratio 0.9972, relative L2 0.0911; bounds just above.
TEST(VolumeLines, CausticMapsSmokeLensMatchesReference)
{
  const auto result = CompareWithReference("smoke-lens", Technique::CausticMaps, At256());
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.005);
  EXPECT_LT(result.RelativeL2Error, 0.095);
}

// Underwater's god rays from the caustic maps' pieces under the open sheet (the medium
// fills the water), as UnderwaterMatchesReference: 256^2 photons, one frame, the default
// blur against the reference at the pass's resolution. Reached: ratio 0.9983, relative
// L2 0.168 (the lines' noise: 0.0602 with 512^2 photons, 0.0591 with ProgressiveFrames
// 4, the next test); bounds just
// above. Before (0.61 px against the reference's own kernel, 200 000 volume photons):
// 1.0026 and 0.303.
TEST(VolumeLines, CausticMapsUnderwaterMatchesReference)
{
  const auto result = CompareWithReference("underwater", Technique::CausticMaps, Underwater(256));
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.0025);
  EXPECT_LT(result.RelativeL2Error, 0.17);
}

// The caustic maps' god rays under the open sheet, averaged by the pass over 4 frames
// (ProgressiveFrames), as UnderwaterProgressiveMatchesReference. Reached: ratio 0.9988,
// relative L2 0.0591 (8 frames: 0.0363, as screen-space's); bounds just above.
// Disabled in CI (23 s there): the caustic maps draw the same lines as screen-space
// (the figures agree to five digits), whose 8-frame test runs, and
// TestProgressiveFrames.CausticMapsRun checks their run. Run it with
// --gtest_also_run_disabled_tests.
TEST(VolumeLines, DISABLED_CausticMapsUnderwaterProgressiveMatchesReference)
{
  const auto result =
    CompareWithReference("underwater", Technique::CausticMaps, Underwater(256, 4));
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.0025);
  EXPECT_LT(result.RelativeL2Error, 0.065);
}

// The cascaded technique's stretches in air (vtkCausticsCascadedTraceCS.glsl appends
// them), 256^2 photons from a 256^2 emitter, one frame (FrameIndex 0). Reached: mean
// radiance ratio 1.0000, relative L2 0.0909; bounds just above.
TEST(VolumeLines, CascadedSmokeLensMatchesReference)
{
  const auto result = CompareWithReference("smoke-lens", Technique::Cascaded, At256());
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.005);
  EXPECT_LT(result.RelativeL2Error, 0.095);
}

// Cascaded's stretches under the open sheet, the pass's mean of 8 frames of 256^2 photons
// (ProgressiveFrames: each frame a new photon set; the water's god rays come from the
// refracted branch, which roulette picks for nearly every photon), the default blur
// against the reference at the pass's resolution. Reached: ratio 0.9991, relative L2
// 0.0502 (0.9979 and 0.0745 when the test averaged 8 frames itself, without the light
// grid's offsets); bounds just above.
// Before (0.61 px against the reference's own kernel, 200 000 volume photons): 1.0022
// and 0.174.
TEST(VolumeLines, CascadedUnderwaterMatchesReference)
{
  const auto result = CompareWithReference("underwater", Technique::Cascaded, Underwater(256, 8));
  EXPECT_NEAR(result.FluxRatio, 1.0, 0.0025);
  EXPECT_LT(result.RelativeL2Error, 0.052);
}

// Without a medium neither technique runs a volume stage nor writes a volume layer
// (issue 14, "Skipping"); the same scene with its medium runs them (the tests above).
TEST(VolumeLines, NoMediumNoVolumeStage)
{
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene("smoke-lens");
  vtkCausticsMedium::AttachTo(renderer, nullptr);
  const VolumeFrame maps = RenderCausticMapVolume(renderer, 64, 64, 1.5);
  EXPECT_FALSE(maps.StageRan);
  EXPECT_EQ(maps.Volume, nullptr);
  const VolumeFrame cascaded = RenderCascadedVolume(renderer, 64, 64, 1.5);
  EXPECT_FALSE(cascaded.StageRan);
  EXPECT_EQ(cascaded.Volume, nullptr);
}

namespace
{
/** Sum over the image of the surface caustic's RGB (any units: ratios only). */
double CausticTotal(vtkImageData* image, const char* name)
{
  vtkDataArray* values = image->GetPointData()->GetArray(name);
  double sum = 0.0;
  for (vtkIdType i = 0; values && i < values->GetNumberOfTuples(); ++i)
  {
    sum += values->GetComponent(i, 0) + values->GetComponent(i, 1) + values->GetComponent(i, 2);
  }
  return sum;
}

/**
 * The underwater scene, with its murky water (filling the refractors or, with `fills`
 * false, only in air: the grid lies under the surface, so then nowhere) or without it.
 */
vtkSmartPointer<vtkOpenGLRenderer> MakeUnderwater(bool withMedium, bool fills)
{
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene("underwater");
  if (!withMedium)
  {
    vtkCausticsMedium::AttachTo(renderer, nullptr);
  }
  else if (vtkCausticsMedium* medium = vtkCausticsMedium::GetFrom(renderer))
  {
    medium->SetFillsRefractors(fills);
  }
  return renderer;
}

/** Underwater's surface caustic with its medium over without it: the reference's. */
double ReferenceMediumRatio(bool fills)
{
  double total[2];
  for (int withMedium = 0; withMedium < 2; ++withMedium)
  {
    vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeUnderwater(withMedium, fills);
    vtkNew<vtkCausticsReferenceRenderer> reference;
    reference->SetInputRenderer(renderer);
    reference->SetImageSize(128, 128);
    reference->SetPhotonsPerLight(400000);
    EXPECT_TRUE(reference->Update()) << reference->GetLastError();
    total[withMedium] = CausticTotal(reference->GetOutput(), "CausticIrradiance");
  }
  return total[1] / total[0];
}

/** The same ratio from a technique's surface caustic (one frame each, 128^2). */
double TechniqueMediumRatio(Technique technique, bool fills)
{
  double total[2];
  for (int withMedium = 0; withMedium < 2; ++withMedium)
  {
    vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeUnderwater(withMedium, fills);
    vtkSmartPointer<vtkCausticsRenderPass> pass;
    if (technique == Technique::CausticMaps)
    {
      pass = vtkSmartPointer<vtkCausticsHierarchicalCausticMapPass>::New();
    }
    else
    {
      auto cascaded = vtkSmartPointer<vtkCausticsCascadedPhotonPass>::New();
      cascaded->DenoiseOff();
      pass = cascaded; // FrameIndex 0 in both: the same photons
    }
    pass->SetLightBufferResolution(128);
    pass->KeepBuffersOn();
    renderer->SetPass(pass);
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(128, 128);
    window->AddRenderer(renderer);
    window->Render();
    vtkNew<vtkImageData> caustic;
    EXPECT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic));
    total[withMedium] = CausticTotal(caustic, caustic->GetPointData()->GetArray(0)->GetName());
    renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(window);
    window->RemoveRenderer(renderer);
  }
  return total[1] / total[0];
}
}

// Underwater's murky water fills the refractors: the reference dims the pool floor's
// caustic by it (ratio 0.8389 with 400 000 photons), and so must the caustic maps' and
// cascaded traces under the open sheet (reached 0.8374 and 0.8387). With the medium
// only in air (FillsRefractors off; the grid lies under the surface) the reference
// holds none there and leaves the caustic as it is (0.9998; 1.0058 with 200 000
// photons: its own noise), and so must the traces (0.834 before they followed that
// rule; reached 0.9998). The bound is the reference's noise (0.01), far below the 0.16
// either rule guards against.
TEST(VolumeLines, ExtinctionUnderTheOpenSheetAsTheReference)
{
  for (bool fills : { true, false })
  {
    const double reference = ReferenceMediumRatio(fills);
    EXPECT_NEAR(reference, fills ? 0.84 : 1.0, 0.01) << "the reference, fills " << fills;
    for (Technique technique : { Technique::CausticMaps, Technique::Cascaded })
    {
      const double ratio = TechniqueMediumRatio(technique, fills);
      std::cout << "underwater surface caustic, with the medium "
                << (fills ? "filling the water" : "only in air") << " over without: reference "
                << reference << ", "
                << (technique == Technique::CausticMaps ? "caustic maps " : "cascaded ") << ratio
                << "\n";
      EXPECT_NEAR(ratio, reference, 0.01);
    }
  }
}

namespace
{
/** Counts (and prints) the warnings of `object` that contain `needle`, while it lives. */
class WarningCounter
{
public:
  WarningCounter(vtkObject* object, const char* needle)
    : Object(object)
    , Needle(needle)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(
      [](vtkObject*, unsigned long, void* self, void* text)
      {
        auto* counter = static_cast<WarningCounter*>(self);
        const std::string message = text ? static_cast<const char*>(text) : "";
        std::cout << "warning: " << message << "\n";
        counter->Count += message.find(counter->Needle) != std::string::npos;
      });
    this->Tag = object->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
  ~WarningCounter() { this->Object->RemoveObserver(this->Tag); }
  WarningCounter(const WarningCounter&) = delete;
  WarningCounter& operator=(const WarningCounter&) = delete;

  int Count = 0;

private:
  vtkObject* Object;
  std::string Needle;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long Tag = 0;
};

/** GL_MAX_SHADER_STORAGE_BLOCK_SIZE of an offscreen window's context, in bytes. */
double StorageBlockBytes()
{
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(16, 16);
  caustics::gl::IsSoftwareOpenGL(window); // makes the window's context current
  GLint64 bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
  return static_cast<double>(bytes);
}
}

// The tracers append their volume segments on the GPU and nothing reads the count
// back, so a list shorter than a trace's segments silently loses the volume caustic's
// light. The lists were capped at 2^21 records whatever the settings, and cascaded's
// bound, photons x (MaximumEvents + 1), under-counts an event that leaves the light's
// view (two stretches). Now each list holds the most its settings allow, when the
// device holds it (records of 48 bytes within GL_MAX_SHADER_STORAGE_BLOCK_SIZE: llvmpipe
// 128 MiB, 2 796 202 records), or warns once and keeps what fits. On smoke-lens
// (64^2 pixels, 256^2 photons):
// - cascaded, MaximumEvents 8: 256^2 x 2 x 8 = 1 048 576 segments fit (main: 589 824);
// - then MaximumEvents 32: 4 194 304 do not fit llvmpipe's block (main: 2^21, without a
//   word): one warning over two frames; the volume total is the 8 events' but for the
//   light of the few photons that now have more events (FrameIndex 0: reached 1.0002;
//   1.00032 with FrameIndex 1; bound 1.0004, just above);
// - caustic maps, MaximumReflections 16: 2 x 256^2 x 17 = 2 228 224 fit (main: 2^21).
// Each trace's count is read back here (a test-only read-back, GetVolumeSegmentList())
// and must be within the capacity.
TEST(VolumeLines, SegmentListsHoldWhatTheSettingsAllow)
{
  const double block = StorageBlockBytes();
  ASSERT_GT(block, 0.0);
  const long long fitting = static_cast<long long>(block / 48.0);
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene("smoke-lens");
  const int photons = 256, size = 64;
  const long long n = static_cast<long long>(photons) * photons;
  const auto check = [fitting](const char* name, const caustics::gl::VolumeSegmentList* list,
                       long long worstCase, int warnings, int expectedWarnings)
  {
    ASSERT_NE(list, nullptr);
    const auto& sizing = list->GetCapacity().GetSizing();
    const unsigned int appended = list->ReadAppendedCount();
    std::cout << name << ": worst case " << sizing.WorstCase << ", fitting " << sizing.Fitting
              << ", capacity " << sizing.Capacity << ", appended " << appended << ", warnings "
              << warnings << "\n";
    EXPECT_EQ(sizing.WorstCase, worstCase) << name;
    EXPECT_EQ(sizing.Capacity, std::min(worstCase, fitting)) << name;
    EXPECT_EQ(warnings, expectedWarnings) << name;
    EXPECT_GT(appended, 0u) << name;
    EXPECT_LE(static_cast<long long>(appended), sizing.Capacity) << name;
  };

  // Cascaded: one pass (its programs compile once), FrameIndex 0 in every frame.
  vtkNew<vtkCausticsCascadedPhotonPass> pass;
  pass->SetLightBufferResolution(photons);
  pass->SetNumberOfPhotons(photons * photons);
  pass->DenoiseOff();
  pass->GetAirlight()->EnabledOff();
  pass->KeepBuffersOn();
  WarningCounter warnings(pass, "photon segments");
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  double total[2] = { 0.0, 0.0 };
  const int events[2] = { 8, 32 };
  for (int k = 0; k < 2; ++k)
  {
    pass->SetMaximumEvents(events[k]);
    for (int frame = 0; frame < 1 + k; ++frame) // 32 events: the warning comes once in two
    {
      pass->SetFrameIndex(0);
      window->Render();
    }
    vtkNew<vtkImageData> volume;
    ASSERT_TRUE(pass->ReadBuffer("VolumeRadiance", volume));
    total[k] = CausticTotal(volume, "VolumeRadiance");
    const std::string name = "cascaded, " + std::to_string(events[k]) + " events";
    check(name.c_str(), pass->GetVolumeSegmentList(), n * 2 * events[k], warnings.Count,
      n * 2 * events[k] > fitting ? 1 : 0);
    warnings.Count = 0;
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  std::cout << "cascaded volume total, 32 events over 8: " << total[1] / total[0] << "\n";
  EXPECT_GT(total[0], 0.0);
  EXPECT_NEAR(total[1] / total[0], 1.0, 0.0004);

  // Caustic maps: 16 mirrors allowed, one frame.
  vtkNew<vtkCausticsHierarchicalCausticMapPass> maps;
  maps->SetLightBufferResolution(photons);
  maps->SetMaximumReflections(16);
  maps->GetAirlight()->EnabledOff();
  renderer->SetPass(maps);
  window->Render();
  check("caustic maps, 16 reflections", maps->GetVolumeSegmentList(), 2 * n * 17, 0, 0);
  renderer->SetPass(nullptr);
  maps->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
}

// The segment lists keep to the pass's memory budget (MaximumGPUMemory less the
// technique's own estimate, GetVolumeSegmentBudget()): with a budget that leaves them
// 1 MiB, the caustic maps' list on smoke-lens (128^2 photons) holds what fits in it,
// warns once naming the knob, and the frame stays finite; with the budget lifted it
// holds its worst case again. Before, the lists took the device's budget whatever the
// pass was told.
TEST(VolumeLines, SegmentListsKeepToMaximumGPUMemory)
{
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene("smoke-lens");
  vtkNew<vtkCausticsHierarchicalCausticMapPass> maps;
  maps->SetLightBufferResolution(128);
  maps->GetAirlight()->EnabledOff();
  maps->KeepBuffersOn();
  WarningCounter warnings(maps, "MaximumGPUMemory");
  renderer->SetPass(maps);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(64, 64);
  window->AddRenderer(renderer);

  // The technique's own estimate, from a budget far above it.
  const double huge = 1.0e12;
  maps->SetMaximumGPUMemory(huge);
  window->Render();
  const double estimate = huge - maps->GetVolumeSegmentBudget();
  const auto unlimited = maps->GetVolumeSegmentList()->GetCapacity().GetSizing();
  ASSERT_GT(estimate, 0.0);
  ASSERT_FALSE(unlimited.IsShort());
  EXPECT_EQ(warnings.Count, 0);

  const double room = 1024.0 * 1024.0;
  maps->SetMaximumGPUMemory(estimate + room);
  for (int frame = 0; frame < 2; ++frame) // the warning comes once
  {
    window->Render();
  }
  const auto& sizing = maps->GetVolumeSegmentList()->GetCapacity().GetSizing();
  const double perSegment =
    vtkCausticsVolumeLines::SegmentBytes + sizeof(float) * (sizing.Pieces + 1.0);
  std::cout << "estimate " << estimate << " B; worst case " << unlimited.WorstCase
            << " segments; with 1 MiB left: capacity " << sizing.Capacity << " ("
            << sizing.Capacity * perSegment << " B)\n";
  EXPECT_TRUE(sizing.IsShort());
  EXPECT_EQ(sizing.WorstCase, unlimited.WorstCase);
  EXPECT_LE(sizing.Capacity * perSegment, room);
  EXPECT_GT(sizing.Capacity * perSegment, 0.9 * room);
  EXPECT_EQ(warnings.Count, 1);
  vtkNew<vtkImageData> volume;
  ASSERT_TRUE(maps->ReadBuffer("VolumeRadiance", volume));
  vtkDataArray* values = volume->GetPointData()->GetArray(0);
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    ASSERT_TRUE(std::isfinite(values->GetVariantValue(i).ToDouble()));
  }
  EXPECT_GT(CausticTotal(volume, "VolumeRadiance"), 0.0);

  maps->SetMaximumGPUMemory(0.0); // the device's budget again
  window->Render();
  EXPECT_EQ(maps->GetVolumeSegmentList()->GetCapacity().GetSizing().Capacity, unlimited.Capacity);
  renderer->SetPass(nullptr);
  maps->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
}

// --- A medium that fills CLOSED refractors (vtkCausticsMedium::FillsRefractors) ---
// The caustic maps' phase 1 (inside, interface to interface) and cascaded's path through
// a closed refractor follow the reference's rule, as screen-space and the distance
// impostors already did: with the medium filling the refractors, every stretch inside
// loses the medium's extinction and leaves a volume segment; without it, neither.
namespace
{
/**
 * ball-lens (a glass ball of radius 1 m over a floor, the sun straight above) in a
 * homogeneous medium filling the scene's bounds: sigma_s 0.1, sigma_a 0.15 1/m. The
 * refracted photons cross about 1.75 m of the ball: filling it takes 35 % of the
 * floor's caustic (the reference's 0.6445).
 */
enum class BallCamera
{
  Outside,    ///< ball-lens's own camera
  InsideBall, ///< amid the light converging in the ball
  UnderFocus  ///< in air, in the cone of light under the ball's focus
};

vtkSmartPointer<vtkOpenGLRenderer> MakeBallInMedium(
  bool fills, BallCamera where = BallCamera::Outside)
{
  vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeScene("ball-lens");
  if (where != BallCamera::Outside)
  {
    // In the ball, 0.87 m from its centre, looking down through the light converging
    // in it; the ball's surface hides the rest (003 §5.3, and the reference's camera).
    // Or under the focus, looking up into the light coming down at the eye.
    const bool ball = where == BallCamera::InsideBall;
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0.0, ball ? 3.2 : 0.9, ball ? 0.85 : 0.25);
    camera->SetFocalPoint(0.0, ball ? 2.3 : 1.8, 0.0);
    camera->SetViewAngle(70.0);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
  }
  vtkNew<vtkCausticsMedium> medium;
  medium->SetScatteringCoefficient(0.1, 0.1, 0.1);
  medium->SetAbsorptionCoefficient(0.15, 0.15, 0.15);
  medium->SetFillsRefractors(fills);
  vtkCausticsMedium::AttachTo(renderer, medium);
  return renderer;
}

/** A frame's (or the reference's) surface caustic total and volume caustic layer. */
struct CausticLayers
{
  double SurfaceTotal = 0.0;            ///< sum of the caustic irradiance (ratios only)
  vtkSmartPointer<vtkImageData> Volume; ///< VolumeRadiance, W/(m^2 sr); null: none read
  long long Segments = -1; ///< volume segments the trace appended (-1: no appending list)
};

/** The reference's surface caustic (400 000 photons) and volume caustic. */
CausticLayers ReferenceLayers(vtkOpenGLRenderer* renderer)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(ImageSize, ImageSize);
  reference->SetPhotonsPerLight(400000);
  EXPECT_TRUE(reference->Update()) << reference->GetLastError();
  CausticLayers layers;
  layers.SurfaceTotal = CausticTotal(reference->GetOutput(), "CausticIrradiance");
  layers.Volume = ReferenceVolumeCaustic(renderer);
  return layers;
}

/**
 * A technique under test: its pass, whether it draws a volume caustic, and the bounds
 * on that caustic's mean radiance ratio against the reference (|ratio - 1|, without and
 * with fills), each just above what is reached (MediumFillingAClosedBallAsTheReference).
 */
struct FillsTechnique
{
  const char* Name;
  vtkSmartPointer<vtkCausticsRenderPass> (*Make)();
  bool Volume;
  double VolumeTotalBound[2];
};

/**
 * The techniques at LightBufferResolution^2 photons, their volume blur the reference's
 * kernel; cascaded without its denoiser, FrameIndex 0 (the same photons with and
 * without fills).
 */
const FillsTechnique FillsTechniques[] = {
  { "caustic maps",
    []() -> vtkSmartPointer<vtkCausticsRenderPass>
    {
      auto pass = vtkSmartPointer<vtkCausticsHierarchicalCausticMapPass>::New();
      pass->SetVolumeBlurPixels(MatchedBlurPixels);
      return pass;
    },
    true, { 0.038, 0.017 } }, // reached 0.9627, 0.9840
  { "cascaded",
    []() -> vtkSmartPointer<vtkCausticsRenderPass>
    {
      auto pass = vtkSmartPointer<vtkCausticsCascadedPhotonPass>::New();
      pass->SetNumberOfPhotons(LightBufferResolution * LightBufferResolution);
      pass->SetVolumeBlurPixels(MatchedBlurPixels);
      pass->DenoiseOff();
      return pass;
    },
    true, { 0.017, 0.015 } }, // reached 0.9842, 0.9863
  { "screen-space",
    []() -> vtkSmartPointer<vtkCausticsRenderPass>
    {
      auto pass = vtkSmartPointer<vtkCausticsScreenSpacePhotonPass>::New();
      pass->SetGodRayBlurPixels(MatchedBlurPixels);
      return pass;
    },
    true, { 0.014, 0.002 } }, // reached 0.9872, 1.0003
  { "impostors",
    []() -> vtkSmartPointer<vtkCausticsRenderPass>
    { return vtkSmartPointer<vtkCausticsImpostorPhotonPass>::New(); },
    false, { 0.0, 0.0 } }, // no volume caustic
};

/** One frame of a technique at ImageSize^2. */
CausticLayers TechniqueLayers(vtkOpenGLRenderer* renderer, const FillsTechnique& technique)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = technique.Make();
  pass->SetLightBufferResolution(LightBufferResolution);
  pass->GetAirlight()->EnabledOff(); // the volume caustic alone
  pass->KeepBuffersOn();
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(ImageSize, ImageSize);
  window->AddRenderer(renderer);
  window->Render();
  CausticLayers layers;
  vtkNew<vtkImageData> caustic;
  EXPECT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic)) << technique.Name;
  layers.SurfaceTotal = CausticTotal(caustic, caustic->GetPointData()->GetArray(0)->GetName());
  if (technique.Volume)
  {
    layers.Volume = vtkSmartPointer<vtkImageData>::New();
    EXPECT_TRUE(pass->ReadBuffer("VolumeRadiance", layers.Volume)) << technique.Name;
  }
  if (const caustics::gl::VolumeSegmentList* list = pass->GetVolumeSegmentList())
  {
    layers.Segments = list->ReadAppendedCount(); // a test-only read-back
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
  return layers;
}
}

// The ball in a medium, with the medium filling the ball or only the air around it, at
// 128^2 pixels and photons, one frame each; the reference with 400 000 photons (surface)
// and 200 000 (volume). Cold (no reference cache) 23-26 s on a loaded 2-core llvmpipe.
// - Surface caustic: the floor's caustic with fills over without. The reference's ratio,
//   0.6445, is the light the ball's inside takes; the four techniques reach 0.6451
//   (caustic maps), 0.6453 (cascaded), 0.6456 (screen-space), 0.6455 (impostors): bound
//   0.002, just above. Before caustic maps and cascaded followed the rule: 1 and 1.
// - Volume caustic against the reference's (the camera outside the ball sees the beams
//   under it, dimmer with fills: ratio 0.678 in the reference, 0.679-0.693 on the GPU):
//   mean radiance ratio (bounds per technique,
//   FillsTechniques) and relative L2, reached 0.082-0.088 (bound 0.09, just above; the
//   reference's own noise at 128^2 is about 0.09: SmokeLensMatchesReference). Before,
//   with fills, caustic maps and cascaded reached ratios 1.421 and 1.452 (the beams
//   under the ball not dimmed by its inside, none inside) and relative L2 0.542, 0.540.
TEST(VolumeLines, MediumFillingAClosedBallAsTheReference)
{
  constexpr int Count = sizeof(FillsTechniques) / sizeof(FillsTechniques[0]);
  double referenceSurface[2] = { 0.0, 0.0 }, referenceVolume[2] = { 0.0, 0.0 };
  double surface[Count][2] = {}, volume[Count][2] = {};
  long long segments[Count][2] = {};
  for (int fills = 0; fills < 2; ++fills)
  {
    vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeBallInMedium(fills != 0);
    const CausticLayers reference = ReferenceLayers(renderer);
    referenceSurface[fills] = reference.SurfaceTotal;
    referenceVolume[fills] = CausticTotal(reference.Volume, "VolumeRadiance");
    for (int k = 0; k < Count; ++k)
    {
      const FillsTechnique& technique = FillsTechniques[k];
      const CausticLayers layers = TechniqueLayers(renderer, technique);
      surface[k][fills] = layers.SurfaceTotal;
      segments[k][fills] = layers.Segments;
      if (!technique.Volume)
      {
        continue;
      }
      volume[k][fills] = CausticTotal(layers.Volume, "VolumeRadiance");
      vtkNew<vtkCausticsErrorMetrics> metrics;
      metrics->SetArrayName("VolumeRadiance");
      ASSERT_TRUE(metrics->Compute(layers.Volume, reference.Volume)) << technique.Name;
      const auto result = metrics->GetResult();
      std::cout << "ball in a medium " << (fills ? "filling the ball" : "only in air") << ", "
                << technique.Name << " volume caustic: " << metrics->GetSummary() << "\n";
      EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0) << technique.Name;
      EXPECT_NEAR(result.FluxRatio, 1.0, technique.VolumeTotalBound[fills])
        << technique.Name << ", fills " << fills;
      EXPECT_LT(result.RelativeL2Error, 0.09) << technique.Name << ", fills " << fills;
    }
  }
  const double referenceRatio[2] = { referenceSurface[1] / referenceSurface[0],
    referenceVolume[1] / referenceVolume[0] };
  // The reference's own rule: the ball's inside takes about a third.
  EXPECT_NEAR(referenceRatio[0], 0.645, 0.005);
  for (int k = 0; k < Count; ++k)
  {
    const FillsTechnique& technique = FillsTechniques[k];
    const double ratio = surface[k][1] / surface[k][0];
    std::cout << "ball in a medium, filling the ball over only in air: surface caustic "
              << "reference " << referenceRatio[0] << ", " << technique.Name << " " << ratio;
    if (technique.Volume)
    {
      std::cout << "; volume caustic reference " << referenceRatio[1] << ", " << technique.Name
                << " " << volume[k][1] / volume[k][0];
    }
    if (segments[k][0] >= 0)
    {
      std::cout << "; segments appended " << segments[k][0] << " -> " << segments[k][1];
      // The pieces inside the ball, which no camera outside it sees (its surface hides
      // them, as in the reference): reached 8604 -> 13664 (caustic maps: 12936 before
      // the light reflected back inside at an exit had its pieces), 5434 -> 9766
      // (cascaded); before, the same count with and without fills.
      EXPECT_GT(segments[k][1], segments[k][0]) << technique.Name;
    }
    std::cout << "\n";
    EXPECT_NEAR(ratio, referenceRatio[0], 0.002) << technique.Name;
  }
}

/**
 * Each technique of FillsTechniques' first three against the reference on `renderer`:
 * the volume caustic's total within ratioBounds[k] and its relative L2 under l2Bounds[k].
 */
void ExpectVolumeCausticsAsTheReference(vtkOpenGLRenderer* renderer, const std::string& label,
  const double ratioBounds[3], const double l2Bounds[3])
{
  const CausticLayers reference = ReferenceLayers(renderer);
  for (int k = 0; k < 3; ++k)
  {
    const FillsTechnique& technique = FillsTechniques[k];
    ASSERT_TRUE(technique.Volume);
    const CausticLayers layers = TechniqueLayers(renderer, technique);
    vtkNew<vtkCausticsErrorMetrics> metrics;
    metrics->SetArrayName("VolumeRadiance");
    ASSERT_TRUE(metrics->Compute(layers.Volume, reference.Volume)) << technique.Name;
    const auto result = metrics->GetResult();
    std::cout << label << ", " << technique.Name << " volume caustic: " << metrics->GetSummary()
              << "\n";
    EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0) << label << ", " << technique.Name;
    EXPECT_NEAR(result.FluxRatio, 1.0, ratioBounds[k]) << label << ", " << technique.Name;
    EXPECT_LT(result.RelativeL2Error, l2Bounds[k]) << label << ", " << technique.Name;
  }
}

// The same ball, the medium filling it, seen by a camera inside it: the volume caustic
// is the light converging in the ball, drawn from the pieces caustic maps' phase 1 and
// cascaded's stretches inside append, and screen-space's. The camera is amid the
// pieces: before the volume lines were clipped to the near plane, a piece reaching
// behind the eye was drawn with the wrong length per pixel (its far end projected
// through w < 0), and the three techniques gave 4.5, 5.1 and 4.9 times the reference's
// total. Then such a piece read its optical depth as if it began at the near plane
// (too little extinction: 1.043 and 1.034 for cascaded and screen-space), and caustic
// maps left out the light reflected back inside at an exit (5.3 % of the reference's
// total here), the two together giving it 0.982. Reached: caustic maps 1.0015,
// cascaded 1.0094, screen-space 1.0005, relative L2 0.101, 0.132, 0.103; bounds just
// above.
TEST(VolumeLines, MediumFillingAClosedBallSeenFromInside)
{
  const double ratioBounds[] = { 0.003, 0.011, 0.002 }; // FillsTechniques' order
  const double l2Bounds[] = { 0.105, 0.14, 0.11 };
  ExpectVolumeCausticsAsTheReference(MakeBallInMedium(true, BallCamera::InsideBall),
    "ball in a medium filling it, seen from inside", ratioBounds, l2Bounds);
}

// The same ball in air under its focus, looking up into the light that comes down at the
// eye: the pieces reach behind the eye at their far end. Until the fragments took their
// optical depth on the record's pieces rather than on the part in front of the near
// plane, such a piece was read as if it ended at the near plane: too much extinction
// along it, and the three techniques were 0.859, 0.861 and 0.864 times the reference's
// total (the opposite of a piece clipped at its start, MediumFillingAClosedBallSeenFromInside).
// Reached: caustic maps 1.0009, cascaded 0.9959, screen-space 1.0013, relative L2 0.066,
// 0.107, 0.072; bounds just above.
TEST(VolumeLines, MediumSeenFromUnderTheFocus)
{
  const double ratioBounds[] = { 0.002, 0.005, 0.002 }; // FillsTechniques' order
  const double l2Bounds[] = { 0.07, 0.11, 0.075 };
  ExpectVolumeCausticsAsTheReference(MakeBallInMedium(true, BallCamera::UnderFocus),
    "ball in a medium, seen from under its focus", ratioBounds, l2Bounds);
}

// An absorbing ball filled with the medium, seen from inside: the light converging in
// the ball loses the glass's own Beer-Lambert share along each piece from where it
// entered, and again on its way to the eye, which is in the glass too. Each technique
// is compared with the reference, which follows both. Before, neither did (the GPU
// carried each piece's flux at its entry, the reference the flux left at the chord's
// far end) and they were 2.4 and 5.9 times apart at 0.5 and 1 1/m, with a warning.
// Bounds just above what is reached (FillsTechniques' order): total 1.0015, 1.0117,
// 1.0018 at 0.5 1/m and 1.0022, 1.0151, 1.0024 at 1 1/m (1.0015, 1.0094, 1.0005
// without absorption, MediumFillingAClosedBallSeenFromInside); relative L2 0.179,
// 0.225, 0.180 and 0.289, 0.355, 0.290, mostly the lines' per-pixel noise, which grows
// as the glass darkens the light far from the entry. Before the fragments took their
// optical depth from the right pieces and caustic maps had the light reflected back
// inside at an exit, the totals rose with the absorption: 1.023, 1.056, 1.046 at
// 0.5 1/m and 1.047, 1.070, 1.056 at 1 1/m.
TEST(VolumeLines, FilledAbsorbingRefractorAsTheReference)
{
  const double absorptions[] = { 0.5, 1.0 };
  const double ratioBounds[2][3] = { { 0.002, 0.013, 0.003 }, { 0.003, 0.017, 0.0035 } };
  const double l2Bounds[2][3] = { { 0.19, 0.235, 0.19 }, { 0.30, 0.365, 0.30 } };
  for (int a = 0; a < 2; ++a)
  {
    vtkSmartPointer<vtkOpenGLRenderer> renderer = MakeBallInMedium(true, BallCamera::InsideBall);
    vtkActorCollection* actors = renderer->GetActors();
    actors->InitTraversal();
    const double absorption[3] = { absorptions[a], absorptions[a], absorptions[a] };
    for (vtkActor* actor = actors->GetNextActor(); actor; actor = actors->GetNextActor())
    {
      if (vtkCausticsMaterial::Describe(actor).role == caustics::Role::Refractor)
      {
        vtkCausticsMaterial::SetAttenuation(actor->GetProperty(), absorption);
      }
    }
    const std::string label = "absorbing ball (" + std::to_string(absorptions[a]) +
      " 1/m) in a medium filling it, seen from inside";
    ExpectVolumeCausticsAsTheReference(renderer, label, ratioBounds[a], l2Bounds[a]);
  }
}
