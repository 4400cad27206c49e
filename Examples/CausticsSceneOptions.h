// What the caustics programs that show a scene share (caustics-render, caustics-view):
// the scene, technique, quality, light, camera and medium options, their help text,
// loading the scene they name (a built-in scene, a glTF 2.0 file or a mesh), the
// overrides applied to it, and the technique's pass. Written once so that both
// programs take the same options, load scenes the same way and give the same errors.
#ifndef CausticsSceneOptions_h
#define CausticsSceneOptions_h

#include "CausticsCommandLine.h"

#include "vtkSmartPointer.h" // For MakePass

#include <array>
#include <string>
#include <vector>

class vtkCausticsBuiltinScene;
class vtkCausticsRenderPass;
class vtkRenderWindow;
class vtkRenderer;

namespace caustics_cli
{
/** The options that say what is shown and how: parsed by DeclareSceneOptions(). */
struct SceneOptions
{
  std::string Scene = "ball-lens";
  std::string Role = "refractor";
  std::string Technique = "best";
  double Time = 0.0;
  double IOR = 0.0;
  int CameraIndex = 0;
  int Photons = 0;        ///< light-buffer side; 0: the technique's default
  int TraceView = 0;      ///< screen-space: vtkCausticsScreenSpacePhotonPass::TRACE_VIEW_*
  int HiddenStarts = 0;   ///< cascaded: 0 march on (MarchHiddenStarts), 1 drop (Fig. 7)
  int Reconstruction = 0; ///< screen-space, caustic-maps, impostors: splats 0, triangles 1
  int VolumeSubSegments = -1; ///< screen-space god-rays' pieces (0: march); -1: the default
  double GodRayBlurPixels = -1.0; ///< screen-space god-rays' Gaussian (pixels); < 0: the default
  int Width = 512, Height = 512;
  int Denoise =
    -1; ///< --denoise [on|off]: 1 SVGF on the caustic irradiance, 0 off, -1 the technique's
  int ProgressiveFrames = 1; ///< --progressive N: the pass's mean of N still frames (1: off)
  /** --camera-view: vtkCausticsRenderPass::CameraViewMethods; -1: the pass's default (both). */
  int CameraView = -1;
  /** --exact-specular: vtkCausticsScreenSpaceRefraction's EXACT_OFF, _ON, _AUTOMATIC; -1: its default. */
  int ExactSpecular = -1;
  int RefractionEvents = -1; ///< --refraction-events N: the pass's RefractionEvents; -1: its default
  bool Airlight = true; ///< --airlight off: no airlight stage (vtkCausticsAirlight)
  bool HasLightDirection = false, HasLightIntensity = false;
  std::array<double, 3> LightDirection{ { 0, -1, 0 } };
  double LightIntensity = 1.0;
  bool HasCameraPosition = false, HasCameraFocal = false, HasCameraUp = false;
  std::array<double, 3> CameraPosition{}, CameraFocal{}, CameraUp{};
  double ViewAngle = 0.0;
  /** --medium and the --medium-* options (docs/scene-input.md). */
  struct MediumOptions
  {
    bool Given = false;                 ///< any of the medium options
    bool HasGrey = false;               ///< --medium SS,SA,G
    std::array<double, 3> Grey{};       ///< sigma_s, sigma_a (1/m per unit density), g
    std::string File, Grid = "density"; ///< --medium FILE.vdb[:GRID]
    bool HasScattering = false, HasAbsorption = false, HasG = false, HasDensityScale = false;
    std::array<double, 3> Scattering{}, Absorption{}; ///< per channel, 1/m per unit density
    double G = 0.0, DensityScale = 1.0;
    bool FillsRefractors = false; ///< --medium-fills-refractors (alone: the scene's medium)
  } Medium;
};

/** Help text, in the order the programs print it; each section ends with a newline. */
///@{
/** "Scene (default: ball-lens):" and its options. */
extern const char* const SceneUsage;
/** --technique (with the registered techniques), --photons, --size: no heading. */
std::string QualityUsage();
/** "Overrides:": light, camera and medium. */
extern const char* const OverridesUsage;
///@}

/** The handler of an option that sets a string. */
Arguments::ValueHandler Text(std::string& field);

/**
 * Declares --scene, --role, --ior, --time, --camera-index, --technique, --photons,
 * --denoise, --size, the light and camera overrides and --medium on `arguments`.
 * `sceneGiven` becomes true once --scene was given.
 */
void DeclareSceneOptions(Arguments& arguments, SceneOptions& options, bool& sceneGiven);

/**
 * After Arguments::Parse(): the positional argument names the scene (at most one
 * scene in all), and the technique must be registered. Throws UsageError.
 */
void FinishSceneOptions(
  const std::vector<std::string>& positionals, SceneOptions& options, bool sceneGiven);

/** "A, B, ..., best (default: X)": the techniques --technique takes. */
std::string TechniqueNames(bool withDefault);

/**
 * Loads the scene into `renderer` (a glTF file imports into `window`'s first
 * renderer): a built-in scene (kept alive by `builtin`), a glTF file, or a mesh
 * placed on a floor under a sun. Throws UsageError for an unknown scene or file
 * type, std::runtime_error when a file cannot be read.
 */
void LoadScene(const SceneOptions& options, vtkRenderWindow* window, vtkRenderer* renderer,
  vtkCausticsBuiltinScene* builtin);

/** The light, camera and medium options applied to the loaded scene; UsageError if they cannot be.
 */
void ApplyOverrides(const SceneOptions& options, vtkRenderer* renderer);

/** The technique's pass (--technique), with --photons as its LightBufferResolution and
 * --denoise. */
vtkSmartPointer<vtkCausticsRenderPass> MakePass(const SceneOptions& options, vtkRenderer* renderer);
/** --technique, with "best" resolved for the renderer's scene (vtkCausticsTechniques). */
std::string TechniqueFor(const SceneOptions& options, vtkRenderer* renderer);

/**
 * Where the last frame's photons' light went (GetLastFramePhotonStatistics, which
 * stalls the GPU: on request only): one line of shares, landed / left the views / lost
 * on paths `technique` cannot follow, or empty when the pass counts none. `warning`
 * gets a line to warn with when the lost light could be more than a tenth of the
 * caustic (caustics::PhotonStatistics::LostShareBound), else is emptied.
 */
std::string DescribePhotonLight(
  vtkCausticsRenderPass* pass, const std::string& technique, std::string& warning);
}

#endif
