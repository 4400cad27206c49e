// caustics-bench --volume: the line-based volume caustics (vtkCausticsVolumeLines, paper
// 003) of each technique that writes volume lines (screen-space, caustic-maps, cascaded)
// on the media scenes: frame time against the volume caustic's error for photon counts
// and sub-segment counts, and the analogue of 003's Table 2 (caustic-buffer size x
// screen size -> frame time) per technique, and the error of ProgressiveFrames' mean of a
// still view against the time to make it, as Markdown
// (docs/technique-volume-caustics.md shows a generated run).
#ifndef CausticsBenchVolume_h
#define CausticsBenchVolume_h

#include <string> // For std::string
#include <vector> // For std::vector

class vtkRenderWindow;

namespace caustics_bench
{
/** What a --volume run needs from the command line. */
/** The techniques that feed vtkCausticsVolumeLines, in the tables' order. */
const std::vector<std::string>& VolumeTechniqueNames();

struct VolumeSettings
{
  std::vector<std::string> Scenes{ "smoke-lens", "underwater" };
  std::vector<std::string> Techniques = VolumeTechniqueNames(); ///< a subset, in any order
  std::vector<int> Grids{ 64, 128, 256 };   ///< light-buffer side N: N x N photons
  std::vector<int> SubSegments{ 1, 8, 32 }; ///< VolumeSubSegments (0: per-fragment march)
  std::vector<int> Sizes{ 64, 128, 256 };   ///< screen sizes of the Table 2 analogue
  /** ProgressiveFrames' means reported, at the largest grid (empty: no such table). */
  std::vector<int> Progressive{ 1, 2, 4, 8 };
  int Size = 128;                           ///< screen size of the time-against-error rows
  int Frames = 3;                           ///< timed frames (median)
  int Warmup = 1;                           ///< untimed frames first
  double VolumePhotons = 2e5;               ///< the reference's volume photons per light
};

/**
 * Renders every row and returns the Markdown (two tables and the settings); the
 * reference is cached like the sweep's. `progress` gets one line per row.
 */
std::string RunVolumeTables(
  const VolumeSettings& settings, vtkRenderWindow* window, std::ostream& progress);
}

#endif
