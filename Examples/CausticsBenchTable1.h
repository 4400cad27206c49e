// caustics-bench --table1: Table 1 of paper 002 (Meenrattanakorn and Lambers,
// 002_97e66a5090de9b07.txt) for vtkCausticsCascadedPhotonPass: the wall time of
// tracing, storing (splatting) and denoising at several photon counts
// (docs/technique-cascaded.md, "Table 1 of the paper, measured here").
#ifndef CausticsBenchTable1_h
#define CausticsBenchTable1_h

#include <string> // For std::string
#include <vector> // For std::vector

class vtkRenderWindow;

namespace caustics_bench
{
/** What a --table1 run measures. */
struct Table1Settings
{
  std::string Scene = "pool";                              ///< a built-in scene
  int Size = 256;                                          ///< pixels per side
  int LightBufferResolution = 1024;                        ///< texels per side
  std::vector<int> Photons = { 524288, 1048576, 2097152 }; ///< per light and frame
  int Warmup = 1;                                          ///< untimed frames (programs compile)
  int Frames = 3;                                          ///< timed frames; medians are kept
};

/** One photon count's medians (ms of wall time, synchronous stage timings). */
struct Table1Row
{
  int Photons = 0;
  double Emit = 0.0;        ///< cascaded emit (ray generation, §3.1)
  double LightLayers = 0.0; ///< cascaded light layers (the light's depth images)
  double Trace = 0.0;       ///< cascaded trace (§3.1-3.2)
  double Store = 0.0;       ///< cascaded splat (Eq. 3: storing)
  double Denoise = 0.0;     ///< denoise (SVGF, §3.3)
  double Frame = 0.0;       ///< the whole Render(), finished
};

/** Renders each photon count of `settings` in `window` (resized) and returns the rows. */
std::vector<Table1Row> RunTable1(const Table1Settings& settings, vtkRenderWindow* window);

/** The rows as a Markdown table, with the settings above it. */
std::string MakeTable1Markdown(const Table1Settings& settings, const std::vector<Table1Row>& rows);
}

#endif
