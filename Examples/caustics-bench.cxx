// caustics-bench: run time against error of the caustics techniques, measured on the
// built-in scenes against the CPU reference renderer.
//
//   caustics-bench [options]
//
// For each scene x technique x configuration (a quality knob setting), it renders
// warm-up frames, then timed frames, and records the median wall time per frame, the
// median GPU time of each stage (timer queries) and the error of the caustic
// irradiance against a cached high-photon-count reference. It also times the
// reference itself at several photon counts: what the same error costs offline.
// Results: benchmarks.csv (one row per configuration), benchmark-stages.csv (one row
// per stage), benchmarks.png (via scripts/plot-benchmarks.py) in the output folder;
// --update-docs rewrites the generated section of docs/benchmarks.md.
// With --animate N it measures temporal stability instead (CausticsBenchTemporal.h):
// N frames of animated sequences per technique, flicker, error under motion, lag and
// ghosting after a cut, into temporal.csv and the "Temporal stability" section.
//
// Every error is one line on stderr naming the problem, and a non-zero exit:
// 2 for bad arguments, 3 when no OpenGL window can be made, 1 for anything else.
#include "CausticsBenchTable1.h"
#include "CausticsBenchTemporal.h"
#include "CausticsBenchVolume.h"
#include "CausticsCommandLine.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"
#include "vtkCausticsImageIO.h"
#include "vtkCausticsImpostorPhotonPass.h"
#include "vtkCausticsProgressivePhotonPass.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"
#include "vtkCausticsWindowFactory.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h> // For WIFEXITED / WEXITSTATUS of std::system

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------
// The quality sweeps: every technique's configurations, declared here and only here.
// ---------------------------------------------------------------------------

/**
 * One configuration of one technique. Knobs are "name=value" pairs separated by
 * spaces (the CSV's knobs column and the docs' table); Apply sets them on a new pass
 * of the technique and returns false when the pass is not of the class the entry
 * was written for (the registry and this table disagree).
 */
struct Configuration
{
  std::string Technique;
  std::string Knobs;
  std::function<bool(vtkCausticsRenderPass*)> Apply;
};

/** An Apply function that downcasts the pass to PassType (SafeDownCast) and calls `set`. */
template <typename PassType>
std::function<bool(vtkCausticsRenderPass*)> Set(std::function<void(PassType*)> set)
{
  return [set](vtkCausticsRenderPass* pass)
  {
    PassType* typed = PassType::SafeDownCast(pass);
    if (!typed)
    {
      return false;
    }
    set(typed);
    return true;
  };
}

/**
 * Screen-space photon tracing (docs/technique-screen-space.md): the photon grid
 * N x N per light at the default layer cap, then the layer cap at N = 256, then its
 * splat kernel, then caustic triangles instead of splats.
 */
void AddScreenSpaceConfigurations(std::vector<Configuration>& table)
{
  auto add = [&table](int grid, int layers, double splat, bool triangles = false)
  {
    std::string knobs = "grid=" + std::to_string(grid) + " layers=" + std::to_string(layers);
    knobs += splat > 0.0 ? " splat=1" : "";
    knobs += triangles ? " triangles" : "";
    table.push_back({ "screen-space", knobs,
      Set<vtkCausticsScreenSpacePhotonPass>(
        [grid, layers, splat, triangles](vtkCausticsScreenSpacePhotonPass* pass)
        {
          pass->SetLightBufferResolution(grid);
          pass->SetMaximumNumberOfLayers(layers);
          if (splat > 0.0)
          {
            pass->SetSplatRadiusPixels(splat);
          }
          pass->SetReconstruction(triangles ? 1 : 0);
        }) });
  };
  for (int grid : { 64, 128, 256, 512 })
  {
    add(grid, 8, 0.0);
  }
  for (int layers : { 1, 2, 4 })
  {
    add(256, layers, 0.0);
  }
  // The default radius of 2 pixel footprints against 1 (sharper, noisier) at N = 256
  // and 512, since the ground truth's own kernel is 1 footprint.
  for (int grid : { 256, 512 })
  {
    add(grid, 8, 1.0);
  }
  // Caustic triangles (docs/accuracy.md, "Caustic triangles against splats").
  for (int grid : { 256, 512 })
  {
    add(grid, 8, 0.0, true);
  }
}

/**
 * A technique's caustic triangles (its SetReconstructionToTriangles(), the shared
 * reconstruction's) at photon grids 256^2 and 512^2, knobs "grid=N triangles".
 */
template <typename PassType>
void AddTriangleRows(std::vector<Configuration>& table, const char* technique)
{
  for (int grid : { 256, 512 })
  {
    table.push_back({ technique, "grid=" + std::to_string(grid) + " triangles",
      Set<PassType>(
        [grid](PassType* pass)
        {
          pass->SetLightBufferResolution(grid);
          pass->SetReconstructionToTriangles();
        }) });
  }
}

using HCM = vtkCausticsHierarchicalCausticMapPass;

/** A variant of the hierarchical caustic map (the paper's Table 3). */
struct Variant
{
  const char* Name;
  int Gather, Cluster, Splat;
};

/**
 * A caustic-map configuration. map: caustic-map resolution (0: the pass's default);
 * cameraFloor: its MinimumCameraSplatRadius (the default 1 is not named in the knobs);
 * incidence: its MinimumMapIncidence in degrees (negative: the default, not named);
 * maxDistance: its MaxDistanceFraction (negative: the default, not named).
 */
void AddCausticMap(std::vector<Configuration>& table, int grid, const Variant& variant, int map = 0,
  double cameraFloor = 1.0, int incidence = -1, double maxDistance = -1.0)
{
  std::string knobs = "grid=" + std::to_string(grid) + " variant=" + variant.Name;
  knobs += map > 0 ? " map=" + std::to_string(map) : "";
  knobs += cameraFloor == 0.0 ? " camera-floor=off" : "";
  knobs += incidence >= 0 ? " map-incidence=" + std::to_string(incidence) : "";
  if (maxDistance >= 0.0)
  {
    std::ostringstream fraction; // 1, 0.5: the shortest form
    fraction << maxDistance;
    knobs += " max-distance=" + fraction.str();
  }
  table.push_back({ "caustic-maps", knobs,
    Set<HCM>(
      [grid, variant, map, cameraFloor, incidence, maxDistance](HCM* pass)
      {
        if (incidence >= 0)
        {
          pass->SetMinimumMapIncidence(incidence);
        }
        if (maxDistance >= 0.0)
        {
          pass->SetMaxDistanceFraction(maxDistance);
        }
        pass->SetLightBufferResolution(grid);
        pass->SetGatherMode(variant.Gather);
        pass->SetClusterMode(variant.Cluster);
        pass->SetSplatMode(variant.Splat);
        if (map > 0)
        {
          pass->SetCausticMapResolution(map);
        }
        pass->SetMinimumCameraSplatRadius(cameraFloor);
      }) });
}

/**
 * Hierarchical caustic maps (docs/technique-caustic-maps.md): the default
 * (hierarchical gather, clustering at the last level, Eq. 2 splats into the
 * multi-resolution map) over photon buffers 256^2..2048^2; the baselines and the
 * other clustering variants at 256^2 and 1024^2; then the map's own resolution.
 */
void AddCausticMapConfigurations(std::vector<Configuration>& table)
{
  const Variant defaultVariant = { "varying-multires", HCM::GATHER_HIERARCHICAL,
    HCM::CLUSTER_LAST_LEVEL, HCM::SPLAT_VARYING_MULTIRES };
  const Variant variants[] = {
    { "flat", HCM::GATHER_FLAT, HCM::CLUSTER_NONE, HCM::SPLAT_CONSTANT },
    { "hierarchical", HCM::GATHER_HIERARCHICAL, HCM::CLUSTER_NONE, HCM::SPLAT_CONSTANT },
    { "combine-last", HCM::GATHER_HIERARCHICAL, HCM::CLUSTER_LAST_LEVEL, HCM::SPLAT_CONSTANT },
    { "combine-all", HCM::GATHER_HIERARCHICAL, HCM::CLUSTER_ALL_LEVELS, HCM::SPLAT_CONSTANT },
  };
  for (int grid : { 256, 512, 1024, 2048 })
  {
    AddCausticMap(table, grid, defaultVariant);
  }
  for (int grid : { 256, 1024 })
  {
    for (const Variant& variant : variants)
    {
      AddCausticMap(table, grid, variant);
    }
  }
  // The caustic map's own resolution (the default 512^2 texels over the light's view of
  // the whole scene) at 1024^2 photons, with and without the kernels' floor of one
  // camera pixel (MinimumCameraSplatRadius): where the error stops falling with
  // photons, it shows whether the map's texels are what limits it, and that the
  // floor makes the result independent of them.
  for (double cameraFloor : { 1.0, 0.0 })
  {
    for (int map : { 256, 512, 1024, 2048 })
    {
      if (cameraFloor == 1.0 && map == 512)
      {
        continue; // the defaults: "grid=1024 variant=varying-multires" above
      }
      AddCausticMap(table, 1024, defaultVariant, map, cameraFloor);
    }
  }
  // The least angle at which the map's view sees the receivers (MinimumMapIncidence):
  // 0 is the paper's light view whatever the light's angle.
  for (int incidence : { 0, 20, 45, 60 })
  {
    AddCausticMap(table, 256, defaultVariant, 0, 1.0, incidence);
  }
  // Eq. 2's spacing: the paper's max distance (1) against the beam's mean width
  // (MaxDistanceFraction, default 0.5), which keeps folds and cusps sharp.
  for (int grid : { 256, 1024 })
  {
    AddCausticMap(table, grid, defaultVariant, 0, 1.0, -1, 1.0);
  }
  // Caustic triangles in the camera's view instead of the map's splats (docs/accuracy.md,
  // "Caustic triangles against splats").
  AddTriangleRows<HCM>(table, "caustic-maps");
}

/**
 * The sweep of every technique, in the order the CSV and the docs list them. A
 * technique registered in vtkCausticsTechniques without entries here runs once with
 * its defaults (knobs "default").
 */
