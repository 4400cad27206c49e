/**
 * @class   vtkCausticsSVGFDenoiser
 * @brief   Spatiotemporal variance-guided filtering (SVGF) of caustic irradiance.
 *
 * The denoising stage of 002_97e66a5090de9b07.txt §3.3, which uses SVGF (Schied
 * et al. 2017, "Spatiotemporal Variance-Guided Filtering") on the caustic
 * irradiance of every technique (vtkCausticsRenderPass::SetDenoise()). Each frame,
 * on this frame's caustic irradiance (RGBA32F, W/m^2, before albedo) and camera
 * G-buffer (vtkCausticsGBuffer: world position, normal, material and role):
 * 1. Reproject: each receiver pixel's world position is taken to where its surface
 *    point was in the last frame (per-actor motion vectors: a table of each mesh's
 *    motion, last model matrix times the inverse of this one, and its last index,
 *    with actors kept by weak pointer, so a new actor has no history), then through
 *    the previous frame's world-to-clip; the history there counts where the previous
 *    G-buffer shows the same surface (mesh, tangent plane, normal). Camera motion is
 *    followed exactly. A receiver follows its own motion only when what lights it
 *    (every reflector, refractor and light) made the same rigid motion, which leaves
 *    its irradiance as it was; otherwise its caustic stays put in the world, and so
 *    does the reprojection.
 * 2. Accumulate: colour and the first two moments of luminance, blended with
 *    max(alpha, 1/frames); a history older than the last change of what lights the
 *    receivers (Inputs::LightChanged) is dropped as a disoccluded one is when it lies
 *    outside this frame's neighbourhood (HistoryRejectionSigmas), so light that moves
 *    over a still receiver (a moving ball's caustic) does not ghost; a history begun
 *    after the change, and any on a still light field, is not tested (the test would
 *    bias sparse photons low). When fewer than MinimumReprojectedFraction of the
 *    receiver pixels reproject (a camera cut), no history is used.
 * 3. Variance of luminance from the moments; while a history is shorter than
 *    SpatialVarianceFrames, the photons' own variance averaged over it where the
 *    technique wrote one (Inputs::PhotonVariance, knob PhotonVariance), else spatially
 *    from 7x7 neighbours
 *    (SVGF's estimate, which takes a fine caustic's structure for noise).
 * 4. A-trous: AtrousIterations wavelet iterations guided by depth, normal and
 *    luminance, with symmetric weights balanced by two Sinkhorn steps so that rows
 *    and columns sum to one (a constant and the flux are both kept; SVGF's
 *    row-normalized weights lost flux on photon noise); the last output is the
 *    denoised irradiance, written back into the input texture. The colour history is the unfiltered accumulated colour
 *    (HistoryIteration 0; SVGF keeps the first iteration's output, which feeds its
 *    blur back frame after frame).
 * The filter's weights are balanced and it filters irradiance itself (already
 * free of albedo: nothing to demodulate), so W/m^2 stay W/m^2. A non-finite input
 * texel is rejected (its history carries on; zero without one), never spread; a
 * negative one counts as zero. Textures are allocated on first use and on resize
 * (which drops the history), programs compiled once; nothing is read back.
 * Knobs: caustics::DenoiserSettings (vtkCausticsDenoiserSettings.h). Cost and
 * measured figures: docs/denoising.md.
 */
#ifndef vtkCausticsSVGFDenoiser_h
#define vtkCausticsSVGFDenoiser_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsDenoiserSettings.h" // For caustics::DenoiserSettings

#include <memory> // For std::unique_ptr

