#include "CausticsBenchVolume.h"

#include "vtkCausticsAirlight.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace caustics_bench
{
namespace
{
double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

/** One frame configuration's medians and the last frame's volume radiance. */
struct VolumeRun
{
  double FrameMilliseconds = 0.0;  ///< wall, Render + wait for the GPU
  double VolumeMilliseconds = 0.0; ///< GPU time of the technique's volume stages
  vtkSmartPointer<vtkImageData> Volume;
};

/** Stages whose name holds this word are the technique's volume stages. */
const char* VolumeStageWord(const std::string& technique)
{
  return technique == "screen-space" ? "god-ray"
    : technique == "caustic-maps"    ? "hcm volume"
                                     : "cascaded volume";
}

/**
 * `technique` with an N x N photon grid (N = `grid`: the light buffers, hence the
 * screen-space and caustic-map photons; cascaded also samples N^2 photons) and
 * `subSegments`; every other knob at its default.
 */
vtkSmartPointer<vtkCausticsRenderPass> MakePass(
  const std::string& technique, int grid, int subSegments)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
  pass->SetLightBufferResolution(grid);
  if (auto* screenSpace = vtkCausticsScreenSpacePhotonPass::SafeDownCast(pass))
  {
    screenSpace->SetVolumeSubSegments(subSegments);
  }
  else if (auto* maps = vtkCausticsHierarchicalCausticMapPass::SafeDownCast(pass))
  {
    maps->SetVolumeSubSegments(subSegments);
  }
  else if (auto* cascaded = vtkCausticsCascadedPhotonPass::SafeDownCast(pass))
  {
    cascaded->SetNumberOfPhotons(grid * grid);
    cascaded->SetVolumeSubSegments(subSegments);
  }
  else
  {
    throw std::runtime_error("technique '" + technique + "' writes no volume lines");
  }
  return pass;
}

VolumeRun Render(const VolumeSettings& settings, vtkRenderWindow* window,
  vtkOpenGLRenderer* renderer, const std::string& technique, int grid, int subSegments, int size)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = MakePass(technique, grid, subSegments);
  const std::string stageWord = VolumeStageWord(technique);
  // The volume caustic alone, as the reference's VolumeCausticRadiance it is compared
  // with (the airlight, a separate stage: docs/airlight.md).
  pass->GetAirlight()->EnabledOff();
  pass->KeepBuffersOn();
  renderer->SetPass(pass);
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  std::vector<double> wall, volume;
  for (int frame = 0; frame < settings.Warmup + settings.Frames; ++frame)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (frame < settings.Warmup)
    {
      continue;
    }
    wall.push_back(ms);
    double sum = 0.0;
    vtkCausticsTimings* timings = pass->GetTimings();
    for (int s = 0; s < timings->GetNumberOfStages(); ++s)
    {
      const std::string name = timings->GetStageName(s);
      if (timings->GetStageRan(s) && name.find(stageWord) != std::string::npos)
      {
        sum += std::max(0.0, timings->GetStageGPUMilliseconds(s));
      }
    }
    volume.push_back(sum);
  }
  VolumeRun run;
  run.FrameMilliseconds = Median(wall);
  run.VolumeMilliseconds = Median(volume);
  run.Volume = vtkSmartPointer<vtkImageData>::New();
  if (!pass->ReadBuffer("VolumeRadiance", run.Volume))
  {
    throw std::runtime_error("no volume radiance was made (is there a medium?)");
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
  return run;
}

/** One mean of ProgressiveFrames: its frames, the wall time to make it, its error. */
struct ProgressiveRow
{
  int Frames = 0;
  double Milliseconds = 0.0; ///< wall, every frame of the run up to this one
  double RelativeL2 = 0.0;
  double TotalRatio = 0.0;
};

/**
 * `technique` (`grid`, 8 sub-segments) averaging a still view (ProgressiveFrames, the
 * largest of `settings.Progressive`): after settings.Warmup frames without averaging,
 * a run whose mean after each listed frame count is compared with `truth`.
 */
