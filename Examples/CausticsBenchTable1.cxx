#include "CausticsBenchTable1.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsTimings.h"

#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderWindow.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace caustics_bench
{
namespace
{
/** The stages of Table 1, in its columns' order. */
const char* const Stages[] = { "cascaded emit", "cascaded light layers", "cascaded trace",
  "cascaded splat", "denoise" };
constexpr int StageCount = 5;

/** Wall time (ms) of a stage of the last frame (its CPU time in synchronous mode). */
double Wall(vtkCausticsTimings* timings, const char* name)
{
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    if (std::string(timings->GetStageName(i)) == name && timings->GetStageRan(i))
    {
      return timings->GetStageCPUMilliseconds(i);
    }
  }
  return 0.0;
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/** One photon count: warm-up, then the timed frames' medians. */
Table1Row MeasureCount(const Table1Settings& settings, int photons, vtkRenderWindow* window)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName(settings.Scene.c_str());
  if (!scene->Populate(renderer))
  {
    throw std::runtime_error("--table1: cannot make the scene '" + settings.Scene + "'");
  }
  vtkNew<vtkCausticsCascadedPhotonPass> pass; // denoised, as by default
  pass->SetLightBufferResolution(settings.LightBufferResolution);
  pass->SetNumberOfPhotons(photons);
  pass->GetTimings()->SynchronousOn(); // each stage finished before the next: wall times
  renderer->SetPass(pass);
  window->AddRenderer(renderer);
  std::vector<std::vector<double>> times(StageCount + 1);
  for (int frame = 0; frame < settings.Warmup + settings.Frames; ++frame)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    const std::chrono::duration<double, std::milli> frameTime =
      std::chrono::steady_clock::now() - start;
    if (!pass->GetLastFrameHadCaustics())
    {
      throw std::runtime_error("--table1: a frame of '" + settings.Scene + "' had no caustics");
    }
    for (int s = 0; frame >= settings.Warmup && s < StageCount; ++s)
    {
      times[s].push_back(Wall(pass->GetTimings(), Stages[s]));
    }
    if (frame >= settings.Warmup)
    {
      times[StageCount].push_back(frameTime.count());
    }
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
  Table1Row row;
  row.Photons = photons;
  double* fields[] = { &row.Emit, &row.LightLayers, &row.Trace, &row.Store, &row.Denoise,
    &row.Frame };
  for (int s = 0; s <= StageCount; ++s)
  {
    *fields[s] = Median(times[s]);
  }
  return row;
}

std::string Millions(int photons)
{
  std::ostringstream text;
  text << std::setprecision(3) << photons / 1048576.0 << " M";
  return text.str();
}
}

std::vector<Table1Row> RunTable1(const Table1Settings& settings, vtkRenderWindow* window)
{
  window->SetSize(settings.Size, settings.Size);
  std::vector<Table1Row> rows;
  for (int photons : settings.Photons)
  {
    rows.push_back(MeasureCount(settings, photons, window));
  }
  return rows;
}

std::string MakeTable1Markdown(const Table1Settings& settings, const std::vector<Table1Row>& rows)
{
  std::ostringstream md;
  md << settings.Scene << ", " << settings.Size << " x " << settings.Size
     << " pixels, light buffer " << settings.LightBufferResolution << " x "
     << settings.LightBufferResolution << ", wall ms (synchronous stage timings), medians of "
     << settings.Frames << " frame(s) after " << settings.Warmup << " warm-up\n\n";
  md << "| photons | tracing (emit + trace) | of it: trace | storing (splat) | denoising | "
        "light layers | whole frame |\n";
  md << "|--:|--:|--:|--:|--:|--:|--:|\n";
  md << std::fixed << std::setprecision(0);
  for (const Table1Row& r : rows)
  {
    md << "| " << Millions(r.Photons) << " (" << r.Photons << ") | " << r.Emit + r.Trace << " | "
       << r.Trace << " | " << r.Store << " | " << r.Denoise << " | " << r.LightLayers << " | "
       << r.Frame << " |\n";
  }
  return md.str();
}
}