class vtkCausticsGBuffer;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct Camera;
struct SceneData;
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsSVGFDenoiser : public vtkObject
{
public:
  static vtkCausticsSVGFDenoiser* New();
  vtkTypeMacro(vtkCausticsSVGFDenoiser, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The knobs live in one caustics::DenoiserSettings value (GetSettings()).
  ///@{
  /** Weight of a new frame in a long colour history, [0.01, 1]. Default 0.2 (SVGF). */
  vtkCausticsSettingClampMacro(Settings, TemporalAlpha, double, 0.01, 1.0);
  /** Weight of a new frame in a long moments history, [0.01, 1]. Default 0.2 (SVGF). */
  vtkCausticsSettingClampMacro(Settings, MomentsAlpha, double, 0.01, 1.0);
  /** Frames a history counts at most, [1, 255]. Default 32. */
  vtkCausticsSettingClampMacro(Settings, MaximumHistoryLength, int, 1, 255);
  /** Histories shorter than this take a spatial variance, [1, 255]. Default 4 (SVGF). */
  vtkCausticsSettingClampMacro(Settings, SpatialVarianceFrames, int, 1, 255);
  /** Short histories take the technique's photon variance where it writes one (else the
   * 7x7 spatial estimate). Default on. */
  vtkCausticsSettingMacro(Settings, PhotonVariance, bool);
  vtkBooleanMacro(PhotonVariance, bool);
  /** A-trous iterations, [0, 10]. Default 5 (SVGF). */
  vtkCausticsSettingClampMacro(Settings, AtrousIterations, int, 0, 10);
  /** The a-trous output kept as colour history (0: unfiltered), [0, 10]. Default 0 (SVGF:
   * 1, measured more biased, see caustics::DenoiserSettings). */
  vtkCausticsSettingClampMacro(Settings, HistoryIteration, int, 0, 10);
  /** Depth edge-stopping, pixel footprints per pixel of offset, [1e-3, 1e3]. Default 1. */
  vtkCausticsSettingClampMacro(Settings, SigmaDepth, double, 1e-3, 1e3);
  /** Normal edge-stopping exponent, [0, 1e4]. Default 128 (SVGF). */
  vtkCausticsSettingClampMacro(Settings, SigmaNormal, double, 0.0, 1e4);
  /** Luminance edge-stopping, standard deviations, [1e-3, 1e3]. Default 4 (SVGF). */
  vtkCausticsSettingClampMacro(Settings, SigmaLuminance, double, 1e-3, 1e3);
  /** History rejected outside this frame's neighbourhood mean +- this many standard
   * deviations; 0 off, [0, 100]. Default 2. */
  vtkCausticsSettingClampMacro(Settings, HistoryRejectionSigmas, double, 0.0, 100.0);
  /** Reprojection plane tolerance, fraction of the camera distance, [1e-5, 1]. Default 0.01. */
  vtkCausticsSettingClampMacro(Settings, DepthTolerance, double, 1e-5, 1.0);
  /** Reprojection normal tolerance (cosine), [-1, 1]. Default 0.9. */
  vtkCausticsSettingClampMacro(Settings, NormalTolerance, double, -1.0, 1.0);
  /** Camera cut below this fraction of reprojected receiver pixels, [0, 1]. Default 0.1. */
  vtkCausticsSettingClampMacro(Settings, MinimumReprojectedFraction, double, 0.0, 1.0);
  ///@}

#ifndef __VTK_WRAP__
  /** The knobs as one value. */
  const caustics::DenoiserSettings& GetSettings() const
  {
    return this->Settings;
  }

  /** What one frame's denoising reads; the irradiance is also where the result goes. */
  struct Inputs
  {
    vtkOpenGLRenderWindow* Window = nullptr;
    vtkTextureObject* Irradiance = nullptr;   ///< RGBA32F, W/m^2; denoised in place
    vtkCausticsGBuffer* GBuffer = nullptr;    ///< this frame's camera G-buffer (opaque roles)
    const caustics::Camera* Camera = nullptr; ///< this frame's camera (world-to-clip, eye)
    /** This frame's snapshot: its meshes' actors and matrices give the per-actor motion
     * (null: every surface is taken as still and new). */
    const caustics::SceneData* Scene = nullptr;
    int Width = 0;
    int Height = 0;
    /** Whether what lights the receivers (meshes, their matrices and materials, lights,
     * medium) changed since the last frame; the camera does not count. */
    bool LightChanged = true;
    /** Whether the optics changed (materials, lights' power and cones, medium): what a
     * rigid motion of the whole scene, lights included, leaves alone. */
    bool OpticsChanged = true;
    /** Whether the irradiance's alpha holds the variance of its luminance from its own
     * photons (CausticsDeposit in glsl/vtkCausticsCommon.glsl); short histories then
     * take it instead of a spatial estimate. */
    bool PhotonVariance = false;
  };

  /**
   * Denoises `in.Irradiance` in place (a copy of the input stays readable as
   * GetRawTexture()). Returns false if a program failed (the input is then as it was).
   */
  bool Denoise(const Inputs& in);
#endif

  /** Drops the history: the next frame starts afresh (a camera cut the caller knows of). */
  void ResetHistory();

  /**
   * Frames denoised since the history was last dropped on the CPU's knowledge (first
   * frame, ResetHistory(), resize), the last one included: 1 when it started afresh.
   * A camera cut found on the GPU (MinimumReprojectedFraction) is not counted here.
   */
  int GetFramesSinceReset() const
  {
    return this->FramesSinceReset;
  }

  /** The last frame's input as it was before denoising (RGBA32F, W/m^2). */
  vtkTextureObject* GetRawTexture();

  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkCausticsSVGFDenoiser();
  ~vtkCausticsSVGFDenoiser() override;

  caustics::DenoiserSettings Settings;

private:
  vtkCausticsSVGFDenoiser(const vtkCausticsSVGFDenoiser&) = delete;
  void operator=(const vtkCausticsSVGFDenoiser&) = delete;

#ifndef __VTK_WRAP__
  // Denoise() in steps (see the class description).
  bool EnsureTextures(const Inputs& in);
  void SetCommonUniforms(const Inputs& in, int program);
  // The per-actor motion table (step 1); true when the whole scene, lights included,
  // made one rigid motion (the light on the receivers is then unchanged).
  bool FollowActors(const Inputs& in);
  bool Reproject(const Inputs& in);
  bool Accumulate(const Inputs& in);
  bool EstimateVariance(const Inputs& in);
  bool FilterAtrous(const Inputs& in);
  bool AtrousStage(
    const Inputs& in, int stage, int iteration, vtkTextureObject* source, vtkTextureObject* output);
  void KeepForNextFrame(const Inputs& in);
#endif

  int FramesSinceReset = 0;
  int FramesSinceLightChanged = 0; // the light field has been still this long
  bool HasHistory = false;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