std::vector<Configuration> MakeConfigurations()
{
  std::vector<Configuration> table;
  AddScreenSpaceConfigurations(table);
  AddCausticMapConfigurations(table);
  // Caustics via distance impostors (docs/technique-distance-impostors.md): one photon
  // per light-buffer texel and Fresnel branch, traced against the cube maps.
  for (int grid : { 128, 256, 512 })
  {
    table.push_back({ "impostors", "grid=" + std::to_string(grid),
      Set<vtkCausticsImpostorPhotonPass>(
        [grid](vtkCausticsImpostorPhotonPass* pass) { pass->SetLightBufferResolution(grid); }) });
  }
  // Their caustic triangles (the shared reconstruction's).
  AddTriangleRows<vtkCausticsImpostorPhotonPass>(table, "impostors");
  // The CPU technique, one independent estimate per frame (its accumulated frames are
  // one estimate from that many times the photons): its cost against its error.
  for (int grid : { 128, 256, 512, 1024 })
  {
    table.push_back(
      { "cpu-progressive", "grid=" + std::to_string(grid) + " kernel=1 progressive=off",
        Set<vtkCausticsProgressivePhotonPass>(
          [grid](vtkCausticsProgressivePhotonPass* pass)
          {
            pass->SetLightBufferResolution(grid);
            pass->SetKernelRadiusPixels(1.0);
            pass->ProgressiveOff();
          }) });
  }
  // "none": the shared stages (snapshot, VTK delegate, G-buffers, light buffers,
  // composite) with no technique. Its cost at each photon-grid size the techniques
  // use is their cost floor; its error (1: no caustic light) is the ceiling.
  for (int grid : { 64, 128, 256, 512 })
  {
    table.push_back({ "none", "grid=" + std::to_string(grid),
      Set<vtkCausticsRenderPass>(
        [grid](vtkCausticsRenderPass* pass) { pass->SetLightBufferResolution(grid); }) });
  }
  return table;
}

// ---------------------------------------------------------------------------
// Command line.
// ---------------------------------------------------------------------------

const char* Usage = R"(usage: caustics-bench [options]

Measures run time against error of the caustics techniques on the built-in scenes.
For each scene x technique x configuration: median wall time per frame, median GPU
time per stage (timer queries), and the error of the caustic irradiance (W/m^2) on
receiver pixels against a high-photon-count CPU reference (cached). Also times the
reference at several photon counts (its error against the high-count one), i.e.
what the same error costs offline. Writes benchmarks.csv, benchmark-stages.csv and
benchmarks.png (scripts/plot-benchmarks.py, needs matplotlib) to the output folder.

Selection:
  --scenes A,B,...           built-in scenes (default: ball-lens,pool,ring,bunny)
  --techniques A,B,...       techniques (default: every registered one, then none)
  --list                     print the scenes, techniques and configurations, and exit
  --defaults                 each technique once with its own defaults (knobs
                             "default") instead of its configurations
  --knobs TEXT               only the configurations whose knobs contain TEXT
                             (e.g. "map-incidence", "grid=256 ")

Measurement:
  --size N                   image size N x N pixels, 16..4096 (default 256)
  --frames N                 timed frames per configuration, 5..1000 (default 7)
  --warmup N                 untimed frames first, 2..100 (default 2)
  --reference-photons N      photons per light of the ground truth (default 2e7);
                             cached in $CAUSTICS_REFERENCE_CACHE or ~/.cache/vtkcaustics
  --reference-ladder A,B,... photon counts at which the reference is timed, each
                             below --reference-photons (default 1e5,1e6,1e7)
  --reference-repeats N      renders per ladder count, 1..20; the median time is
                             kept; a count stops repeating once its runs took 30 s
                             (default 3)
  --reference-kernel R       radius of the reference's density-estimation kernel in
                             pixel footprints, ground truth and ladder, in [0.25, 64]
                             (default 1; vtkCausticsReferenceRenderer's own default
                             is 2), or pixel: the flux landing in each pixel's
                             footprint over its area (PixelFootprintEstimate)

Output:
  --output DIR               output folder, created if needed (default: caustics-bench-results)
  --no-plot                  do not run scripts/plot-benchmarks.py
  --images                   also write each configuration's caustic irradiance
                             (W/m^2, last frame) to images/SCENE_TECHNIQUE_KNOBS.exr
                             in the output folder, to look at what the error measures
  --python PATH              Python with matplotlib for the plot (default:
                             $CAUSTICS_PYTHON, else /usr/bin/python3, else python3)
  --update-docs              rewrite the generated section of docs/benchmarks.md and
                             copy the plot to docs/benchmarks.png
  --docs FILE                the Markdown file --update-docs rewrites (default:
                             docs/benchmarks.md in the current folder, the repository root)

  --smoke                    tiny run for CI: the first scene at 64 x 64, the first
                             configuration of each technique, 1 warm-up + 2 timed
                             frames, reference 1e5 photons, ladder 1e4,3e4 run once
                             (with --animate: every sequence at 64 x 64, light
                             buffers 64 x 64, 1 warm-up frame, reference 1e5 photons)

Volume caustics (docs/technique-volume-caustics.md):
  --volume                   instead of the sweep: the line-based volume caustics
                             (vtkCausticsVolumeLines) of each technique that writes
                             volume lines (--techniques, default: screen-space,
                             caustic-maps,cascaded) on --scenes (default:
                             smoke-lens,underwater) at --size: frame time against the
                             volume caustic's error for each photon grid and
                             sub-segment count, and 003's Table 2 analogue (photon
                             grid x screen size -> frame time) per technique on the
                             first scene; writes volume.md
  --volume-grids A,B,...     photon grids N (N x N photons; default 64,128,256)
  --volume-sub-segments A,.. sub-segment counts, 0 = per-fragment march (default 1,8,32)
  --volume-sizes A,B,...     screen sizes of the Table 2 analogue (default 64,128,256)
  --volume-progressive A,..  frame counts whose ProgressiveFrames mean is compared
                             with the reference, at the largest grid (default
                             1,2,4,8; 0: no such table)

Temporal stability:
  --animate N                instead of the sweep: render N frames (4..1000) of each
                             animated sequence with each technique's variants (its
                             defaults; cpu-progressive also with progressive=off;
                             "none" only when --techniques names it),
                             the scene moving for N/2 frames, then cut to a distant
                             pose held still. Reports flicker where the reference is
                             still, the error where it moves, the lag and ghosting
                             after the cut, time per frame (docs/benchmarks.md,
                             "Temporal stability"); writes temporal.csv,
                             temporal-frames.csv, temporal.md. The reference renders
                             every frame (cached) with --reference-photons (default
                             here 2e6); --warmup untimed frames come first
  --sequences A,B,...        animated sequences (default: pool-waves,moving-ball,light-sweep)

Table 1 of paper 002 (cascaded photon tracing):
  --table1                   instead of the sweep: time the cascaded technique's
                             tracing, storing (splat) and denoising at 0.5, 1 and
                             2 M photons on the first --scenes scene (default
                             pool) at --size, light buffer 1024 x 1024, medians of
                             3 timed frames after 1 warm-up (--smoke: 64 x 64,
                             light buffer 64, 1024 to 4096 photons, 1 frame);
                             writes table1.md (docs/technique-cascaded.md)
  --help                     this text
)";

struct Options
{
  std::vector<std::string> Scenes;
  std::vector<std::string> Techniques;
  int Size = 256;
  int Frames = 7;
  int Warmup = 2;
  double ReferencePhotons = 2e7;
  std::vector<double> Ladder = { 1e5, 1e6, 1e7 };
  int ReferenceRepeats = 3;
  // The ground truth's kernel radius in pixel footprints: 1, about a pixel's own
  // extent (an Epanechnikov kernel of radius 0.71 has the variance of the pixel box),
  // rather than the reference renderer's default of 2, which halves the peak of a
  // sharp caustic line (the bunny's) and would charge a sharper technique for it;
  // the extra noise is paid for with the ground truth's photons.
  double ReferenceKernel = 1.0;
  std::string Output = "caustics-bench-results";
  bool Plot = true;
  bool Images = false;
  std::string Python;
  bool UpdateDocs = false;
  std::string Docs;
  bool Smoke = false;
  bool Defaults = false;
  std::string Knobs; // only configurations whose knobs contain it
  bool List = false;
  bool Help = false;
  std::string CommandLine;
  int Animate = 0;     // --animate N: frames per sequence; 0: the sweep
  bool Table1 = false; // --table1: paper 002's Table 1 instead of the sweep
  bool ScenesGiven = false;
  std::vector<std::string> Sequences = caustics_bench::GetSequenceNames();
  bool SequencesGiven = false;
  bool TechniquesGiven = false;
  bool Volume = false; // --volume: the volume caustics' tables instead of the sweep
  caustics_bench::VolumeSettings VolumeTables;
};

using caustics_cli::NoWindowError;
using caustics_cli::ParseCount;
using caustics_cli::ParseNumber;
using caustics_cli::UsageError;

std::vector<std::string> SplitList(const std::string& option, const std::string& text)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ','))
  {
    if (part.empty())
    {
      throw UsageError(option + " expects a comma-separated list, got '" + text + "'");
    }
    if (std::find(parts.begin(), parts.end(), part) != parts.end())
    {
      throw UsageError(option + " lists '" + part + "' twice");
    }
    parts.push_back(part);
  }
  if (parts.empty())
  {
    throw UsageError(option + " expects a comma-separated list, got '" + text + "'");
  }
  return parts;
}

std::string Join(const std::vector<std::string>& items, const char* separator = ", ")
{
  std::string text;
  for (const auto& item : items)
  {
    text += (text.empty() ? "" : separator) + item;
  }
  return text;
}

