// Randomized stress and soak driver of the caustics passes (issue 18, parts 4 and 5).
//
//   CausticsStress --seed S --count N [--time-limit T] [--technique NAME]
//                  [--energy-slack X] [--verbose]
//     renders the scenes of seeds S .. S+N-1 (StressScene.h) with every registered
//     technique (vtkCausticsTechniques) and checks each frame (StressChecks.h). A
//     failing scene prints "FAIL seed=K ..." with the command that replays it alone
//     (--seed K --count 1). A scene that runs longer than T seconds (default 60) is
//     a hang: the seed is printed and the process exits 3. X (default 1.1) is the
//     allowed caustic flux / bound; lower it to watch the energy check fail.
//   CausticsStress --soak F [--technique NAME] [--verbose]
//     renders F frames (at least 64) per technique with resizes and actors added
//     and removed, and checks that GPU objects, GPU bytes and RSS stay flat
//     (StressSoak.h).
// Exit status: 0 when every scene passed, 1 when some failed, 2 on bad arguments.
#include "StressChecks.h"
#include "StressScene.h"
#include "StressSoak.h"

#include "vtkCausticsProgressivePhotonPass.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"

#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderWindow.h"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
struct Options
{
  std::uint64_t Seed = 1;
  int Count = 50;
  double TimeLimit = 60.0;
  int SoakFrames = 0;
  std::string Technique; ///< empty: every registered technique
  bool Verbose = false;
  double EnergySlack = stress::EnergySlack; ///< lower it to see the energy check fail
};

/** Ends the process when a scene runs past the time limit (a hang), naming its seed. */
class Watchdog
{
public:
  explicit Watchdog(double seconds)
    : Limit(seconds)
    , Thread([this] { this->Watch(); })
  {
  }
  ~Watchdog()
  {
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      this->Done = true;
    }
    this->Wake.notify_all();
    this->Thread.join();
  }
  void Start(std::uint64_t seed)
  {
    std::lock_guard<std::mutex> lock(this->Lock);
    this->Seed = seed;
    ++this->Scene;
    this->Wake.notify_all();
  }

private:
  void Watch()
  {
    std::unique_lock<std::mutex> lock(this->Lock);
    while (!this->Done)
    {
      const long scene = this->Scene;
      const auto limit = std::chrono::duration<double>(this->Limit);
      if (!this->Wake.wait_for(lock, limit, [&] { return this->Done || this->Scene != scene; }) &&
        scene > 0)
      {
        std::cout << "FAIL seed=" << this->Seed << ": hang, over " << this->Limit
                  << " s (replay: CausticsStress --seed " << this->Seed << " --count 1)"
                  << std::endl;
        std::_Exit(3);
      }
    }
  }

  double Limit;
  std::mutex Lock;
  std::condition_variable Wake;
  bool Done = false;
  long Scene = 0;
  std::uint64_t Seed = 0;
  std::thread Thread;
};

/** Checks of one frame; returns "" when it passed, else why not (one line). */
std::string CheckFrame(
  vtkCausticsRenderPass* pass, const stress::SceneSummary& scene, double slack, double& ratio)
{
  std::ostringstream why;
  const std::vector<std::string>& errors = stress::Messages::Errors();
  if (!errors.empty())
  {
    for (const std::string& error : errors)
    {
      if (error.find('\n') != std::string::npos || error.empty())
      {
        why << "an error of more than one line: " << error << "; ";
      }
    }
    if (pass->GetLastFrameHadCaustics())
    {
      why << "caustics rendered despite the error: " << errors.front();
    }
    return why.str(); // a clear refusal passes: nothing more to check
  }
  for (const std::string& name : stress::NonFiniteLayers(pass, !scene.VtkShadesNaN))
  {
    why << name << " has NaN/Inf" << (name == "CausticIrradiance" ? " or < 0" : "") << "; ";
  }
  const stress::Energy energy = stress::MeasureEnergy(pass);
  ratio = energy.Ratio();
  if (ratio > slack)
  {
    why << "caustic flux " << energy.Flux[0] << "," << energy.Flux[1] << "," << energy.Flux[2]
        << " W above the bound " << energy.Bound[0] << "," << energy.Bound[1] << ","
        << energy.Bound[2] << " W (ratio " << ratio << ")";
  }
  return why.str();
}

