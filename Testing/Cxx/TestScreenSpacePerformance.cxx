// What screen-space photon tracing costs:
// - SkipsWhatTheSceneDoesNotNeed: with no specular actor, with one that no light
//   reaches, or with none in the camera's view, the caustic stages do not run and
//   a frame costs what plain VTK rendering of the same window costs (within 5%);
// - DISABLED_StageTimings: the rerunnable timing report of docs/technique-screen-space.md
//   (median GPU time of every stage over a few frames, per built-in scene), run by
//     build-<name>/bin/TestScreenSpacePerformance --gtest_also_run_disabled_tests \
//       --gtest_filter='*StageTimings*'
//   with SSP_GRID (light-buffer texels per side, default 256) and SSP_LAYERS
//   (default 8) in the environment to change the configuration.
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTimings.h"

#include "vtkActor.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace
{
double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

/** Lower quartile: a frame's cost without the spikes other processes add. */
double LowerQuartile(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 4];
}

/**
 * Wall time (ms) of a frame with and without the pass: frames alternate in one
 * window (so both see the same load), after warm-up frames, at least `frames` of
 * each and as many more as fit in about a second (a skipped frame of the ball lens
 * costs 0.6 ms, where the scheduler's noise alone moves 21 frames by 5 %); the
 * lower quartile of each series is its cost (medians move with the load of a
 * shared machine).
 */
void TimeFrames(vtkRenderer* renderer, vtkRenderWindow* window, vtkRenderPass* pass, int frames,
  double& withPass, double& plain)
{
  using Clock = std::chrono::steady_clock;
  std::vector<double> a, b;
  const auto begin = Clock::now();
  for (int i = 0; i < frames + 3 ||
       (i < 2000 && std::chrono::duration<double>(Clock::now() - begin).count() < 1.0);
       ++i)
  {
    for (int k = 0; k < 2; ++k)
    {
      renderer->SetPass(k == 0 ? pass : nullptr);
      window->Render(); // the switch itself: not timed
      const auto start = Clock::now();
      window->Render();
      window->WaitForCompletion();
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      if (i >= 3)
      {
        (k == 0 ? a : b).push_back(ms);
      }
    }
  }
  renderer->SetPass(pass);
  withPass = LowerQuartile(a);
  plain = LowerQuartile(b);
}
}

TEST(ScreenSpacePerformance, SkipsWhatTheSceneDoesNotNeed)
{
  for (const std::string variant : { "no specular actor", "no light reaches it", "out of view" })
  {
    vtkNew<vtkOpenGLRenderer> renderer;
    vtkNew<vtkCausticsBuiltinScene> scene;
    scene->SetSceneName(variant == "no light reaches it" ? "bunny" : "ball-lens");
    ASSERT_TRUE(scene->Populate(renderer));
    if (variant == "no specular actor")
    {
      vtkActorCollection* actors = renderer->GetActors();
      actors->InitTraversal();
      while (vtkActor* actor = actors->GetNextActor())
      {
        vtkCausticsMaterial::SetRole(actor, vtkCausticsMaterial::ROLE_RECEIVER);
      }
    }
    else if (variant == "no light reaches it")
    {
      // The spot light under the ceiling turned to the ceiling: its 50 degree cone
      // misses the bunny.
      vtkLight* spot = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
      spot->SetFocalPoint(0.0, 3.0, 0.0);
    }
    else
    {
      // The camera looks at a corner of the floor, away from the ball.
      renderer->GetActiveCamera()->SetPosition(4.0, 1.0, 4.0);
      renderer->GetActiveCamera()->SetFocalPoint(6.0, 0.0, 6.0);
      renderer->ResetCameraClippingRange();
    }
    vtkNew<vtkCausticsScreenSpacePhotonPass> pass;
    // An off-screen ball can still focus light into view, so skipping it is the
    // user's choice (off by default): the skip itself is what is tested here.
    pass->SetSkipOffscreenSpecular(variant == "out of view");
    renderer->SetPass(pass);
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(256, 256);
    window->AddRenderer(renderer);
    window->Render();
    EXPECT_FALSE(pass->GetLastFrameHadCaustics()) << variant;
    vtkCausticsTimings* timings = pass->GetTimings();
    for (int i = 0; i < timings->GetNumberOfStages(); ++i)
    {
      const std::string stage = timings->GetStageName(i);
      EXPECT_TRUE(!timings->GetStageRan(i) || stage == "scene snapshot" || stage == "vtk delegate")
        << variant << ": " << stage << " ran";
    }
    // A loaded machine can still disturb one series: up to three attempts of at
    // least 21 frames and a second each (the best ratio counts), two seconds apart
    // so that one slow spell of a shared machine does not spoil all three (a CI run
    // once gave 1.06-1.08 in three back-to-back attempts, and 0.93-1.02 in every
    // run since).
    double best = 1e300;
    for (int attempt = 0; attempt < 3 && best > 1.05; ++attempt)
    {
      if (attempt > 0)
      {
        std::this_thread::sleep_for(std::chrono::seconds(2));
      }
      double withPass = 0.0, plain = 0.0;
      TimeFrames(renderer, window, pass, 21, withPass, plain);
      best = std::min(best, withPass / plain);
      std::cout << variant << ": " << withPass << " ms with the pass, " << plain
                << " ms plain VTK (ratio " << withPass / plain << ")\n";
    }
    EXPECT_LE(best, 1.05) << variant;
    renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(window);
  }
}

