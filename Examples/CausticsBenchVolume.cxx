#include "CausticsBenchVolume.h"

#include "vtkCausticsAirlight.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
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
  double VolumeMilliseconds = 0.0; ///< GPU time of the god-ray stages
  vtkSmartPointer<vtkImageData> Volume;
};

VolumeRun Render(const VolumeSettings& settings, vtkRenderWindow* window,
  vtkOpenGLRenderer* renderer, int grid, int subSegments, int size)
{
  vtkNew<vtkCausticsScreenSpacePhotonPass> pass;
  pass->SetLightBufferResolution(grid);
  pass->SetVolumeSubSegments(subSegments);
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
      if (timings->GetStageRan(s) && name.find("god-ray") != std::string::npos)
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

std::string RunVolumeTables(
  const VolumeSettings& settings, vtkRenderWindow* window, std::ostream& progress)
{
  std::ostringstream md;
  md << "Time against error at " << settings.Size << "² (screen-space technique, its "
     << "god-rays; median of " << settings.Frames << " frames after " << settings.Warmup
     << " warm-up; error of `VolumeRadiance` against the reference's "
     << "`VolumeCausticRadiance`, " << settings.VolumePhotons << " volume photons):\n\n"
     << "| scene | photons | sub-segments | frame (ms) | god-rays (ms) | rel. L2 | total ratio |\n"
     << "|---|--:|--:|--:|--:|--:|--:|\n";
  for (const std::string& name : settings.Scenes)
  {
    vtkSmartPointer<vtkOpenGLRenderer> renderer = Scene(name);
    vtkSmartPointer<vtkImageData> truth = Reference(settings, renderer, settings.Size);
    for (int grid : settings.Grids)
    {
      for (int subSegments : settings.SubSegments)
      {
        const VolumeRun run = Render(settings, window, renderer, grid, subSegments, settings.Size);
        vtkNew<vtkCausticsErrorMetrics> metrics;
        metrics->SetArrayName("VolumeRadiance");
        if (!metrics->Compute(run.Volume, truth))
        {
          throw std::runtime_error(metrics->GetLastError());
        }
        const std::string row = "| " + name + " | " + std::to_string(grid) + "² | " +
          (subSegments == 0 ? std::string("march") : std::to_string(subSegments)) + " | " +
          Fixed(run.FrameMilliseconds, 0) + " | " + Fixed(run.VolumeMilliseconds, 0) + " | " +
          Fixed(metrics->GetRelativeL2Error(), 3) + " | " + Fixed(metrics->GetFluxRatio(), 3) +
          " |\n";
        md << row;
        progress << row << std::flush;
      }
    }
  }
  // 003's Table 2: caustic-buffer resolution against screen size (frame time; the paper
  // gives frames per second).
  const std::string scene = settings.Scenes.front();
  md << "\nTable 2 analogue (003 §6): " << scene
     << ", frame time in ms (median, wall) by caustic-buffer (photon grid) and screen size, "
     << "default sub-segments:\n\n| photons \\ screen |";
  for (int size : settings.Sizes)
  {
    md << " " << size << "² |";
  }
  md << "\n|---|";
  for (std::size_t k = 0; k < settings.Sizes.size(); ++k)
  {
    md << "--:|";
  }
  md << "\n";
  vtkSmartPointer<vtkOpenGLRenderer> renderer = Scene(scene);
  for (int grid : settings.Grids)
  {
    md << "| " << grid << "² |";
    for (int size : settings.Sizes)
    {
      const VolumeRun run = Render(settings, window, renderer, grid, 8, size);
      md << " " << Fixed(run.FrameMilliseconds, 0) << " |";
      progress << "table 2: " << grid << "² photons, " << size
               << "²: " << Fixed(run.FrameMilliseconds, 0) << " ms" << std::endl;
    }
    md << "\n";
  }
  return md.str();
}
}
