// ProgressiveFrames: the pass's mean of a still scene's frames (vtkCausticsProgressiveMean).
// The run grows one frame at a time, its first frame is the image without averaging,
// it holds (no caustic stage runs) once complete, it restarts on any change of camera,
// light or setting, and its mean keeps the flux of one frame. The accuracy it buys is
// measured against the reference in TestVolumeLines (UnderwaterProgressiveMatchesReference).
#include "TestTechniqueFrame.h"

#include "vtkCamera.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsTimings.h"
#include "vtkDataArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace
{
constexpr int Size = 64;
constexpr int Photons = 64;

bool StageRan(vtkCausticsRenderPass* pass, const char* name)
{
  vtkCausticsTimings* timings = pass->GetTimings();
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    if (std::string(timings->GetStageName(i)) == name)
    {
      return timings->GetStageRan(i);
    }
  }
  return false;
}

/** `test` against `reference`, on their first point-data array (RGB). */
vtkCausticsErrorMetrics::Result Compare(vtkImageData* test, vtkImageData* reference)
{
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetArrayName(reference->GetPointData()->GetArray(0)->GetName());
  EXPECT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  return metrics->GetResult();
}

double Difference(vtkImageData* test, vtkImageData* reference)
{
  return Compare(test, reference).RelativeL2Error;
}

/** A ball-lens frame by `technique` whose caustic buffers can be read. */
struct Frame : TechniqueFrame
{
  explicit Frame(const char* technique)
    : TechniqueFrame(technique, Size, Photons)
  {
    this->Pass->KeepBuffersOn();
  }
  vtkSmartPointer<vtkImageData> Caustic() { return this->Render("CausticIrradiance"); }
};

/**
 * A run of `frames` frames with ProgressiveFrames `frames`, then one more: the count
 * grows, the first frame is the one-frame image, the held frame repeats the mean
 * without running the caustic stages, and the mean's flux is one frame's within
 * `fluxTolerance` (the one frame's own noise where the technique is stochastic).
 */
void ExpectARun(const char* technique, int frames, double fluxTolerance = 0.01)
{
  SCOPED_TRACE(technique);
  Frame single(technique);
  const vtkSmartPointer<vtkImageData> one = single.Caustic();
  ASSERT_NE(one, nullptr);
  EXPECT_EQ(single.Pass->GetProgressiveFrames(), 1);
  EXPECT_EQ(single.Pass->GetFramesAveraged(), 1);

  Frame run(technique);
  run.Pass->SetProgressiveFrames(frames);
  vtkSmartPointer<vtkImageData> first, mean;
  vtkNew<vtkImageData> lastColor, heldColor;
  for (int k = 1; k <= frames; ++k)
  {
    mean = run.Caustic();
    EXPECT_TRUE(run.Pass->ReadBuffer("FinalColor", lastColor));
    ASSERT_NE(mean, nullptr);
    EXPECT_EQ(run.Pass->GetFramesAveraged(), k);
    EXPECT_TRUE(StageRan(run.Pass, "caustic irradiance")) << "frame " << k;
    if (k == 1)
    {
      first = mean;
    }
  }
  EXPECT_LT(Difference(first, one), 1e-6) << "the first frame is the one-frame image";
  EXPECT_GT(Difference(mean, first), 1e-3) << "the frames had different photons";
  EXPECT_NEAR(Compare(mean, one).FluxRatio, 1.0, fluxTolerance);

  const vtkSmartPointer<vtkImageData> held = run.Caustic();
  EXPECT_TRUE(run.Pass->ReadBuffer("FinalColor", heldColor));
  EXPECT_LT(Difference(heldColor, lastColor), 1e-6) << "the held frame shows the last image";
  EXPECT_EQ(run.Pass->GetFramesAveraged(), frames);
  EXPECT_FALSE(StageRan(run.Pass, "caustic irradiance")) << "a complete mean is held";
  EXPECT_FALSE(StageRan(run.Pass, "light buffers"));
  EXPECT_LT(Difference(held, mean), 1e-7);
  EXPECT_TRUE(run.Pass->GetLastFrameHadCaustics());
}
}

TEST(ProgressiveFrames, ScreenSpaceRun)
{
  ExpectARun("screen-space", 4);
}

TEST(ProgressiveFrames, CausticMapsRun)
{
  ExpectARun("caustic-maps", 4);
}

// Cascaded draws its photons by Russian roulette: one frame's flux at 64^2 photons is
// itself an estimate with about 1 % of noise (1.0101 of the mean of 3 here).
TEST(ProgressiveFrames, CascadedRun)
{
  ExpectARun("cascaded", 3, 0.03);
}

TEST(ProgressiveFrames, ImpostorsRun)
{
  ExpectARun("impostors", 3);
}

// Any change of what a frame depends on restarts the mean: the camera, a light, a
// setting of the pass; ResetProgressive() does it by hand.
TEST(ProgressiveFrames, RestartsOnChange)
{
  Frame run("screen-space");
  run.Pass->SetProgressiveFrames(8);
  for (int k = 0; k < 3; ++k)
  {
    run.Caustic();
  }
  ASSERT_EQ(run.Pass->GetFramesAveraged(), 3);

  run.Renderer->GetActiveCamera()->Azimuth(2.0);
  run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 1) << "camera moved";
  run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 2);

  vtkLight* light = vtkLight::SafeDownCast(run.Renderer->GetLights()->GetItemAsObject(0));
  ASSERT_NE(light, nullptr);
  light->SetIntensity(0.5 * light->GetIntensity());
  run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 1) << "light changed";
  run.Caustic();

  run.Pass->SetRoughnessCutoff(0.25);
  run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 1) << "setting changed";
  run.Caustic();

  run.Pass->ResetProgressive();
  run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 1) << "reset";

  run.Pass->SetProgressiveFrames(1);
  run.Caustic();
  run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 1) << "off";
  EXPECT_TRUE(StageRan(run.Pass, "caustic irradiance"));
}

// The window's size changes the mean's textures: the run restarts at the new size.
TEST(ProgressiveFrames, RestartsOnResize)
{
  Frame run("caustic-maps");
  run.Pass->SetProgressiveFrames(4);
  run.Caustic();
  run.Caustic();
  ASSERT_EQ(run.Pass->GetFramesAveraged(), 2);
  run.Window->SetSize(48, 40);
  const vtkSmartPointer<vtkImageData> resized = run.Caustic();
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 1);
  ASSERT_NE(resized, nullptr);
  int dims[3];
  resized->GetDimensions(dims);
  EXPECT_EQ(dims[0], 48);
  EXPECT_EQ(dims[1], 40);
}

// Absurd values are clamped; the setting is printed.
TEST(ProgressiveFrames, Parameters)
{
  Frame run("screen-space");
  run.Pass->SetProgressiveFrames(0);
  EXPECT_EQ(run.Pass->GetProgressiveFrames(), 1);
  run.Pass->SetProgressiveFrames(1000000);
  EXPECT_EQ(run.Pass->GetProgressiveFrames(), 4096);
  std::ostringstream printed;
  run.Pass->Print(printed);
  EXPECT_NE(printed.str().find("ProgressiveFrames: 4096"), std::string::npos);
  EXPECT_EQ(run.Pass->GetFramesAveraged(), 0) << "no frame yet";
}