/** Quotes an argument for a POSIX shell when it needs it. */
std::string ShellQuote(const std::string& text)
{
  const char* safe = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=/.,:@%";
  if (!text.empty() && text.find_first_not_of(safe) == std::string::npos)
  {
    return text;
  }
  std::string quoted = "'";
  for (char c : text)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

/** Techniques by default: every registered one except "none", then "none" (the floor). */
std::vector<std::string> DefaultTechniques()
{
  std::vector<std::string> names;
  for (const auto& name : vtkCausticsTechniques::GetNames())
  {
    if (name != "none")
    {
      names.push_back(name);
    }
  }
  names.emplace_back("none");
  return names;
}

/** The integer option that sets `field`, in [low, high]. */
caustics_cli::Arguments::ValueHandler Count(int& field, double low, double high)
{
  return [&field, low, high](const std::string& option, const std::string& value)
  { field = static_cast<int>(ParseCount(option, value, low, high)); };
}

void DeclareSelectionOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Flag("--list", [&options] { options.List = true; });
  arguments.Flag("--defaults", [&options] { options.Defaults = true; });
  arguments.Value(
    "--knobs", [&options](const std::string&, const std::string& value) { options.Knobs = value; });
  arguments.Value("--scenes",
    [&options](const std::string& option, const std::string& value)
    {
      options.Scenes = SplitList(option, value);
      options.ScenesGiven = true;
      for (const auto& scene : options.Scenes)
      {
        if (!vtkCausticsBuiltinScene::IsSceneName(scene))
        {
          throw UsageError("unknown scene '" + scene +
            "' (built-in: " + Join(vtkCausticsBuiltinScene::GetSceneNames()) + ")");
        }
      }
    });
  arguments.Value("--techniques",
    [&options](const std::string& option, const std::string& value)
    {
      options.Techniques = SplitList(option, value);
      options.TechniquesGiven = true;
      for (auto& technique : options.Techniques)
      {
        technique = technique == "best" ? vtkCausticsTechniques::GetBestName() : technique;
        if (!vtkCausticsTechniques::Create(technique))
        {
          throw UsageError("unknown technique '" + technique +
            "' (known: " + Join(vtkCausticsTechniques::GetNames()) + ", best)");
        }
      }
    });
}

void DeclareMeasurementOptions(
  caustics_cli::Arguments& arguments, Options& options, bool& ladderGiven, bool& photonsGiven)
{
  arguments.Value("--size", Count(options.Size, 16, 4096));
  arguments.Value("--frames", Count(options.Frames, 5, 1000));
  arguments.Value("--warmup", Count(options.Warmup, 2, 100));
  arguments.Value("--reference-photons",
    [&options, &photonsGiven](const std::string& option, const std::string& value)
    {
      options.ReferencePhotons = ParseCount(option, value, 1000, 1e10);
      photonsGiven = true;
    });
  arguments.Value("--reference-ladder",
    [&options, &ladderGiven](const std::string& option, const std::string& value)
    {
      options.Ladder.clear();
      for (const auto& count : SplitList(option, value))
      {
        options.Ladder.push_back(ParseCount(option, count, 100, 1e10));
      }
      std::sort(options.Ladder.begin(), options.Ladder.end());
      ladderGiven = true;
    });
  arguments.Value("--reference-kernel",
    [&options](const std::string& option, const std::string& value)
    {
      if (value == "pixel")
      {
        options.ReferenceKernel = 0.0; // the pixel-footprint estimate
        return;
      }
      // A number where it is not "pixel": the message names both.
      const bool number = value.find_first_not_of("0123456789.eE+-") == std::string::npos;
      options.ReferenceKernel = number ? ParseNumber(option, value) : -1.0;
      if (options.ReferenceKernel < 0.25 || options.ReferenceKernel > 64.0)
      {
        throw UsageError(option + " expects a radius in [0.25, 64] pixel footprints, or pixel");
      }
    });
  arguments.Value("--reference-repeats", Count(options.ReferenceRepeats, 1, 20));
}

void DeclareOutputOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Value("--output",
    [&options](const std::string&, const std::string& value)
    {
      options.Output = value;
      if (options.Output.empty())
      {
        throw UsageError("--output needs a folder name");
      }
    });
  arguments.Flag("--no-plot", [&options] { options.Plot = false; });
  arguments.Flag("--images", [&options] { options.Images = true; });
  arguments.Value("--python",
    [&options](const std::string&, const std::string& value) { options.Python = value; });
  arguments.Flag("--update-docs", [&options] { options.UpdateDocs = true; });
  arguments.Value(
    "--docs", [&options](const std::string&, const std::string& value) { options.Docs = value; });
  arguments.Flag("--smoke", [&options] { options.Smoke = true; });
  arguments.Flag("--volume", [&options] { options.Volume = true; });
  auto integers = [](std::vector<int>& field, int low, int high)
  {
    return [&field, low, high](const std::string& option, const std::string& value)
    {
      field.clear();
      for (const std::string& part : SplitList(option, value))
      {
        field.push_back(caustics_cli::ParseInteger(option, part, low, high));
      }
    };
  };
  arguments.Value("--volume-grids", integers(options.VolumeTables.Grids, 8, 1182));
  arguments.Value("--volume-sub-segments", integers(options.VolumeTables.SubSegments, 0, 64));
  arguments.Value("--volume-sizes", integers(options.VolumeTables.Sizes, 16, 4096));
  arguments.Value("--volume-progressive",
    [&options](const std::string& option, const std::string& value)
    {
      std::vector<int>& counts = options.VolumeTables.Progressive;
      counts.clear();
      for (const std::string& part : SplitList(option, value))
      {
        counts.push_back(caustics_cli::ParseInteger(option, part, 0, 4096));
      }
      counts.erase(std::remove(counts.begin(), counts.end(), 0), counts.end());
    });
}

void DeclareTemporalOptions(caustics_cli::Arguments& arguments, Options& options)
{
  arguments.Value("--animate", Count(options.Animate, 4, 1000));
  arguments.Flag("--table1", [&options] { options.Table1 = true; });
  arguments.Value("--sequences",
    [&options](const std::string& option, const std::string& value)
    {
      options.Sequences = SplitList(option, value);
      options.SequencesGiven = true;
      const auto known = caustics_bench::GetSequenceNames();
      for (const auto& sequence : options.Sequences)
      {
        if (std::find(known.begin(), known.end(), sequence) == known.end())
        {
          throw UsageError("unknown sequence '" + sequence + "' (known: " + Join(known) + ")");
        }
      }
    });
}

/**
 * --animate: its own reference default; --sequences only with it, and none of the
 * sweep's own options with it (they would be ignored).
 */
void ApplyTemporal(Options& options, bool photonsGiven, bool ladderGiven)
{
  if (options.Animate == 0)
  {
    if (options.SequencesGiven)
    {
      throw UsageError("--sequences needs --animate N");
    }
    return;
  }
  const char* sweepOnly = options.Defaults ? "--defaults"
    : !options.Knobs.empty()               ? "--knobs"
    : options.Images                       ? "--images"
    : ladderGiven                          ? "--reference-ladder"
    : options.List                         ? "--list"
                                           : nullptr;
  if (sweepOnly)
  {
    throw UsageError(std::string(sweepOnly) + " does not apply to --animate");
  }
  if (!photonsGiven && !options.Smoke)
  {
    options.ReferencePhotons = 2e6; // one reference per distinct frame
  }
  // "none" (no caustics, error 1) is the sweep's floor; here only when asked for.
  if (!options.TechniquesGiven)
  {
    options.Techniques.erase(
      std::remove(options.Techniques.begin(), options.Techniques.end(), "none"),
      options.Techniques.end());
  }
}

/** --smoke: the first scene at 64 x 64, few frames, a small reference and ladder. */
void ApplySmoke(Options& options, bool ladderGiven)
{
  if (options.UpdateDocs)
  {
    throw UsageError("--update-docs cannot be combined with --smoke (the docs show full runs)");
  }
  options.Scenes.resize(1);
  options.Size = 64;
  options.Warmup = 1;
  options.Frames = 2;
  options.ReferencePhotons = 1e5;
  if (!ladderGiven)
  {
    options.Ladder = { 1e4, 3e4 };
  }
  options.ReferenceRepeats = 1;
}

void CheckLadder(const Options& options)
{
  for (double count : options.Ladder)
  {
    if (count >= options.ReferencePhotons)
    {
      std::ostringstream message;
      message << "--reference-ladder count " << static_cast<long long>(count)
              << " must be below --reference-photons ("
              << static_cast<long long>(options.ReferencePhotons)
              << "): the ladder is measured against that reference";
      throw UsageError(message.str());
    }
  }
}