/** Renders scene `seed` with one technique; returns "" or why it failed. */
std::string RenderWith(const std::string& technique, vtkRenderWindow* window,
  vtkOpenGLRenderer* renderer, const stress::SceneSummary& scene, const Options& options,
  double& ratio)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
  pass->SetLightBufferResolution(scene.Photons);
  pass->SetShadowMapResolution(128);
  pass->ComputeDirectIrradianceOn();
  pass->KeepBuffersOn();
  renderer->SetPass(pass);
  stress::Messages::Clear();
  window->Render();
  std::string why = CheckFrame(pass, scene, options.EnergySlack, ratio);
  if (options.Verbose)
  {
    std::cout << "  " << technique << ": "
              << (pass->GetLastFrameHadCaustics() ? "caustics" : "none") << ", flux/bound " << ratio
              << ", " << stress::Messages::Errors().size() << " errors, "
              << stress::Messages::Warnings() << " warnings" << std::endl;
    for (const std::string& error : stress::Messages::Errors())
    {
      std::cout << "    error: " << error << std::endl;
    }
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  const vtkCausticsRenderPass::GraphicsMemory left = vtkCausticsRenderPass::GetGraphicsMemory();
  if (left.Objects() != 0 || left.Bytes() != 0)
  {
    why += "ReleaseGraphicsResources left " + std::to_string(left.Objects()) + " objects, " +
      std::to_string(left.Bytes()) + " bytes";
  }
  return why;
}

/** One scene, every technique. Returns true if it passed; prints why not. */
bool RunScene(std::uint64_t seed, const Options& options, double& worstRatio)
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkOpenGLRenderer> renderer;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  const stress::SceneSummary scene = stress::MakeScene(seed, renderer);
  window->SetSize(scene.Width, scene.Height);
  if (options.Verbose)
  {
    std::cout << "seed=" << seed << ": " << scene.Text << std::endl;
  }
  bool passed = true;
  const std::vector<std::string> techniques = options.Technique.empty()
    ? vtkCausticsTechniques::GetNames()
    : std::vector<std::string>{ options.Technique };
  for (const std::string& technique : techniques)
  {
    double ratio = 0.0;
    const std::string why = RenderWith(technique, window, renderer, scene, options, ratio);
    worstRatio = std::max(worstRatio, ratio);
    if (!why.empty())
    {
      std::cout << "FAIL seed=" << seed << " technique=" << technique << ": " << why
                << "\n  scene: " << scene.Text << "\n  replay: CausticsStress --seed " << seed
                << " --count 1 --technique " << technique << std::endl;
      passed = false;
    }
  }
  return passed;
}

int RunScenes(const Options& options)
{
  stress::Messages::Install();
  Watchdog watchdog(options.TimeLimit);
  const auto start = std::chrono::steady_clock::now();
  int failures = 0;
  double worstRatio = 0.0;
  for (int k = 0; k < options.Count; ++k)
  {
    const std::uint64_t seed = options.Seed + static_cast<std::uint64_t>(k);
    watchdog.Start(seed);
    failures += RunScene(seed, options, worstRatio) ? 0 : 1;
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "stress: " << options.Count << " scenes (seeds " << options.Seed << " to "
            << options.Seed + options.Count - 1 << "), " << failures << " failed, " << seconds
            << " s; largest caustic flux / bound " << worstRatio << std::endl;
  return failures == 0 ? 0 : 1;
}

bool Parse(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--verbose")
    {
      options.Verbose = true;
    }
    else if (hasValue && arg == "--seed")
    {
      options.Seed = std::stoull(argv[++i]);
    }
    else if (hasValue && arg == "--count")
    {
      options.Count = std::stoi(argv[++i]);
    }
    else if (hasValue && arg == "--time-limit")
    {
      options.TimeLimit = std::stod(argv[++i]);
    }
    else if (hasValue && arg == "--soak")
    {
      options.SoakFrames = std::stoi(argv[++i]);
    }
    else if (hasValue && arg == "--energy-slack")
    {
      options.EnergySlack = std::stod(argv[++i]);
    }
    else if (hasValue && arg == "--technique")
    {
      options.Technique = argv[++i];
    }
    else
    {
      return false;
    }
  }
  return options.Count > 0 && options.TimeLimit > 0.0 && options.SoakFrames >= 0;
}
}

int main(int argc, char* argv[])
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique(); // every technique, the CPU one too
  Options options;
  bool parsed = false;
  try
  {
    parsed = Parse(argc, argv, options);
  }
  catch (const std::exception&)
  {
    parsed = false;
  }
  if (!parsed || (!options.Technique.empty() && !vtkCausticsTechniques::Create(options.Technique)))
  {
    std::cerr << "usage: CausticsStress [--seed S] [--count N] [--time-limit SECONDS] "
                 "[--technique NAME] [--energy-slack X] [--verbose]\n"
                 "       CausticsStress --soak FRAMES [--technique NAME] [--verbose]\n";
    return 2;
  }
  if (options.SoakFrames > 0)
  {
    return stress::RunSoak(options.SoakFrames, options.Technique, options.Verbose) ? 0 : 1;
  }
  return RunScenes(options);
}
