// caustics-bench --animate: temporal stability of every technique on animated scenes
// (docs/benchmarks.md, "Temporal stability"), and what it shares with the static
// benchmark in caustics-bench.cxx (the reference as the benchmark sets it up, the
// caustic irradiance read back from a pass).
#ifndef CausticsBenchTemporal_h
#define CausticsBenchTemporal_h

#include "CausticsCommandLine.h" // For caustics_cli::OneLineOutputWindow

#include "vtkCausticsTemporalMetrics.h" // For vtkCausticsTemporalMetrics::Result
#include "vtkSmartPointer.h"            // For vtkSmartPointer

#include <functional> // For std::function
#include <string>     // For std::string
#include <vector>     // For std::vector

class vtkCausticsReferenceRenderer;
class vtkCausticsRenderPass;
class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;

namespace caustics_bench
{
/**
 * The renderer's scene at size x size, rendered by the reference with `photons` per
 * light, kernel radius `kernelPixels` (0: the pixel-footprint estimate), `seed`, cached
 * or not; the irradiance at each
 * pixel's nearest opaque surface, as the techniques output it.
 */
vtkSmartPointer<vtkCausticsReferenceRenderer> MakeReference(vtkRenderer* renderer, int size,
  double photons, double kernelPixels, unsigned int seed, bool cache);

/** The pass's caustic irradiance of the last frame, or zeros when it ran no caustic stage. */
vtkSmartPointer<vtkImageData> ReadCausticIrradiance(vtkCausticsRenderPass* pass, int size);

/** The animated sequences --sequences accepts, in their order in the tables. */
std::vector<std::string> GetSequenceNames();

/**
 * One technique set up one way for the temporal runs: a new pass of Technique gets
 * Setup applied. A variant of a technique (e.g. denoised) is one more line in
 * MakeTemporalVariants().
 */
struct TemporalVariant
{
  std::string Technique;
  std::string Name;
  std::function<void(vtkCausticsRenderPass*)> Setup;
};

/** Every variant, in table order (caustics-bench --animate runs those of the chosen techniques). */
std::vector<TemporalVariant> MakeTemporalVariants();

/**
 * The variants of `technique`: its entries in MakeTemporalVariants(), or its defaults
 * (variant "default") for a registered technique without entries.
 */
std::vector<TemporalVariant> TemporalVariantsOf(const std::string& technique);

/** What an --animate run needs from the command line. */
struct TemporalSettings
{
  int Frames = 16; // N: frames per sequence; the cut is at N / 2
  int Size = 128;  // image N x N pixels
  int Warmup = 2;  // untimed frames at the first frame's pose
  double ReferencePhotons = 2e6;
  double ReferenceKernel = 1.0;
  int SmokeResolution = 0; // > 0: every pass's light-buffer resolution (--smoke)
  std::vector<std::string> Sequences;
  std::vector<std::string> Techniques;
};

/** One sequence x variant: the temporal metrics and the per-frame figures. */
struct TemporalRow
{
  std::string Sequence;
  std::string Technique;
  std::string Variant;
  int Frames = 0;
  int Cut = 0;
  double MeanMilliseconds = 0.0; // wall time per frame (Render and wait for the GPU)
  vtkCausticsTemporalMetrics::Result Metrics;
  std::vector<double> FrameMilliseconds, FrameError, FrameFlux;
  std::string Status = "ok";
};

/** What the run did for the references of one sequence, for the docs. */
struct TemporalTruth
{
  std::string Sequence;
  std::string Scene;
  int Rendered = 0; // reference frames rendered (the others came from the cache)
  double Seconds = 0.0;
};

/**
 * Runs every chosen technique's variants over each chosen sequence in `window`;
 * calls `report` with each row as it is measured. Throws on a failed reference.
 */
std::vector<TemporalRow> RunTemporal(const TemporalSettings& settings, vtkRenderWindow* window,
  caustics_cli::OneLineOutputWindow* messages, std::vector<TemporalTruth>& truths,
  const std::function<void(const TemporalRow&)>& report);

/** The Markdown table of the rows (one per sequence x variant). */
std::string MakeTemporalTable(const std::vector<TemporalRow>& rows);

/** One line per sequence: what moves, the cut, the reference frames. */
std::string DescribeSequences(const TemporalSettings& settings);

/**
 * Writes temporal.csv (one row per sequence x variant) and temporal-frames.csv (one
 * per frame) into `folder`; returns the first path.
 */
std::string WriteTemporalCSV(const std::string& folder, const std::vector<TemporalRow>& rows);
}

#endif