std::vector<ProgressiveRow> RenderProgressive(const VolumeSettings& settings,
  vtkRenderWindow* window, vtkOpenGLRenderer* renderer, const std::string& technique, int grid,
  vtkImageData* truth)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = MakePass(technique, grid, 8);
  pass->GetAirlight()->EnabledOff();
  pass->KeepBuffersOn();
  renderer->SetPass(pass);
  window->SetSize(settings.Size, settings.Size);
  window->AddRenderer(renderer);
  for (int frame = 0; frame < settings.Warmup; ++frame)
  {
    window->Render(); // programs compiled, buffers made
  }
  const int frames = *std::max_element(settings.Progressive.begin(), settings.Progressive.end());
  pass->SetProgressiveFrames(frames); // a new setting: the run starts at the next frame
  std::vector<ProgressiveRow> rows;
  double elapsed = 0.0;
  for (int frame = 1; frame <= frames; ++frame)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    elapsed +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (std::find(settings.Progressive.begin(), settings.Progressive.end(), frame) ==
      settings.Progressive.end())
    {
      continue;
    }
    vtkNew<vtkImageData> volume;
    vtkNew<vtkCausticsErrorMetrics> metrics;
    metrics->SetArrayName("VolumeRadiance");
    if (!pass->ReadBuffer("VolumeRadiance", volume) || !metrics->Compute(volume, truth))
    {
      throw std::runtime_error("no volume radiance to compare (is there a medium?)");
    }
    if (pass->GetFramesAveraged() != frame)
    {
      throw std::runtime_error("the mean holds " + std::to_string(pass->GetFramesAveraged()) +
        " frames, not " + std::to_string(frame) + " (did the view change?)");
    }
    rows.push_back({ frame, elapsed, metrics->GetRelativeL2Error(), metrics->GetFluxRatio() });
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
  return rows;
}

/** The reference's volume caustic at size x size, named VolumeRadiance. */
vtkSmartPointer<vtkImageData> Reference(
  const VolumeSettings& settings, vtkOpenGLRenderer* renderer, int size)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(size, size);
  reference->SetPhotonsPerLight(10000); // surfaces: not compared
  reference->SetVolumePhotonsPerLight(static_cast<vtkIdType>(settings.VolumePhotons));
  if (!reference->Update())
  {
    throw std::runtime_error("the reference failed: " + std::string(reference->GetLastError()));
  }
  auto target = vtkSmartPointer<vtkImageData>::New();
  target->ShallowCopy(reference->GetOutput());
  vtkDataArray* caustic = reference->GetOutput()->GetPointData()->GetArray("VolumeCausticRadiance");
  vtkSmartPointer<vtkDataArray> copy;
  copy.TakeReference(caustic->NewInstance());
  copy->DeepCopy(caustic);
  copy->SetName("VolumeRadiance");
  target->GetPointData()->RemoveArray("VolumeRadiance");
  target->GetPointData()->AddArray(copy);
  return target;
}

vtkSmartPointer<vtkOpenGLRenderer> Scene(const std::string& name)
{
  auto renderer = vtkSmartPointer<vtkOpenGLRenderer>::New();
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName(name.c_str());
  if (!scene->Populate(renderer))
  {
    throw std::runtime_error(scene->GetLastError());
  }
  return renderer;
}

std::string Fixed(double value, int digits)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}
}

const std::vector<std::string>& VolumeTechniqueNames()
{
  static const std::vector<std::string> names{ "screen-space", "caustic-maps", "cascaded" };
  return names;
}

