// caustics-render: renders a built-in caustics scene, a glTF 2.0 file or a mesh
// with one of the module's techniques, to PNG (display) and EXR (physical layers).
//
//   caustics-render [options] [SCENE | FILE.gltf | FILE.glb | FILE.ply|obj|stl]
//
// Every error is one line on stderr naming the problem, and a non-zero exit:
// 2 for bad arguments, 3 when no OpenGL window can be made, 1 for anything else.
#include "CausticsCommandLine.h"
#include "CausticsSceneOptions.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsDeviceLimits.h"
#include "vtkCausticsGLTFImporter.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsImageIO.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsMedium.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsProgressivePhotonPass.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsWindowFactory.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLogger.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOutputWindow.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
const char* UsageHead =
  R"(usage: caustics-render [options] [SCENE | FILE.gltf | FILE.glb | MESH.ply|obj|stl]

Renders caustics with a VTK render pass and writes PREFIX.png (display colour)
and PREFIX.exr (linear HDR layers: R,G,B final colour; direct.*, caustic.*:
irradiance in W/m^2 at each pixel's visible surface before albedo; volume.*:
in-scattered radiance in W/(m^2 sr); mask.Y: 1 where a receiver is visible).
)";

const char* UsageTail = R"(
Output:
  --output PREFIX            output file prefix (default: caustics)
  --exposure E               multiplier applied before the PNG's 8-bit clamp (default 1)
  --timings                  print per-stage GPU and CPU times (ms, a table)
  --help                     this text

Ground truth:
  --reference                also render the CPU reference (Embree) of the same view
                             to PREFIX-reference.exr: caustic.*, direct.* (W/m^2,
                             at the same surfaces as PREFIX.exr's: under water and
                             glass), volume.* (W/(m^2 sr)), mask.Y; shows its progress
  --reference-photons N      its photons per light, 1..1e10 (default 1e6); implies
                             --reference
  --reference-kernel R       radius of its density-estimation kernel in pixel
                             footprints, in [0.25, 64] (default 2, the reference
                             renderer's; caustics-bench's ground truth takes 1: a
                             radius of 2 halves the peak of a line one pixel wide),
                             or pixel: the flux landing in each pixel's footprint
                             over its area, the pixel's mean with no blur
  --no-reference-cache       render it even when a cached result exists
)";

/** What caustics-render does with the scene: its frames, outputs and ground truth. */
struct Options : caustics_cli::SceneOptions
{
  std::string Output = "caustics";
  int Frames = 1;
  double Exposure = 1.0;
  bool Timings = false;
  bool Reference = false;
  double ReferencePhotons = 1e6;
  double ReferenceKernel = 2.0;
  bool ReferenceCache = true;
};

using caustics_cli::NoWindowError;
using caustics_cli::ParseInteger;
using caustics_cli::ParseNumber;
using caustics_cli::UsageError;

void DeclareOutputOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Value("--frames",
    [&options](const std::string& option, const std::string& value)
    { options.Frames = ParseInteger(option, value, 1, 10000); });
  arguments.Value("--output", caustics_cli::Text(options.Output));
  arguments.Value("--exposure",
    [&options](const std::string& option, const std::string& value)
    {
      options.Exposure = ParseNumber(option, value);
      if (options.Exposure <= 0.0)
      {
        throw UsageError("--exposure must be > 0");
      }
    });
  arguments.Flag("--timings", [&options] { options.Timings = true; });
}

void DeclareReferenceOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Flag("--reference", [&options] { options.Reference = true; });
  arguments.Value("--reference-photons",
    [&options](const std::string& option, const std::string& value)
    {
      options.ReferencePhotons = caustics_cli::ParseCount(option, value, 1, 1e10);
      options.Reference = true;
    });
  arguments.Value("--reference-kernel",
    [&options](const std::string& option, const std::string& value)
    {
      options.Reference = true;
      if (value == "pixel")
      {
        options.ReferenceKernel = 0.0; // the pixel-footprint estimate
        return;
      }
      // A number where it is not "pixel": the message names both.
      const bool number = value.find_first_not_of("0123456789.eE+-") == std::string::npos;
      options.ReferenceKernel = number ? ParseNumber(option, value) : -1.0;
      if (!(options.ReferenceKernel >= 0.25 && options.ReferenceKernel <= 64.0))
      {
        throw UsageError(option + " expects a radius in [0.25, 64] pixel footprints, or pixel");
      }
    });
  arguments.Flag("--no-reference-cache", [&options] { options.ReferenceCache = false; });
}

Options Parse(int argc, char* argv[], bool& help)
{
  Options options;
  help = false;
  bool sceneGiven = false;
  caustics_cli::Arguments arguments;
  arguments.Flag("--help", [&help] { help = true; });
  arguments.Flag("-h", [&help] { help = true; });
  caustics_cli::DeclareSceneOptions(arguments, options, sceneGiven);
  DeclareOutputOptions(arguments, options);
  DeclareReferenceOptions(arguments, options);
  caustics_cli::FinishSceneOptions(arguments.Parse(argc, argv), options, sceneGiven);
  // The output of --progressive N is the mean of N frames: render them all.
  options.Frames = std::max(options.Frames, options.ProgressiveFrames);
  return options;
}

/** Copies buffer `name` of the pass into `output` as array `as`, if the frame made it. */
bool CopyBuffer(vtkCausticsRenderPass* pass, const char* name, const char* as, vtkImageData* output)
{
  vtkNew<vtkImageData> buffer;
  pass->GlobalWarningDisplayOff();
  const bool ok = pass->ReadBuffer(name, buffer);
  pass->GlobalWarningDisplayOn();
  if (!ok)
  {
    return false;
  }
  vtkDataArray* array = buffer->GetPointData()->GetArray(0);
  array->SetName(as);
  output->GetPointData()->AddArray(array);
  return true;
}

/** The median of the known (non-negative) values; NaN when none is known. */
double Median(std::vector<double> values)
{
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !(v >= 0.0); }),
    values.end());
  if (values.empty())
  {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/**
 * VTK's messages, kept to one line each: errors are remembered (the run then fails
 * naming the first one), warnings are printed as "caustics-render: warning: ...".
 */

/** Each stage's GPU and CPU times over the frames, in the order the stages first ran. */
struct StageTimes
{
  std::vector<std::string> Order;
  std::map<std::string, std::vector<double>> GPU, CPU;
  std::vector<double> Frames;    // wall time of each frame
  std::vector<double> FramesCPU; // CPU time of the process (all its threads) in each frame

  void Add(vtkCausticsTimings* timings)
  {
    for (int s = 0; s < timings->GetNumberOfStages(); ++s)
    {
      const std::string name = timings->GetStageName(s);
      if (!timings->GetStageRan(s))
      {
        continue;
      }
      if (!this->GPU.count(name))
      {
        this->Order.push_back(name);
      }
      this->GPU[name].push_back(timings->GetStageGPUMilliseconds(s));
      this->CPU[name].push_back(timings->GetStageCPUMilliseconds(s));
    }
  }
};

vtkSmartPointer<vtkRenderWindow> MakeWindow(const Options& options, std::string& how)
{
  vtkSmartPointer<vtkRenderWindow> window = vtkCausticsWindowFactory::Create(true, &how);
  if (!window)
  {
    throw NoWindowError(how);
  }
  window->SetMultiSamples(0);
  window->SetSize(options.Width, options.Height);
  return window;
}

/** The technique's pass, keeping its buffers for read-back, with synchronous timings. */
vtkSmartPointer<vtkCausticsRenderPass> MakePass(const Options& options, vtkRenderer* renderer)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass = caustics_cli::MakePass(options, renderer);
  pass->KeepBuffersOn();
  pass->ComputeDirectIrradianceOn();
  pass->GetTimings()->SynchronousOn();
  return pass;
}