/** $CAUSTICS_PYTHON, else Debian's python3 (it has python3-matplotlib), else python3. */
std::string DefaultPython()
{
  const char* fromEnvironment = std::getenv("CAUSTICS_PYTHON");
  if (fromEnvironment && *fromEnvironment)
  {
    return fromEnvironment;
  }
  return vtksys::SystemTools::FileExists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

Options Parse(int argc, char* argv[])
{
  Options options;
  // The surface scenes: the media scenes' volume layer has no rows yet (--scenes names them).
  for (const std::string& name : vtkCausticsBuiltinScene::GetSceneNames())
  {
    if (!vtkCausticsBuiltinScene::IsMediaScene(name))
    {
      options.Scenes.push_back(name);
    }
  }
  options.Techniques = DefaultTechniques();
  for (int i = 0; i < argc; ++i)
  {
    options.CommandLine += (i ? " " : "") + ShellQuote(argv[i]);
  }
  bool ladderGiven = false, photonsGiven = false;
  caustics_cli::Arguments arguments;
  arguments.Flag("--help", [&options] { options.Help = true; });
  arguments.Flag("-h", [&options] { options.Help = true; });
  DeclareSelectionOptions(arguments, options);
  DeclareMeasurementOptions(arguments, options, ladderGiven, photonsGiven);
  DeclareOutputOptions(arguments, options);
  DeclareTemporalOptions(arguments, options);
  for (const auto& positional : arguments.Parse(argc, argv))
  {
    throw UsageError("unknown option '" + positional + "' (see --help)");
  }
  if (options.Table1 && (options.Animate > 0 || options.UpdateDocs))
  {
    throw UsageError(std::string(options.Animate > 0 ? "--animate" : "--update-docs") +
      " does not apply to --table1");
  }
  if (options.Smoke)
  {
    ApplySmoke(options, ladderGiven);
  }
  ApplyTemporal(options, photonsGiven, ladderGiven);
  if (options.Volume && options.TechniquesGiven)
  {
    // --volume: the techniques that write volume lines, as --techniques names them.
    const auto& volume = caustics_bench::VolumeTechniqueNames();
    for (const auto& technique : options.Techniques)
    {
      if (std::find(volume.begin(), volume.end(), technique) == volume.end())
      {
        throw UsageError("--volume: technique '" + technique +
          "' writes no volume lines (those that do: " + Join(volume) + ")");
      }
    }
    options.VolumeTables.Techniques = options.Techniques;
  }
  if (options.Animate == 0)
  {
    CheckLadder(options);
  }
  options.Python = options.Python.empty() ? DefaultPython() : options.Python;
  if (options.Docs.empty())
  {
    options.Docs = "docs/benchmarks.md";
  }
  return options;
}

/** The configurations of `technique`: its table entries, or its defaults. */
std::vector<Configuration> ConfigurationsOf(
  const std::string& technique, const std::vector<Configuration>& table)
{
  std::vector<Configuration> selected;
  for (const auto& configuration : table)
  {
    if (configuration.Technique == technique)
    {
      selected.push_back(configuration);
    }
  }
  if (selected.empty())
  {
    selected.push_back({ technique, "default", [](vtkCausticsRenderPass*) { return true; } });
  }
  return selected;
}

// ---------------------------------------------------------------------------
// Statistics and the machine.
// ---------------------------------------------------------------------------

/** Median; NaN for no values or when one is NaN (a time that was not measured). */
double Median(std::vector<double> values)
{
  if (values.empty() ||
    std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); }))
  {
    return NaN;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double Milliseconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

struct Machine
{
  std::string CPU = "unknown CPU";
  unsigned int Threads = 0;
  std::string Window;
  std::string GLRenderer = "unknown";
  std::string GLVersion = "unknown";
  std::string Date;
  std::string LoadAverage = "unknown"; // 1-minute load average when the run started
};

std::string AfterColon(const std::string& line)
{
  const auto colon = line.find(':');
  const std::string value = colon == std::string::npos ? line : line.substr(colon + 1);
  const auto first = value.find_first_not_of(" \t");
  const auto last = value.find_last_not_of(" \t\r");
  return first == std::string::npos ? std::string() : value.substr(first, last - first + 1);
}

/** CPU model, hardware threads and the date; the GL strings come after the first frame. */
Machine DescribeMachine()
{
  Machine machine;
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
  {
    if (line.rfind("model name", 0) == 0)
    {
      machine.CPU = AfterColon(line);
      break;
    }
  }
  machine.Threads = std::thread::hardware_concurrency();
  // Other work on the machine slows both the GPU (llvmpipe) and the reference down.
  std::ifstream loadavg("/proc/loadavg");
  loadavg >> machine.LoadAverage;
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  machine.Date = date;
  return machine;
}

void DescribeGL(vtkRenderWindow* window, Machine& machine)
{
  std::istringstream capabilities(window->ReportCapabilities());
  std::string line;
  while (std::getline(capabilities, line))
  {
    if (line.rfind("OpenGL renderer string", 0) == 0)
    {
      machine.GLRenderer = AfterColon(line);
    }
    else if (line.rfind("OpenGL version string", 0) == 0)
    {
      machine.GLVersion = AfterColon(line);
    }
  }
}

// ---------------------------------------------------------------------------
// Measurements.
// ---------------------------------------------------------------------------

/**
 * Median times of one stage. GPU is NaN for CPU-only stages (the reference). Its
 * throughput comes from the counted frames after the timed ones (CountWork): the
 * stage's wall time there (its CPU time between glFinish brackets) and its work.
 */
struct Stage
{
  std::string Name;
  double GPUMilliseconds = NaN;
  double CPUMilliseconds = NaN;
  double CountedMilliseconds = NaN; // median wall time in the counted frames
  long long Fragments = -1;         // fragments written (splat, line fragments, ...)
  long long Invocations = -1;       // compute shader invocations
  long long Primitives = -1;        // points, lines, triangles drawn
  double Photons = NaN;             // photons offered to the stage, where known

  /** `count` per second of the stage's counted wall time; NaN when either is unknown. */
  double PerSecond(double count) const
  {
    return count >= 0.0 && this->CountedMilliseconds > 0.0
      ? count / (this->CountedMilliseconds / 1000.0)
      : NaN;
  }
  bool HasWork() const { return this->Fragments > 0 || this->Invocations > 0 || this->Photons > 0; }
};

/** One row of benchmarks.csv: a configuration of a technique, or a reference run. */
struct Row
{
  std::string Scene;
  std::string Technique; // a registered name, or "reference"
  std::string Knobs;
  int Frames = 0;                // timed frames (reference: timed renders)
  double WallMilliseconds = NaN; // median per frame (reference: per render)
  double GPUMilliseconds = NaN;  // median of the per-frame sum of stage GPU times
  vtkCausticsErrorMetrics::Result Error;
  std::vector<Stage> Stages;
  std::string Status = "ok";
  bool IsReference() const { return this->Technique == "reference"; }
};

using caustics_bench::MakeReference;
using caustics_bench::ReadCausticIrradiance;
using caustics_cli::OneLineOutputWindow;

/** Error of `test`'s CausticIrradiance against the reference image, on its receiver pixels. */
vtkCausticsErrorMetrics::Result CompareWithReference(vtkImageData* test, vtkImageData* truth)
{
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetArrayName("CausticIrradiance");
  metrics->SetMaskArrayName("ReceiverMask");
  metrics->SetAreaArrayName("PixelArea");
  if (!metrics->Compute(test, truth))
  {
    throw std::runtime_error(std::string("comparison failed: ") + metrics->GetLastError());
  }
  return metrics->GetResult();
}

/** What the run did to make its ground truths: one line per scene for the docs. */
struct TruthRecord
{
  std::string Scene;
  vtkIdType Photons = 0;
  bool FromCache = false;
  double Seconds = 0.0;
  std::string CacheFile; // name of the cached EXR (a hash of every input)
};

/**
 * The reference at each ladder count (seed 2, cache off, so it is really rendered
 * and independent of the ground truth's seed 1): median wall time over repeats and
 * error against the ground truth. Repeats stop once a count has used 30 s.
 */
std::vector<Row> TimeReferenceLadder(const Options& options, const std::string& scene,
  vtkRenderer* renderer, vtkImageData* truth, OneLineOutputWindow* messages)
{
  std::vector<Row> rows;
  for (double photons : options.Ladder)
  {
    Row row;
    row.Scene = scene;
    row.Technique = "reference";
    std::vector<double> wall, tracing, view, volume;
    double spent = 0.0;
    vtkSmartPointer<vtkCausticsReferenceRenderer> reference;
    for (int repeat = 0; repeat < options.ReferenceRepeats && (repeat == 0 || spent < 30.0);
         ++repeat)
    {
      reference = MakeReference(renderer, options.Size, photons, options.ReferenceKernel, 2, false);
      if (!reference->Update())
      {
        throw std::runtime_error(
          "the reference failed on scene '" + scene + "': " + reference->GetLastError());
      }
      wall.push_back(1000.0 * reference->GetWallTime());
      const auto& statistics = reference->GetStatistics();
      tracing.push_back(1000.0 * statistics.photonSeconds);
      view.push_back(1000.0 * statistics.viewSeconds);
      volume.push_back(1000.0 * statistics.volumeSeconds);
      spent += reference->GetWallTime();
    }
    row.Knobs = "photons=" + std::to_string(reference->GetNumberOfPhotonsEmitted());
    row.Frames = static_cast<int>(wall.size());
    row.WallMilliseconds = Median(wall);
    row.Stages = { { "photon tracing", NaN, Median(tracing) },
      { "camera rays and gather", NaN, Median(view) }, { "volume", NaN, Median(volume) } };
    row.Error = CompareWithReference(reference->GetOutput(), truth);
    const std::string error = messages->TakeError();
    if (!error.empty())
    {
      throw std::runtime_error(error);
    }
    rows.push_back(row);
  }
  return rows;
}

/**
 * Writes `image`'s CausticIrradiance to <output>/images/<name>.exr (name made
 * file-safe), for --images.
 */
void WriteIrradiance(const Options& options, vtkImageData* image, std::string name)
{
  for (char& c : name)
  {
    c = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  }
  const std::string folder = options.Output + "/images";
  vtksys::SystemTools::MakeDirectory(folder);
  std::string error;
  if (!vtkCausticsImageIO::WriteEXR(
        image, { { "CausticIrradiance", "caustic" } }, folder + "/" + name + ".exr", &error))
  {
    throw std::runtime_error("--images: " + error);
  }
}

/**
 * Photons offered to a stage, where known: the photon grid of one light (N x N
 * light-buffer texels) for the per-light stages that take every photon of the grid
 * (emission, the caustic map's trace, the first bounce's line tracing); NaN elsewhere.
 */
double PhotonsOfStage(const std::string& name, int grid)
{
  auto endsWith = [&name](const std::string& end)
  {
    return name.size() >= end.size() &&
      name.compare(name.size() - end.size(), end.size(), end) == 0;
  };
  const bool perPhoton = endsWith("emission") || name == "hcm emit" || name == "hcm trace" ||
    endsWith("bounce 1 line tracing");
  return perPhoton ? static_cast<double>(grid) * grid : NaN;
}

/**
 * Frames after the timed ones with vtkCausticsTimings::CountWork on (it waits at
 * every stage boundary, so these frames are not timed): each stage's median wall
 * time in them and the work of the last one, for its throughput.
 */
void CountStageWork(const Options& options, vtkRenderWindow* window, vtkCausticsRenderPass* pass,
  std::vector<Stage>& stages)
{
  vtkCausticsTimings* timings = pass->GetTimings();
  timings->CountWorkOn();
  std::map<std::string, std::vector<double>> wall;
  std::map<std::string, std::array<long long, 3>> work;
  for (int frame = 0; frame < (options.Smoke ? 1 : 3); ++frame)
  {
    window->Render();
    window->WaitForCompletion();
    for (int s = 0; s < timings->GetNumberOfStages(); ++s)
    {
      if (timings->GetStageTimedOnGPU(s))
      {
        wall[timings->GetStageName(s)].push_back(timings->GetStageCPUMilliseconds(s));
        work[timings->GetStageName(s)] = { timings->GetStageWork(
                                             s, vtkCausticsTimings::FRAGMENTS_WRITTEN),
          timings->GetStageWork(s, vtkCausticsTimings::COMPUTE_SHADER_INVOCATIONS),
          timings->GetStageWork(s, vtkCausticsTimings::PRIMITIVES_SUBMITTED) };
      }
    }
  }
  timings->CountWorkOff();
  for (Stage& stage : stages)
  {
    if (work.count(stage.Name))
    {
      stage.CountedMilliseconds = Median(wall[stage.Name]);
      stage.Fragments = work[stage.Name][0];
      stage.Invocations = work[stage.Name][1];
      stage.Primitives = work[stage.Name][2];
      stage.Photons = PhotonsOfStage(stage.Name, pass->GetLightBufferResolution());
    }
  }
}

/** A new pass of the configuration's technique with the configuration applied. */
vtkSmartPointer<vtkCausticsRenderPass> MakePass(const Configuration& configuration)
{
  vtkSmartPointer<vtkCausticsRenderPass> pass =
    vtkCausticsTechniques::Create(configuration.Technique);
  if (!configuration.Apply(pass))
  {
    throw std::runtime_error("the configuration table expects another class for technique '" +
      configuration.Technique + "' than " + pass->GetClassName());
  }
  pass->GetTimings()->SynchronousOn();
  return pass;
}

/**
 * Warmup untimed frames, then Frames timed ones (each: Render and wait for the GPU
 * to finish; stage GPU times from synchronous timer queries): the row's medians.
 */
void TimeFrames(
  const Options& options, vtkRenderWindow* window, vtkCausticsRenderPass* pass, Row& row)
{
  std::vector<double> wall, gpuTotal;
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> gpu, cpu;
  vtkCausticsTimings* timings = pass->GetTimings();
  for (int frame = 0; frame < options.Warmup + options.Frames; ++frame)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    const double elapsed = Milliseconds(start);
    if (frame < options.Warmup)
    {
      continue;
    }
    wall.push_back(elapsed);
    double total = 0.0;
    for (int s = 0; s < timings->GetNumberOfStages(); ++s)
    {
      if (!timings->GetStageRan(s))
      {
        continue;
      }
      const std::string name = timings->GetStageName(s);
      if (!gpu.count(name))
      {
        order.push_back(name);
      }
      cpu[name].push_back(timings->GetStageCPUMilliseconds(s));
      // CPU work (e.g. the scene snapshot) has no GPU time; -1: the timer query had no
      // result (it would wrongly lower the total).
      const double milliseconds = timings->GetStageGPUMilliseconds(s);
      gpu[name].push_back(
        timings->GetStageTimedOnGPU(s) && milliseconds >= 0.0 ? milliseconds : NaN);
      total += timings->GetStageTimedOnGPU(s) ? gpu[name].back() : 0.0;
    }
    gpuTotal.push_back(total);
  }
  row.Frames = options.Frames;
  row.WallMilliseconds = Median(wall);
  row.GPUMilliseconds = Median(gpuTotal);
  for (const auto& name : order)
  {
    row.Stages.push_back({ name, Median(gpu[name]), Median(cpu[name]) });
  }
}