TEST(ScreenSpacePerformance, DISABLED_StageTimings)
{
  const int grid = std::getenv("SSP_GRID") ? std::atoi(std::getenv("SSP_GRID")) : 256;
  const int layers = std::getenv("SSP_LAYERS") ? std::atoi(std::getenv("SSP_LAYERS")) : 8;
  const int frames = 5;
  std::cout << "screen-space photon tracing, 256 x 256 pixels, " << grid << "^2 texels per light, "
            << layers << " layers at most, median of " << frames << " frames after 1 warm-up\n";
  for (const char* name : { "ball-lens", "pool", "ring", "bunny" })
  {
    vtkNew<vtkOpenGLRenderer> renderer;
    vtkNew<vtkCausticsBuiltinScene> scene;
    scene->SetSceneName(name);
    ASSERT_TRUE(scene->Populate(renderer));
    vtkNew<vtkCausticsScreenSpacePhotonPass> pass;
    pass->SetLightBufferResolution(grid);
    pass->SetMaximumNumberOfLayers(layers);
    pass->GetTimings()->SynchronousOn();
    renderer->SetPass(pass);
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(256, 256);
    window->AddRenderer(renderer);
    window->Render();
    std::map<std::string, std::vector<double>> stages;
    std::vector<std::string> order;
    std::vector<double> totals;
    for (int frame = 0; frame < frames; ++frame)
    {
      window->Render();
      vtkCausticsTimings* timings = pass->GetTimings();
      double total = 0.0;
      for (int i = 0; i < timings->GetNumberOfStages(); ++i)
      {
        const std::string stage = timings->GetStageName(i);
        // The technique's own stages ("ssp ..."); the base pass's "caustic
        // irradiance" encloses them.
        if (!timings->GetStageRan(i) || stage.compare(0, 4, "ssp ") != 0)
        {
          continue;
        }
        if (!stages.count(stage))
        {
          order.push_back(stage);
        }
        stages[stage].push_back(timings->GetStageGPUMilliseconds(i));
        total += timings->GetStageGPUMilliseconds(i);
      }
      totals.push_back(total);
    }
    // Read back after the timed frames (a stall, never in the render path).
    vtkCausticsLayeredDepth* ldi = pass->GetLayeredDepth();
    std::cout << name << ": depth complexity " << ldi->ReadDepthComplexity() << ", "
              << ldi->ReadNumberOfPeeledLayers(0) << " layers peeled; technique total "
              << std::fixed << std::setprecision(1) << Median(totals) << " ms GPU\n";
    for (const std::string& stage : order)
    {
      std::cout << "  " << std::left << std::setw(44) << stage << std::right << std::setw(9)
                << Median(stages[stage]) << " ms\n";
    }
    EXPECT_TRUE(pass->GetLastFrameHadCaustics());
    renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(window);
  }
}