std::string RunVolumeTables(
  const VolumeSettings& settings, vtkRenderWindow* window, std::ostream& progress)
{
  std::ostringstream md;
  md << "Time against error at " << settings.Size << "² (each technique's volume stages: "
     << "screen-space's `god-ray` stages, caustic maps' `hcm volume`, cascaded's "
     << "`cascaded volume`; median of " << settings.Frames << " frames after " << settings.Warmup
     << " warm-up; error of `VolumeRadiance` against the reference's "
     << "`VolumeCausticRadiance`, " << settings.VolumePhotons << " volume photons):\n\n"
     << "| scene | technique | photons | sub-segments | frame (ms) | volume stages (ms) | "
     << "rel. L2 | total ratio |\n"
     << "|---|---|--:|--:|--:|--:|--:|--:|\n";
  for (const std::string& name : settings.Scenes)
  {
    vtkSmartPointer<vtkOpenGLRenderer> renderer = Scene(name);
    vtkSmartPointer<vtkImageData> truth = Reference(settings, renderer, settings.Size);
    for (const std::string& technique : settings.Techniques)
    {
      for (int grid : settings.Grids)
      {
        for (int subSegments : settings.SubSegments)
        {
          const VolumeRun run =
            Render(settings, window, renderer, technique, grid, subSegments, settings.Size);
          vtkNew<vtkCausticsErrorMetrics> metrics;
          metrics->SetArrayName("VolumeRadiance");
          if (!metrics->Compute(run.Volume, truth))
          {
            throw std::runtime_error(metrics->GetLastError());
          }
          const std::string row = "| " + name + " | " + technique + " | " + std::to_string(grid) +
            "² | " + (subSegments == 0 ? std::string("march") : std::to_string(subSegments)) +
            " | " + Fixed(run.FrameMilliseconds, 0) + " | " + Fixed(run.VolumeMilliseconds, 0) +
            " | " + Fixed(metrics->GetRelativeL2Error(), 3) + " | " +
            Fixed(metrics->GetFluxRatio(), 3) + " |\n";
          md << row;
          progress << row << std::flush;
        }
      }
    }
  }
  if (!settings.Progressive.empty())
  {
    const int grid = *std::max_element(settings.Grids.begin(), settings.Grids.end());
    md << "\nProgressive mean (`ProgressiveFrames`, `--progressive`) of a still view at "
       << settings.Size << "², " << grid << "² photons, 8 sub-segments: the error of the mean "
       << "of the first k frames, and the wall time of those k frames:\n\n"
       << "| scene | technique | frames | time to the mean (ms) | rel. L2 | total ratio |\n"
       << "|---|---|--:|--:|--:|--:|\n";
    for (const std::string& name : settings.Scenes)
    {
      vtkSmartPointer<vtkOpenGLRenderer> renderer = Scene(name);
      vtkSmartPointer<vtkImageData> truth = Reference(settings, renderer, settings.Size);
      for (const std::string& technique : settings.Techniques)
      {
        for (const ProgressiveRow& r :
          RenderProgressive(settings, window, renderer, technique, grid, truth))
        {
          const std::string row = "| " + name + " | " + technique + " | " +
            std::to_string(r.Frames) + " | " + Fixed(r.Milliseconds, 0) + " | " +
            Fixed(r.RelativeL2, 3) + " | " + Fixed(r.TotalRatio, 3) + " |\n";
          md << row;
          progress << "progressive: " << row << std::flush;
        }
      }
    }
  }
  // 003's Table 2: caustic-buffer resolution against screen size (frame time; the paper
  // gives frames per second), for each technique.
  const std::string scene = settings.Scenes.front();
  md << "\nTable 2 analogue (003 §6): " << scene
     << ", frame time in ms (median, wall) by technique, caustic-buffer (photon grid) and "
     << "screen size, default sub-segments:\n\n| technique | photons \\ screen |";
  for (int size : settings.Sizes)
  {
    md << " " << size << "² |";
  }
  md << "\n|---|---|";
  for (std::size_t k = 0; k < settings.Sizes.size(); ++k)
  {
    md << "--:|";
  }
  md << "\n";
  vtkSmartPointer<vtkOpenGLRenderer> renderer = Scene(scene);
  for (const std::string& technique : settings.Techniques)
  {
    for (int grid : settings.Grids)
    {
      md << "| " << technique << " | " << grid << "² |";
      for (int size : settings.Sizes)
      {
        const VolumeRun run = Render(settings, window, renderer, technique, grid, 8, size);
        md << " " << Fixed(run.FrameMilliseconds, 0) << " |";
        progress << "table 2: " << technique << ", " << grid << "² photons, " << size
                 << "²: " << Fixed(run.FrameMilliseconds, 0) << " ms" << std::endl;
      }
      md << "\n";
    }
  }
  return md.str();
}
}