/**
 * The last timed frame's caustic irradiance against the ground truth (and, with
 * --images, written out); then the counted frames. Returns the error, "" if none.
 */
std::string CompareAndCount(const Options& options, const Configuration& configuration,
  vtkRenderWindow* window, vtkCausticsRenderPass* pass, vtkImageData* truth, Row& row)
{
  try
  {
    vtkSmartPointer<vtkImageData> irradiance = ReadCausticIrradiance(pass, options.Size);
    row.Error = CompareWithReference(irradiance, truth);
    if (options.Images)
    {
      WriteIrradiance(
        options, irradiance, row.Scene + "_" + configuration.Technique + "_" + configuration.Knobs);
    }
    if (!pass->GetLastFrameHadCaustics())
    {
      row.Status = "no caustic stage ran";
    }
    CountStageWork(options, window, pass, row.Stages);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}

/**
 * One configuration: a new pass of the technique with the configuration applied,
 * its timed frames, the last one's error against the ground truth, then the
 * counted frames for the stages' throughput.
 */
Row MeasureConfiguration(const Options& options, const std::string& scene,
  const Configuration& configuration, vtkRenderWindow* window, vtkOpenGLRenderer* renderer,
  vtkImageData* truth, OneLineOutputWindow* messages)
{
  Row row;
  row.Scene = scene;
  row.Technique = configuration.Technique;
  row.Knobs = configuration.Knobs;
  vtkSmartPointer<vtkCausticsRenderPass> pass = MakePass(configuration);
  renderer->SetPass(pass);
  TimeFrames(options, window, pass, row);
  std::string error = messages->TakeError();
  if (error.empty())
  {
    error = CompareAndCount(options, configuration, window, pass, truth, row);
  }
  const std::string late = messages->TakeError();
  if (!error.empty() || !late.empty())
  {
    row.Status = "error: " + (error.empty() ? late : error);
    row.Error = vtkCausticsErrorMetrics::Result();
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  messages->TakeError();
  return row;
}

// ---------------------------------------------------------------------------
// Output: CSV, plot, docs.
// ---------------------------------------------------------------------------

std::string Number(double value, int precision = 6)
{
  if (std::isnan(value))
  {
    return "nan";
  }
  if (std::isinf(value))
  {
    return value > 0 ? "inf" : "-inf";
  }
  std::ostringstream text;
  text << std::setprecision(precision) << value;
  return text.str();
}

std::string CSVField(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos)
  {
    return text;
  }
  std::string quoted = "\"";
  for (char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return quoted + "\"";
}

/** Both CSV files, written row by row so that an interrupted run keeps what it measured. */
class CSVWriter
{
public:
  void Open(const std::string& folder)
  {
    auto open = [](std::ofstream& file, const std::string& path)
    {
      file.open(path, std::ios::out | std::ios::trunc);
      if (!file)
      {
        throw std::runtime_error("cannot write " + path);
      }
    };
    this->RowsPath = folder + "/benchmarks.csv";
    this->StagesPath = folder + "/benchmark-stages.csv";
    this->ThroughputPath = folder + "/benchmark-throughput.csv";
    open(this->Rows, this->RowsPath);
    open(this->Stages, this->StagesPath);
    open(this->Throughput, this->ThroughputPath);
    // Units: ms per frame (reference: per render), error columns as in docs/accuracy.md.
    this->Rows << "scene,technique,knobs,width,height,frames,wall_ms,gpu_ms,rel_l2,flux_ratio,"
                  "peak_error_px,psnr_db,rmse,nonfinite_px,compared_px,status\n";
    this->Stages << "scene,technique,knobs,stage,gpu_ms,cpu_ms\n";
    // Work of one counted frame; rates per second of the stage's counted wall time.
    this->Throughput << "scene,technique,knobs,stage,counted_wall_ms,fragments,compute_invocations,"
                        "primitives,photons,fragments_per_s,invocations_per_s,primitives_per_s,"
                        "photons_per_s\n";
  }
  void Write(const Row& row, int size)
  {
    const auto& e = row.Error;
    this->Rows << CSVField(row.Scene) << ',' << CSVField(row.Technique) << ','
               << CSVField(row.Knobs) << ',' << size << ',' << size << ',' << row.Frames << ','
               << Number(row.WallMilliseconds) << ','
               << (row.IsReference() ? "" : Number(row.GPUMilliseconds)) << ','
               << Number(e.RelativeL2Error) << ',' << Number(e.FluxRatio) << ','
               << Number(e.PeakPositionError) << ',' << Number(e.PSNR) << ',' << Number(e.RMSE)
               << ',' << e.NonFinitePixels << ',' << e.ComparedPixels << ',' << CSVField(row.Status)
               << '\n';
    for (const auto& stage : row.Stages)
    {
      this->Stages << CSVField(row.Scene) << ',' << CSVField(row.Technique) << ','
                   << CSVField(row.Knobs) << ',' << CSVField(stage.Name) << ','
                   << (std::isnan(stage.GPUMilliseconds) ? "" : Number(stage.GPUMilliseconds))
                   << ',' << Number(stage.CPUMilliseconds) << '\n';
    }
    this->WriteThroughput(row);
    this->Rows.flush();
    this->Stages.flush();
    this->Throughput.flush();
    if (!this->Rows || !this->Stages || !this->Throughput)
    {
      throw std::runtime_error("cannot write " + this->RowsPath + " (disk full?)");
    }
  }
  std::string RowsPath, StagesPath, ThroughputPath;

private:
  void WriteThroughput(const Row& row)
  {
    auto count = [](long long value) { return value < 0 ? std::string() : std::to_string(value); };
    for (const auto& stage : row.Stages)
    {
      if (std::isnan(stage.CountedMilliseconds))
      {
        continue;
      }
      this->Throughput << CSVField(row.Scene) << ',' << CSVField(row.Technique) << ','
                       << CSVField(row.Knobs) << ',' << CSVField(stage.Name) << ','
                       << Number(stage.CountedMilliseconds) << ',' << count(stage.Fragments) << ','
                       << count(stage.Invocations) << ',' << count(stage.Primitives) << ','
                       << (std::isnan(stage.Photons) ? "" : Number(stage.Photons)) << ','
                       << Number(stage.PerSecond(stage.Fragments)) << ','
                       << Number(stage.PerSecond(stage.Invocations)) << ','
                       << Number(stage.PerSecond(stage.Primitives)) << ','
                       << Number(stage.PerSecond(stage.Photons)) << '\n';
    }
  }

  std::ofstream Rows, Stages, Throughput;
};

/**
 * Runs scripts/plot-benchmarks.py on the CSV. Returns the PNG's path, or "" with
 * `why` set when the plot was skipped (no Python, no matplotlib) or failed.
 */
std::string Plot(const Options& options, const std::string& csv, std::string& why)
{
  // Beside this program as built and as installed: <bin>/<CAUSTICS_SCRIPTS_FROM_BIN>.
  const std::string program = vtksys::SystemTools::GetRealPath("/proc/self/exe");
  const std::string script = vtksys::SystemTools::CollapseFullPath(
    std::string(CAUSTICS_SCRIPTS_FROM_BIN) + "/plot-benchmarks.py",
    vtksys::SystemTools::GetFilenamePath(program));
  const std::string png = options.Output + "/benchmarks.png";
  if (!vtksys::SystemTools::FileExists(script))
  {
    why = "no " + script;
    return "";
  }
  vtksys::SystemTools::RemoveFile(png); // a plot of an earlier run must not pass for this one
  const std::string command = ShellQuote(options.Python) + " " + ShellQuote(script) + " " +
    ShellQuote(csv) + " --output " + ShellQuote(png);
  std::cout << std::flush;
  const int status = std::system(command.c_str());
  const int code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 0 && vtksys::SystemTools::FileExists(png))
  {
    return png;
  }
  why = code == 127 ? "cannot run " + options.Python
    : code == 3     ? options.Python + " has no matplotlib"
                    : "plot-benchmarks.py failed (exit " + std::to_string(code) + ")";
  return "";
}

std::string FormatTime(double milliseconds)
{
  std::ostringstream text;
  text << std::fixed;
  if (std::isnan(milliseconds))
  {
    return "–";
  }
  if (milliseconds >= 1000.0)
  {
    text << std::setprecision(milliseconds >= 10000.0 ? 1 : 2) << milliseconds / 1000.0 << " s";
  }
  else
  {
    text << std::setprecision(milliseconds >= 100.0 ? 0 : 1) << milliseconds << " ms";
  }
  return text.str();
}

std::string Fixed(double value, int precision)
{
  if (!std::isfinite(value))
  {
    return Number(value);
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(precision) << value;
  return text.str();
}

/** The reference's estimate as the docs' tables name it (`kernel` 0: pixel footprints). */
std::string KernelText(double kernel)
{
  return kernel > 0.0 ? "kernel radius " + Fixed(kernel, 2) + " pixel footprints"
                      : "the flux in each pixel's footprint";
}

/**
 * The rows no cheaper row beats in error (relative L2), by rising wall time: the
 * Pareto front of time against error. Rows without a finite positive error are left out.
 */
std::vector<const Row*> ParetoFront(std::vector<const Row*> rows)
{
  std::sort(rows.begin(), rows.end(),
    [](const Row* a, const Row* b) { return a->WallMilliseconds < b->WallMilliseconds; });
  std::vector<const Row*> front;
  for (const Row* row : rows)
  {
    const double error = row->Error.RelativeL2Error;
    if (std::isfinite(error) && error > 0.0 && std::isfinite(row->WallMilliseconds) &&
      (front.empty() || error < front.back()->Error.RelativeL2Error))
    {
      front.push_back(row);
    }
  }
  return front;
}

/**
 * Time the reference needs for `error`, from the scene's ladder: its Pareto front,
 * interpolated linearly in log(time) against log(error). Outside the ladder's range,
 * a bound: "< t" when even the cheapest run is more accurate, "> t" when the most
 * accurate is not enough. `speedUp` receives reference time / wall (NaN for a bound).
 */
std::string OfflineEquivalent(
  const std::vector<const Row*>& ladder, double error, double wall, double& speedUp)
{
  speedUp = NaN;
  const std::vector<const Row*> front = ParetoFront(ladder);
  if (front.empty() || !std::isfinite(error) || error <= 0.0)
  {
    return "–";
  }
  if (error >= front.front()->Error.RelativeL2Error)
  {
    return "< " + FormatTime(front.front()->WallMilliseconds);
  }
  if (error < front.back()->Error.RelativeL2Error)
  {
    return "> " + FormatTime(front.back()->WallMilliseconds);
  }
  for (std::size_t i = 0; i + 1 < front.size(); ++i)
  {
    const double e0 = front[i]->Error.RelativeL2Error, e1 = front[i + 1]->Error.RelativeL2Error;
    if (error <= e0 && error >= e1)
    {
      const double t0 = front[i]->WallMilliseconds, t1 = front[i + 1]->WallMilliseconds;
      const double u = (std::log(error) - std::log(e0)) / (std::log(e1) - std::log(e0));
      const double milliseconds = std::exp(std::log(t0) + u * (std::log(t1) - std::log(t0)));
      speedUp = milliseconds / wall;
      return FormatTime(milliseconds);
    }
  }
  return "–";
}

/** The generated section's header: the command and a table of the run's conditions. */
void WriteDocsHeader(std::ostream& md, const Options& options, const Machine& machine,
  const std::vector<TruthRecord>& truths, double runSeconds)
{
  std::string cwd = vtksys::SystemTools::GetCurrentWorkingDirectory();
  // The repository root holds docs/benchmarks.md.
  const std::string root = vtksys::SystemTools::GetFilenamePath(
    vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(options.Docs)));
  std::string relative = vtksys::SystemTools::RelativePath(
    vtksys::SystemTools::GetRealPath(root), vtksys::SystemTools::GetRealPath(cwd));
  md << "Command (from " << (relative.empty() ? "the repository root" : "`" + relative + "`")
     << ", under `xvfb-run -a` where there is no display):\n\n```sh\n"
     << options.CommandLine << "\n```\n\n";
  md << "| | |\n|---|---|\n";
  md << "| date | " << machine.Date << " |\n";
  md << "| CPU | " << machine.CPU << ", " << machine.Threads << " hardware threads; load average "
     << machine.LoadAverage << " at the start |\n";
  md << "| OpenGL | " << machine.GLRenderer << "; " << machine.GLVersion << " (window "
     << machine.Window << ") |\n";
  md << "| image | " << options.Size << " x " << options.Size << " pixels |\n";
  md << "| frames | median of " << options.Frames << " timed frames after " << options.Warmup
     << " warm-up frames |\n";
  for (const auto& truth : truths)
  {
    md << "| ground truth, " << truth.Scene << " | reference, " << truth.Photons
       << " photons per light, seed 1, " << KernelText(options.ReferenceKernel) << ", `"
       << truth.CacheFile << "` ("
       << (truth.FromCache ? "from the cache" : "rendered in " + Fixed(truth.Seconds, 0) + " s")
       << ") |\n";
  }
  md << "| reference ladder | seed 2, cache off, median of up to " << options.ReferenceRepeats
     << " renders per count (fewer once a count took 30 s) |\n";
  md << "| run time | " << Fixed(runSeconds, 0) << " s in all |\n\n";
}

/** One scene's table of rows: time, error, offline equivalent, Pareto front. */
void WriteDocsSceneTable(std::ostream& md, const std::vector<const Row*>& sceneRows)
{
  std::vector<const Row*> ladder;
  std::copy_if(sceneRows.begin(), sceneRows.end(), std::back_inserter(ladder),
    [](const Row* row) { return row->IsReference(); });
  const std::vector<const Row*> front = ParetoFront(sceneRows);
  md << "| technique | knobs | wall / frame | GPU / frame | rel. L2 | flux ratio | peak err "
        "(px) | PSNR (dB) | non-finite px | reference time for this error | speed-up | Pareto "
        "front |\n";
  md << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|:-:|\n";
  for (const Row* row : sceneRows)
  {
    const auto& e = row->Error;
    double speedUp = NaN;
    const std::string offline = row->IsReference()
      ? "–"
      : OfflineEquivalent(ladder, e.RelativeL2Error, row->WallMilliseconds, speedUp);
    md << "| " << row->Technique << (row->Status == "ok" ? "" : " (" + row->Status + ")") << " | "
       << row->Knobs << " | " << FormatTime(row->WallMilliseconds) << " | "
       << FormatTime(row->GPUMilliseconds) << " | " << Fixed(e.RelativeL2Error, 4) << " | "
       << Fixed(e.FluxRatio, 3) << " | "
       << (e.TestFlux == 0.0 ? "–" : Fixed(e.PeakPositionError, 1)) << " | " << Fixed(e.PSNR, 1)
       << " | " << e.NonFinitePixels << " | " << offline << " | "
       << (std::isnan(speedUp) ? "–" : Fixed(speedUp, 1) + "x") << " | "
       << (std::count(front.begin(), front.end(), row) ? "◆" : "") << " |\n";
  }
}

/** One scene's GPU time per stage (ms, median), one column per stage. */
void WriteDocsStageTable(std::ostream& md, const std::vector<const Row*>& sceneRows)
{
  std::vector<std::string> stageNames;
  for (const Row* row : sceneRows)
  {
    for (const auto& stage : row->Stages)
    {
      if (!row->IsReference() &&
        std::find(stageNames.begin(), stageNames.end(), stage.Name) == stageNames.end())
      {
        stageNames.push_back(stage.Name);
      }
    }
  }
  if (stageNames.empty())
  {
    return;
  }
  md << "\nGPU time per stage (ms, median):\n\n| technique | knobs |";
  for (const auto& name : stageNames)
  {
    md << " " << name << " |";
  }
  md << "\n|---|---|";
  for (std::size_t i = 0; i < stageNames.size(); ++i)
  {
    md << "--:|";
  }
  md << "\n";
  for (const Row* row : sceneRows)
  {
    if (row->IsReference())
    {
      continue;
    }
    md << "| " << row->Technique << " | " << row->Knobs << " |";
    for (const auto& name : stageNames)
    {
      auto stage = std::find_if(
        row->Stages.begin(), row->Stages.end(), [&](const Stage& s) { return s.Name == name; });
      md << " "
         << (stage == row->Stages.end() || std::isnan(stage->GPUMilliseconds)
                ? "–"
                : Fixed(stage->GPUMilliseconds, 2))
         << " |";
    }
    md << "\n";
  }
}

/** The generated section of docs/benchmarks.md. */
std::string MakeDocsSection(const Options& options, const Machine& machine,
  const std::vector<TruthRecord>& truths, const std::vector<Row>& rows, const std::string& plot,
  const std::string& plotSkipped, double runSeconds)
{
  std::ostringstream md;
  WriteDocsHeader(md, options, machine, truths, runSeconds);
  for (const auto& scene : options.Scenes)
  {
    std::vector<const Row*> sceneRows;
    for (const auto& row : rows)
    {
      if (row.Scene == scene)
      {
        sceneRows.push_back(&row);
      }
    }
    md << "### " << scene << "\n\n";
    WriteDocsSceneTable(md, sceneRows);
    WriteDocsStageTable(md, sceneRows);
    md << "\n";
  }
  if (!plot.empty())
  {
    md << "![Run time against relative L2 error, per scene](benchmarks.png)\n";
  }
  else
  {
    md << "(No plot: " << plotSkipped << ".)\n";
  }
  return md.str();
}

/** The lines around a generated section of the docs file. */
struct Markers
{
  const char* Begin;
  const char* End;
};
const Markers SweepMarkers = {
  "<!-- BEGIN caustics-bench --update-docs: generated, do not edit -->",
  "<!-- END caustics-bench --update-docs -->"
};
const Markers TemporalMarkers = { "<!-- BEGIN caustics-bench --animate: generated, do not edit -->",
  "<!-- END caustics-bench --animate -->" };

/**
 * The docs file's text and where its generated section lies (between the end of
 * the begin marker and the start of the end marker). Throws, naming the problem, when
 * the file cannot be read or lacks one begin marker followed by one end marker.
 */
std::string ReadDocs(
  const std::string& path, const Markers& markers, std::size_t& from, std::size_t& to)
{
  const char* BeginMarker = markers.Begin;
  const char* EndMarker = markers.End;
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot read " + path + " (--docs names the file to update)");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const auto begin = text.find(BeginMarker);
  to = text.find(EndMarker);
  if (begin == std::string::npos || to == std::string::npos || to < begin ||
    text.find(BeginMarker, begin + 1) != std::string::npos ||
    text.find(EndMarker, to + 1) != std::string::npos)
  {
    throw std::runtime_error(path + ": needs one line '" + BeginMarker + "' followed by one '" +
      EndMarker + "' around the generated section");
  }
  from = begin + std::string(BeginMarker).size();
  return text;
}

/** Replaces the generated section of the docs file with `section`; the rest is kept. */
void UpdateDocs(const std::string& path, const std::string& section, const Markers& markers)
{
  std::size_t from = 0, to = 0;
  const std::string text = ReadDocs(path, markers, from, to);
  std::ofstream out(path, std::ios::out | std::ios::trunc);
  out << text.substr(0, from) << "\n" << section << text.substr(to);
  if (!out)
  {
    throw std::runtime_error("cannot write " + path);
  }
}

// ---------------------------------------------------------------------------
// The run.
// ---------------------------------------------------------------------------

/** "12.3 M" (or "-" when not a finite number). */
std::string Rate(double perSecond)
{
  return std::isfinite(perSecond) ? Fixed(perSecond / 1e6, perSecond >= 1e7 ? 1 : 2) + " M" : "-";
}

/** Each stage that did counted work: its time beside its throughput. */
void PrintThroughput(const Row& row)
{
  for (const auto& stage : row.Stages)
  {
    if (std::isnan(stage.CountedMilliseconds) || !stage.HasWork())
    {
      continue;
    }
    std::cout << "      " << std::left << std::setw(36) << stage.Name << std::right << std::setw(9)
              << FormatTime(stage.GPUMilliseconds) << " gpu" << std::setw(10)
              << FormatTime(stage.CountedMilliseconds) << " counted  "
              << Rate(stage.PerSecond(stage.Fragments)) << " fragments/s  "
              << Rate(stage.PerSecond(stage.Invocations)) << " invocations/s  "
              << Rate(stage.PerSecond(stage.Primitives)) << " primitives/s"
              << (std::isnan(stage.Photons)
                     ? ""
                     : "  " + Rate(stage.PerSecond(stage.Photons)) + " photons/s")
              << std::endl;
  }
}

void PrintRow(const Row& row)
{
  std::cout << "  " << std::left << std::setw(13) << row.Technique << std::setw(34) << row.Knobs
            << std::right << " wall " << std::setw(9) << FormatTime(row.WallMilliseconds)
            << "  gpu " << std::setw(9) << FormatTime(row.GPUMilliseconds) << "  relL2 "
            << Fixed(row.Error.RelativeL2Error, 4) << "  flux " << Fixed(row.Error.FluxRatio, 3)
            << (row.Status == "ok" ? "" : "  [" + row.Status + "]") << std::endl;
  PrintThroughput(row);
}

/** --list: the scenes, the techniques and every technique's configurations. */
void PrintConfigurations(const std::vector<Configuration>& table)
{
  std::cout << "scenes: " << Join(vtkCausticsBuiltinScene::GetSceneNames()) << "\n"
            << "techniques:\n"
            << vtkCausticsTechniques::Describe() << "configurations:\n";
  for (const auto& technique : DefaultTechniques())
  {
    for (const auto& configuration : ConfigurationsOf(technique, table))
    {
      std::cout << "  " << technique << ": " << configuration.Knobs << "\n";
    }
  }
}

/** Fails on unwritable output or docs without markers before any work. */
void CheckOutputs(const Options& options)
{
  if (options.UpdateDocs)
  {
    std::size_t from = 0, to = 0;
    // Its markers are checked before the long run.
    ReadDocs(options.Docs, options.Animate ? TemporalMarkers : SweepMarkers, from, to);
  }
  if (!vtksys::SystemTools::MakeDirectory(options.Output) ||
    !vtksys::SystemTools::FileIsDirectory(options.Output))
  {
    throw std::runtime_error("cannot create the output folder " + options.Output);
  }
}

vtkSmartPointer<vtkRenderWindow> MakeWindow(const Options& options, Machine& machine)
{
  std::string how;
  vtkSmartPointer<vtkRenderWindow> window = vtkCausticsWindowFactory::Create(true, &how);
  if (!window)
  {
    throw NoWindowError(how);
  }
  machine.Window = how;
  window->SetMultiSamples(0);
  window->SetSize(options.Size, options.Size);
  return window;
}

/** What the run measured, for the CSV, the docs and the exit status. */
struct Results
{
  Machine Computer; // this machine and its OpenGL
  std::vector<Row> Rows;
  std::vector<TruthRecord> Truths;
  int Failed = 0;

  void Add(const Row& row, CSVWriter& csv, int size)
  {
    this->Failed += row.Status.rfind("error", 0) == 0 ? 1 : 0;
    PrintRow(row);
    csv.Write(row, size);
    this->Rows.push_back(row);
  }
};

/** The scene's ground truth (cached), recorded in `results`. */
vtkSmartPointer<vtkCausticsReferenceRenderer> MakeGroundTruth(const Options& options,
  const std::string& scene, vtkRenderer* renderer, Results& results, OneLineOutputWindow* messages)
{
  auto truth = MakeReference(
    renderer, options.Size, options.ReferencePhotons, options.ReferenceKernel, 1, true);
  std::ostringstream label;
  label << scene << ": ground truth, " << static_cast<long long>(options.ReferencePhotons)
        << " photons per light";
  bool ok = false;
  {
    // Minutes at the default photon count: progress and time left while it runs.
    caustics_cli::ProgressReport progress(truth, label.str());
    ok = truth->Update();
  }
  if (!ok)
  {
    throw std::runtime_error(
      "the reference failed on scene '" + scene + "': " + truth->GetLastError());
  }
  messages->TakeError();
  results.Truths.push_back({ scene, truth->GetNumberOfPhotonsEmitted(), truth->GetLoadedFromCache(),
    truth->GetWallTime(), vtksys::SystemTools::GetFilenameName(truth->GetCacheFile()) });
  std::cout << label.str() << (truth->GetLoadedFromCache() ? " (cached, " : " (rendered, ")
            << Fixed(truth->GetWallTime(), 1) << " s): " << truth->GetCacheFile() << std::endl;
  return truth;
}

/** One scene: its ground truth, the reference ladder, every selected configuration. */
void MeasureScene(const Options& options, const std::string& scene,
  const std::vector<Configuration>& table, vtkRenderWindow* window, CSVWriter& csv,
  Results& results, OneLineOutputWindow* messages)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsBuiltinScene> builtin;
  builtin->SetSceneName(scene.c_str());
  if (!builtin->Populate(renderer))
  {
    throw std::runtime_error(builtin->GetLastError());
  }
  // The GPU frames and the reference see the same camera, clipping range included.
  renderer->ResetCameraClippingRange();
  auto truth = MakeGroundTruth(options, scene, renderer, results, messages);
  for (Row& row : TimeReferenceLadder(options, scene, renderer, truth->GetOutput(), messages))
  {
    results.Add(row, csv, options.Size);
  }
  for (const auto& technique : options.Techniques)
  {
    std::vector<Configuration> configurations =
      ConfigurationsOf(technique, options.Defaults ? std::vector<Configuration>() : table);
    if (!options.Knobs.empty())
    {
      configurations.erase(std::remove_if(configurations.begin(), configurations.end(),
                             [&options](const Configuration& c)
                             { return (c.Knobs + " ").find(options.Knobs) == std::string::npos; }),
        configurations.end());
    }
    if (options.Smoke)
    {
      configurations.resize(std::min<std::size_t>(configurations.size(), 1));
    }
    for (const auto& configuration : configurations)
    {
      Row row = MeasureConfiguration(
        options, scene, configuration, window, renderer, truth->GetOutput(), messages);
      if (results.Computer.GLRenderer == "unknown")
      {
        DescribeGL(window, results.Computer);
      }
      results.Add(row, csv, options.Size);
    }
  }
  window->RemoveRenderer(renderer);
}