StageTimes RenderFrames(
  const Options& options, vtkRenderWindow* window, vtkCausticsRenderPass* pass)
{
  StageTimes times;
  // Frames over 2 s say how far they are (issue 17).
  caustics_cli::FrameProgress progress(pass->GetTimings(), "caustics-render", options.Frames);
  for (int frame = 0; frame < options.Frames; ++frame)
  {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    progress.NextFrame();
    window->Render();
    times.Frames.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    times.FramesCPU.push_back(1000.0 * static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC);
    times.Add(pass->GetTimings());
  }
  return times;
}

/**
 * The last frame's buffers as arrays of one image, and the EXR layers they become
 * (array name, layer prefix). A frame without a caustic stage gets a zero caustic layer.
 */
vtkSmartPointer<vtkImageData> ReadLayers(const Options& options, vtkCausticsRenderPass* pass,
  std::vector<std::pair<std::string, std::string>>& layers)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(options.Width, options.Height, 1);
  if (!CopyBuffer(pass, "FinalColor", "FinalColor", image))
  {
    throw std::runtime_error("the frame produced no image (see the errors above)");
  }
  layers = { { "FinalColor", "" } };
  if (CopyBuffer(pass, "DirectIrradiance", "DirectIrradiance", image))
  {
    layers.emplace_back("DirectIrradiance", "direct");
  }
  if (!CopyBuffer(pass, "CausticIrradiance", "CausticIrradiance", image))
  {
    // No caustic stage ran (no specular actor or light): the caustic term is zero.
    vtkNew<vtkFloatArray> zero;
    zero->SetName("CausticIrradiance");
    zero->SetNumberOfComponents(3);
    zero->SetNumberOfTuples(static_cast<vtkIdType>(options.Width) * options.Height);
    zero->Fill(0.0);
    image->GetPointData()->AddArray(zero);
  }
  layers.emplace_back("CausticIrradiance", "caustic");
  if (CopyBuffer(pass, "VolumeRadiance", "VolumeRadiance", image))
  {
    layers.emplace_back("VolumeRadiance", "volume");
  }
  if (CopyBuffer(pass, "ReceiverMask", "ReceiverMask", image))
  {
    layers.emplace_back("ReceiverMask", "mask");
  }
  return image;
}

void WriteImages(const Options& options, vtkImageData* image,
  const std::vector<std::pair<std::string, std::string>>& layers)
{
  std::string error;
  const std::string png = options.Output + ".png", exr = options.Output + ".exr";
  if (!vtkCausticsImageIO::WritePNG(image, "FinalColor", png, options.Exposure, false, &error) ||
    !vtkCausticsImageIO::WriteEXR(image, layers, exr, &error))
  {
    throw std::runtime_error(error);
  }
}

/**
 * Where the last frame's photons' light went, after the timings
 * (caustics_cli::DescribePhotonLight): with --timings a line of shares, and always a
 * warning when the light lost on paths the technique cannot follow may be more than
 * a tenth of the caustic.
 */
void ReportPhotonStatistics(
  const Options& options, vtkCausticsRenderPass* pass, const std::string& technique)
{
  std::string warning;
  const std::string line = caustics_cli::DescribePhotonLight(pass, technique, warning);
  if (options.Timings && !line.empty())
  {
    std::cout << "caustics-render: " << line << "\n";
  }
  if (!warning.empty())
  {
    std::cout.flush(); // the warning follows what was printed before it
    std::cerr << "caustics-render: warning: " << warning << "\n";
  }
}

