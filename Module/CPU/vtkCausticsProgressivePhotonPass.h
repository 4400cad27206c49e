/**
 * @class   vtkCausticsProgressivePhotonPass
 * @brief   Caustics on the CPU: the reference's photon tracer, accumulated over frames.
 *
 * For machines without a GPU, where llvmpipe runs the GPU techniques on the CPU
 * anyway: the Embree photon tracer of vtkCausticsReferenceRenderer traces exact
 * paths (any number of bounces, concave glass, every receiver) and estimates the
 * caustic irradiance with its kernel. Each frame:
 * 1. the scene snapshot's hash (the reference's cache key without the seed) is
 *    compared with the last frame's; any change of geometry, material, light,
 *    camera, size or medium restarts the accumulation;
 * 2. while fewer than MaximumFrames are accumulated, LightBufferResolution^2 more
 *    photons per light are traced with a new seed, and the running mean of the
 *    frames' estimates (an estimate from all their photons) is updated;
 * 3. the mean is uploaded as the caustic irradiance (W/m^2, the same buffer and
 *    units as the GPU techniques), and in a scattering medium the volume caustic
 *    (W/(m^2 sr)).
 * The rest of the frame is the base pass's: VTK's shading, direct irradiance and
 * the camera view of glass and mirrors. It needs no light buffers. A still scene
 * converges; a moving one shows the first frame's noise.
 *
 * Registered as "cpu-progressive" by RegisterTechnique() (the tools call it; this
 * module links Embree, which the GPU passes must not).
 */
#ifndef vtkCausticsProgressivePhotonPass_h
#define vtkCausticsProgressivePhotonPass_h

#include "vtkCausticsRenderPass.h"
#include "vtkRenderingCausticsCPUModule.h" // For export macro

#include <memory> // For std::unique_ptr

class VTKRENDERINGCAUSTICSCPU_EXPORT vtkCausticsProgressivePhotonPass
  : public vtkCausticsRenderPass
{
public:
  static vtkCausticsProgressivePhotonPass* New();
  vtkTypeMacro(vtkCausticsProgressivePhotonPass, vtkCausticsRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Adds "cpu-progressive" to vtkCausticsTechniques (again: no effect). */
  static void RegisterTechnique();

  ///@{
  /**
   * Frames accumulated before tracing stops (the estimate then stays as it is
   * until something changes), in [1, 1048576]. Default 64.
   */
  vtkSetClampMacro(MaximumFrames, int, 1, 1048576);
  vtkGetMacro(MaximumFrames, int);
  ///@}

  ///@{
  /**
   * Accumulate frames while nothing changes (default on). Off, every frame is one
   * independent estimate of LightBufferResolution^2 photons with a new seed: what
   * one frame costs against the error it has, for the benchmark (k accumulated
   * frames are one estimate from k times the photons).
   */
  vtkSetMacro(Progressive, bool);
  vtkGetMacro(Progressive, bool);
  vtkBooleanMacro(Progressive, bool);
  ///@}

  ///@{
  /**
   * Radius of the density-estimation kernel in pixel footprints on the receiver, in
   * [0.25, 64] (vtkCausticsReferenceRenderer::KernelRadiusPixels): smaller is
   * sharper and noisier per frame, the bias that accumulation cannot remove. Default 2.
   */
  vtkSetClampMacro(KernelRadiusPixels, double, 0.25, 64.0);
  vtkGetMacro(KernelRadiusPixels, double);
  ///@}

  ///@{
  /** Threads of the tracer, 0: every core. Default 0. */
  vtkSetClampMacro(NumberOfThreads, int, 0, 4096);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /** Frames in the current estimate (0 before the first, and after a change). */
  int GetNumberOfAccumulatedFrames() const;

  /** Photons per light in the current estimate. */
  long long GetNumberOfAccumulatedPhotons() const;

  /** Forgets the estimate: the next frame starts again. */
  void Restart();

protected:
  vtkCausticsProgressivePhotonPass();
  ~vtkCausticsProgressivePhotonPass() override;

  CausticNeeds GetCausticNeeds() override;
  bool AveragesFramesItself() const override { return true; } // its own accumulation
  bool RenderCausticIrradiance(const FrameInputs& in) override;
  bool RenderVolumeRadiance(const FrameInputs& in, vtkTextureObject* target) override;

  int MaximumFrames = 64;
  bool Progressive = true;
  double KernelRadiusPixels = 2.0;
  int NumberOfThreads = 0;

private:
  vtkCausticsProgressivePhotonPass(const vtkCausticsProgressivePhotonPass&) = delete;
  void operator=(const vtkCausticsProgressivePhotonPass&) = delete;

  // RenderCausticIrradiance() in steps.
  bool Accumulate(const FrameInputs& in);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