/** The plot (unless --no-plot) and, with --update-docs, the docs' generated section. */
void WritePlotAndDocs(
  const Options& options, const CSVWriter& csv, const Results& results, double runSeconds)
{
  std::string plot, plotSkipped = "--no-plot";
  if (options.Plot)
  {
    plot = Plot(options, csv.RowsPath, plotSkipped);
    std::cout << (plot.empty() ? "plot skipped: " + plotSkipped : "wrote " + plot) << std::endl;
  }
  if (!options.UpdateDocs)
  {
    return;
  }
  const std::string docsFolder = vtksys::SystemTools::GetFilenamePath(options.Docs);
  if (!plot.empty() && !vtksys::SystemTools::CopyFileAlways(plot, docsFolder + "/benchmarks.png"))
  {
    throw std::runtime_error("cannot write " + docsFolder + "/benchmarks.png");
  }
  UpdateDocs(options.Docs,
    MakeDocsSection(
      options, results.Computer, results.Truths, results.Rows, plot, plotSkipped, runSeconds),
    SweepMarkers);
  std::cout << "updated " << options.Docs << (plot.empty() ? "" : " and benchmarks.png")
            << std::endl;
}

// ---------------------------------------------------------------------------
// --animate: temporal stability (CausticsBenchTemporal.h).
// ---------------------------------------------------------------------------