void PrintSummary(const Options& options, vtkCausticsRenderPass* pass, const std::string& how,
  const std::string& technique)
{
  const auto& scene = pass->GetSceneExtractor()->GetScene();
  std::cout << "caustics-render: " << options.Scene << ", technique "
            << technique
            << ", " << options.Width << "x" << options.Height << ", window " << how << ", "
            << scene.Meshes.size() << " meshes, " << scene.Lights.size() << " light(s)"
            << (pass->GetLastFrameHadCaustics() ? "" : " (no caustic stage needed)") << "\n";
  auto* screenSpace = vtkCausticsScreenSpacePhotonPass::SafeDownCast(pass);
  if (screenSpace && pass->GetLastFrameHadCaustics())
  {
    std::cout << "caustics-render: photons traced in "
              << (screenSpace->GetLastTraceViewFitted()
                     ? "a fitted view around the reflectors and refractors (one is outside "
                       "the camera's view, or --trace-view fitted)"
                     : "the camera's view")
              << "\n";
  }
  if (pass->GetProgressiveFrames() > 1 && pass->GetLastFrameHadCaustics())
  {
    std::cout << "caustics-render: caustic and volume layers are the mean of "
              << pass->GetFramesAveraged() << " frame(s)\n";
  }
  std::cout << "wrote " << options.Output << ".png and " << options.Output << ".exr\n";
}

/**
 * The per-stage table: one row per stage that ran, columns wide enough for the
 * longest name; "-" where a time is not known (a CPU-only stage has no GPU time).
 */
void PrintTimings(const Options& options, StageTimes& times)
{
  const std::string wall = "whole frame (wall clock)";
  const std::string processCPU = "whole frame (process cpu)";
  std::size_t width = processCPU.size();
  for (const auto& name : times.Order)
  {
    width = std::max(width, name.size());
  }
  auto row = [width](const std::string& name, const std::string& gpu, const std::string& cpu)
  {
    std::cout << "  " << std::left << std::setw(static_cast<int>(width)) << name << std::right
              << std::setw(12) << gpu << std::setw(12) << cpu << "\n";
  };
  auto cell = [](double milliseconds)
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << milliseconds;
    return std::isnan(milliseconds) ? std::string("-") : text.str();
  };
  std::cout << "per-stage time in ms, median of " << options.Frames << " frame(s):\n";
  row("stage", "gpu", "cpu");
  for (const auto& name : times.Order)
  {
    row(name, cell(Median(times.GPU[name])), cell(Median(times.CPU[name])));
  }
  row(wall, "-", cell(Median(times.Frames)));
  // llvmpipe's threads included: a figure the machine's load stretches far less.
  row(processCPU, "-", cell(Median(times.FramesCPU)));
  // What a process's first frame pays for besides the stages' work.
  const caustics::gl::GraphicsCounts memory = caustics::gl::CountGraphicsMemory();
  std::cout << "graphics memory held by the caustics stages: " << memory.Textures
            << " textures, " << caustics::gl::FormatBytes(static_cast<double>(memory.TextureBytes))
            << "; " << memory.Buffers << " buffers, "
            << caustics::gl::FormatBytes(static_cast<double>(memory.BufferBytes)) << "\n"
            << "programs compiled and linked: " << vtkCausticsShaderProgram::GetNumberOfBuilds()
            << ", " << cell(vtkCausticsShaderProgram::GetBuildMilliseconds())
            << " ms (Mesa's on-disk shader cache makes them fast after a first run)\n";
}

/**
 * --reference: the CPU ground truth of the same view (vtkCausticsReferenceRenderer)
 * to PREFIX-reference.exr, showing its progress while it runs.
 */
void RenderReference(const Options& options, vtkRenderer* renderer)
{
  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(options.Width, options.Height);
  reference->SetPhotonsPerLight(static_cast<vtkIdType>(options.ReferencePhotons));
  if (options.ReferenceKernel > 0.0)
  {
    reference->SetKernelRadiusPixels(options.ReferenceKernel);
  }
  else
  {
    reference->PixelFootprintEstimateOn();
  }
  reference->SetUseCache(options.ReferenceCache);
  // The technique's layers hold the irradiance at each pixel's nearest opaque
  // surface (the pool's floor under the water): the reference's must be at the
  // same points, or PREFIX.exr and PREFIX-reference.exr cannot be compared.
  reference->CameraSeesRefractorsOff();
  std::ostringstream label;
  label << "caustics-render: reference, " << static_cast<long long>(options.ReferencePhotons)
        << " photons per light";
  bool ok = false;
  {
    caustics_cli::ProgressReport progress(reference, label.str());
    ok = reference->Update();
  }
  if (!ok)
  {
    throw std::runtime_error(std::string("the reference failed: ") + reference->GetLastError());
  }
  const std::string exr = options.Output + "-reference.exr";
  std::string error;
  if (!vtkCausticsImageIO::WriteEXR(reference->GetOutput(),
        { { "CausticIrradiance", "caustic" }, { "DirectIrradiance", "direct" },
          { "VolumeRadiance", "volume" }, { "ReceiverMask", "mask" } },
        exr, &error))
  {
    throw std::runtime_error(error);
  }
  std::cout << "wrote " << exr << " (reference, "
            << (reference->GetLoadedFromCache() ? "from its cache" : "rendered") << " in "
            << caustics_cli::FormatSeconds(reference->GetWallTime()) << "; ";
  if (options.ReferenceKernel > 0.0)
  {
    std::cout << "kernel radius " << options.ReferenceKernel << " pixel footprints)\n";
  }
  else
  {
    std::cout << "the flux in each pixel's footprint)\n";
  }
}

int Run(const Options& options)
{
  std::string how;
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options, how);
  vtkNew<vtkOpenGLRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsBuiltinScene> builtin;
  caustics_cli::LoadScene(options, window, renderer, builtin);
  caustics_cli::ApplyOverrides(options, renderer);
  // `best` is chosen once: the choice walks every mesh (closed, convex).
  Options chosen = options;
  chosen.Technique = caustics_cli::TechniqueFor(options, renderer);
  vtkSmartPointer<vtkCausticsRenderPass> pass = MakePass(chosen, renderer);
  renderer->SetPass(pass);
  // Refuse a photon grid this OpenGL cannot hold before anything is allocated (the
  // frame checks again with the scene's lights: no outputs then either).
  if (!pass->CheckResources(window))
  {
    throw std::runtime_error(pass->GetResourceError());
  }
  StageTimes times = RenderFrames(options, window, pass);
  if (*pass->GetResourceError())
  {
    throw std::runtime_error(pass->GetResourceError());
  }

  std::vector<std::pair<std::string, std::string>> layers;
  vtkSmartPointer<vtkImageData> image = ReadLayers(options, pass, layers);
  WriteImages(options, image, layers);
  PrintSummary(options, pass, how, chosen.Technique);
  if (options.Timings)
  {
    PrintTimings(options, times);
  }
  ReportPhotonStatistics(options, pass, chosen.Technique);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  if (options.Reference)
  {
    RenderReference(options, renderer);
  }
  return 0;
}

/** The usage text with the registered techniques filled in. */
std::string UsageText()
{
  return std::string(UsageHead) + "\n" + caustics_cli::SceneUsage + "\nTechnique and quality:\n" +
    caustics_cli::QualityUsage() +
    "  --frames N                 frames rendered; timings are their median (default 1;\n"
    "                             at least N with --progressive N)\n\n" +
    caustics_cli::OverridesUsage + UsageTail;
}
}

int main(int argc, char* argv[])
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique(); // the CPU technique, by name
  return caustics_cli::RunMain("caustics-render", caustics_cli::LoggedErrors::Fail,
    [&](caustics_cli::OneLineOutputWindow*)
    {
      bool help = false;
      const Options options = Parse(argc, argv, help);
      if (help)
      {
        std::cout << UsageText();
        return 0;
      }
      return Run(options);
    });
}