/** The settings of the temporal run from the options. */
caustics_bench::TemporalSettings TemporalSettingsOf(const Options& options)
{
  caustics_bench::TemporalSettings settings;
  settings.Frames = options.Animate;
  settings.Size = options.Size;
  settings.Warmup = options.Warmup;
  settings.ReferencePhotons = options.ReferencePhotons;
  settings.ReferenceKernel = options.ReferenceKernel;
  settings.SmokeResolution = options.Smoke ? 64 : 0;
  settings.Sequences = options.Sequences;
  settings.Techniques = options.Techniques;
  return settings;
}

/** The generated "Temporal stability" section: the command, the conditions, the table. */
std::string MakeTemporalDocsSection(const Options& options, const Machine& machine,
  const std::vector<caustics_bench::TemporalTruth>& truths, const std::string& table,
  double runSeconds)
{
  std::ostringstream md;
  md << "Command (from the repository root, under `xvfb-run -a` where there is no display):\n\n"
     << "```sh\n"
     << options.CommandLine << "\n```\n\n";
  md << "| | |\n|---|---|\n";
  md << "| date | " << machine.Date << " |\n";
  md << "| CPU | " << machine.CPU << ", " << machine.Threads << " hardware threads; load average "
     << machine.LoadAverage << " at the start |\n";
  md << "| OpenGL | " << machine.GLRenderer << "; " << machine.GLVersion << " |\n";
  md << "| image | " << options.Size << " x " << options.Size << " pixels |\n";
  md << "| frames | " << options.Animate << " per sequence after " << options.Warmup
     << " untimed warm-up frames at frame 0's pose; cut at frame " << options.Animate / 2 << " |\n";
  md << "| reference | every frame, " << static_cast<long long>(options.ReferencePhotons)
     << " photons per light, seed 1, " << KernelText(options.ReferenceKernel) << ", cached |\n";
  for (const auto& truth : truths)
  {
    md << "| reference, " << truth.Sequence << " | " << truth.Rendered << " frames rendered, "
       << options.Animate - truth.Rendered << " from the cache, " << Fixed(truth.Seconds, 0)
       << " s |\n";
  }
  md << "| run time | " << Fixed(runSeconds, 0) << " s in all |\n\n";
  md << caustics_bench::DescribeSequences(TemporalSettingsOf(options)) << "\n" << table;
  return md.str();
}

/** --animate N: every chosen technique's variants over every chosen sequence. */
int RunTemporal(const Options& options, OneLineOutputWindow* messages)
{
  const auto runStart = std::chrono::steady_clock::now();
  CheckOutputs(options);
  Machine machine = DescribeMachine();
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options, machine);
  std::cout << "caustics-bench --animate " << options.Animate << ": " << Join(options.Sequences)
            << " x " << Join(options.Techniques) << ", " << options.Size << "x" << options.Size
            << ", " << machine.CPU << " (" << machine.Threads << " threads)" << std::endl;
  std::vector<caustics_bench::TemporalTruth> truths;
  int failed = 0;
  const auto rows =
    caustics_bench::RunTemporal(TemporalSettingsOf(options), window, messages, truths,
      [&](const caustics_bench::TemporalRow& row)
      {
        if (machine.GLRenderer == "unknown")
        {
          DescribeGL(window, machine);
        }
        failed += row.Status == "ok" ? 0 : 1;
        std::cout << "  " << std::left << std::setw(13) << row.Sequence << std::setw(17)
                  << row.Technique << std::setw(17) << row.Variant << std::right << " "
                  << FormatTime(row.MeanMilliseconds) << "/frame  flicker "
                  << Number(row.Metrics.Flicker, 2) << "  moving err "
                  << Fixed(row.Metrics.MovingError, 4) << "  lag " << row.Metrics.Lag
                  << (row.Status == "ok" ? "" : "  [" + row.Status + "]") << std::endl;
      });
  const std::string table = caustics_bench::MakeTemporalTable(rows);
  const std::string csv = caustics_bench::WriteTemporalCSV(options.Output, rows);
  std::ofstream(options.Output + "/temporal.md") << table;
  std::cout << "\n"
            << table << "\nwrote " << csv << ", temporal-frames.csv and temporal.md" << std::endl;
  if (options.UpdateDocs)
  {
    UpdateDocs(options.Docs,
      MakeTemporalDocsSection(options, machine, truths, table, Milliseconds(runStart) / 1000.0),
      TemporalMarkers);
    std::cout << "updated " << options.Docs << std::endl;
  }
  if (failed > 0)
  {
    throw std::runtime_error(
      std::to_string(failed) + " sequence run(s) failed; their rows in " + csv + " say why");
  }
  return 0;
}

/** --table1: paper 002's Table 1 for the cascaded technique (CausticsBenchTable1.h). */
int RunTable1(const Options& options)
{
  CheckOutputs(options);
  Machine machine = DescribeMachine();
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options, machine);
  caustics_bench::Table1Settings settings;
  settings.Scene = options.ScenesGiven ? options.Scenes.front() : "pool";
  settings.Size = options.Size;
  if (options.Smoke)
  {
    settings.LightBufferResolution = 64;
    settings.Photons = { 1024, 2048, 4096 };
    settings.Frames = 1;
  }
  std::cout << "caustics-bench --table1: " << settings.Scene << ", " << settings.Size << "x"
            << settings.Size << ", " << machine.CPU << " (" << machine.Threads << " threads)"
            << std::endl;
  const auto rows = caustics_bench::RunTable1(settings, window);
  DescribeGL(window, machine);
  const std::string table = caustics_bench::MakeTable1Markdown(settings, rows) + "\n" +
    machine.CPU + " (" + std::to_string(machine.Threads) + " threads), " + machine.GLRenderer +
    ", load average " + machine.LoadAverage + " at the start; " + options.CommandLine + "\n";
  const std::string path = options.Output + "/table1.md";
  std::ofstream(path) << table;
  std::cout << "\n" << table << "\nwrote " << path << std::endl;
  return 0;
}

/** --volume: the volume caustics' tables, into <output>/volume.md. */
int RunVolume(const Options& options)
{
  CheckOutputs(options);
  Machine machine = DescribeMachine();
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options, machine);
  caustics_bench::VolumeSettings settings = options.VolumeTables;
  if (options.ScenesGiven)
  {
    settings.Scenes = options.Scenes;
  }
  settings.Size = options.Size;
  settings.Frames = options.Frames;
  settings.Warmup = options.Warmup;
  std::cout << "caustics-bench --volume: " << Join(settings.Scenes) << " x "
            << Join(settings.Techniques) << ", " << settings.Size << "x" << settings.Size << ", "
            << machine.CPU << " (" << machine.Threads << " threads)" << std::endl;
  const std::string tables = caustics_bench::RunVolumeTables(settings, window, std::cout);
  const std::string path = options.Output + "/volume.md";
  std::ofstream(path) << "Generated by `" << options.CommandLine << "` on "
                      << machine.CPU << ".\n\n"
                      << tables;
  std::cout << "\n" << tables << "\nwrote " << path << std::endl;
  return 0;
}

int Run(const Options& options, OneLineOutputWindow* messages)
{
  if (options.Table1)
  {
    return RunTable1(options);
  }
  if (options.Animate > 0)
  {
    return RunTemporal(options, messages);
  }
  if (options.Volume)
  {
    return RunVolume(options);
  }
  const auto runStart = std::chrono::steady_clock::now();
  const std::vector<Configuration> table = MakeConfigurations();
  if (options.List)
  {
    PrintConfigurations(table);
    return 0;
  }
  CheckOutputs(options);
  CSVWriter csv;
  csv.Open(options.Output);
  Results results;
  results.Computer = DescribeMachine();
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(options, results.Computer);
  std::cout << "caustics-bench: " << Join(options.Scenes) << " x " << Join(options.Techniques)
            << ", " << options.Size << "x" << options.Size << ", " << options.Frames
            << " frames after " << options.Warmup << " warm-up, " << results.Computer.CPU << " ("
            << results.Computer.Threads << " threads), window " << results.Computer.Window
            << std::endl;
  for (const auto& scene : options.Scenes)
  {
    MeasureScene(options, scene, table, window, csv, results, messages);
  }
  std::cout << "wrote " << csv.RowsPath << ", " << csv.StagesPath << " and " << csv.ThroughputPath
            << std::endl;
  WritePlotAndDocs(options, csv, results, Milliseconds(runStart) / 1000.0);
  if (results.Failed > 0)
  {
    throw std::runtime_error(std::to_string(results.Failed) +
      " configuration(s) failed; their rows in " + csv.RowsPath + " say why");
  }
  return 0;
}
}

int main(int argc, char* argv[])
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique(); // the CPU technique, by name
  // Errors are taken per configuration: the one they broke fails, naming the first.
  return caustics_cli::RunMain("caustics-bench", caustics_cli::LoggedErrors::Remember,
    [&](OneLineOutputWindow* messages)
    {
      const Options options = Parse(argc, argv);
      if (options.Help)
      {
        std::cout << Usage;
        return 0;
      }
      return Run(options, messages);
    });
}
