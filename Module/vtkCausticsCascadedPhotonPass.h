/**
 * @class   vtkCausticsCascadedPhotonPass
 * @brief   Caustics by cascaded image-space photon tracing: the light's view, then the camera's.
 *
 * Meenrattanakorn and Lambers, "Real-Time Caustics Using Cascaded Image-Space Photon
 * Tracing" (002_97e66a5090de9b07.txt). Per light, Render() follows the paper's steps:
 * 1. inputs (§3.1): the light buffers (reflective shadow map with flux per texel)
 *    and the camera's opaque G-buffer; the first specular event of every texel is
 *    the shared vtkCausticsPhotonEmitter's (both Fresnel branches of a refractor);
 * 2. light layers: the opaque surfaces (receivers, reflectors) and the refractors'
 *    nearest and farthest faces, seen from the light (the paper's opaque-pass RSM
 *    depth, plus the back faces that let a photon leave a refractor);
 * 3. ray generation (§3.1): NumberOfPhotons points of the R2 low-discrepancy
 *    sequence (Roberts' plastic-number sequence, a blue-noise-like point set that
 *    needs no texture or script), rotated by a per-frame random offset
 *    (Cranley-Patterson) so that each frame is an independent unbiased estimate for
 *    a temporal denoiser to average; each point picks an emitter texel, the flux is
 *    scaled by texels per photon, and the Fresnel branch is chosen by Russian
 *    roulette on the exact reflectance (flux divided by the probability);
 * 4. the cascade (§3.2): inside a refractor the photon marches through the light's
 *    image to the exit face and refracts (or reflects, by roulette); in air it
 *    marches through the light's image against the opaque depth, the termination
 *    refined by Eq. 2; where the ray leaves the light's view or passes behind what
 *    the light sees, the last position is reprojected into the camera's view and
 *    the march goes on there against the camera's depth (Fig. 5); hits pass the
 *    normal check; mirrors reflect, up to MaximumEvents specular events; a
 *    participating medium (homogeneous, or a density grid) attenuates every stretch
 *    in air (not in the water under an open sheet, as in the reference);
 * 5. irradiance (Eq. 3): the landed photons, in the shared photon record layout, go
 *    to vtkCausticsPhotonSplatter, whose energy-normalized splats give W/m^2;
 * 6. volume caustics, with a scattering medium only: the stretches in air of step 4
 *    are appended as they are travelled and drawn by the shared line-based stage
 *    (caustics::gl::VolumeSegmentList, vtkCausticsVolumeLines, 003 §4-5) into the
 *    volume layer (stages "cascaded volume lines" and "cascaded volume blur").
 * CameraStage off keeps step 4 in the light's view (photons leaving it are lost).
 * Where the camera's march starts at a point the camera does not see, the paper drops
 * the photon (Fig. 7); here it marches on behind until it comes out in front
 * (MarchHiddenStarts). GetLastFramePhotonStatistics says how much light was lost.
 * Not done: the paper's roughness and luminance cut-offs (every surface is either
 * perfectly specular or diffuse here, and a luminance cut-off would bias the
 * estimate); camera-view marches see no refractors.
 */
#ifndef vtkCausticsCascadedPhotonPass_h
#define vtkCausticsCascadedPhotonPass_h

#include "vtkCausticsRenderPass.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsCascadedSettings.h" // For caustics::CascadedSettings

#include <memory> // For std::unique_ptr

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsCascadedPhotonPass : public vtkCausticsRenderPass
{
public:
  static vtkCausticsCascadedPhotonPass* New();
  vtkTypeMacro(vtkCausticsCascadedPhotonPass, vtkCausticsRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Photons sampled per light and frame (§3.1), in [0, 16777216]; each carries the
   * flux of LightBufferResolution^2 / NumberOfPhotons texels. Default 65536.
   */
  vtkCausticsSettingClampMacro(Settings, NumberOfPhotons, int, 0, 16777216);
  ///@}

  ///@{
  /**
   * Reproject photons that leave the light's view (or pass behind what it sees) into
   * the camera's view and march on there (§3.2, Fig. 5). Off: light view only.
   * Default on.
   */
  vtkCausticsSettingMacro(Settings, CameraStage, bool);
  vtkBooleanMacro(CameraStage, bool);
  ///@}

  ///@{
  /**
   * A photon reprojected into the camera's view at a point the camera does not see
   * (behind the surface its pixel shows: a mirror's or a wall's far side) marches on
   * behind that surface until it comes out in front, and may land there. The paper
   * drops it (§3.2, Fig. 7): off. On, a mirror bunny's caustic keeps the light it
   * sends from faces the camera does not see (flux 0.73 -> 0.93 of the reference's,
   * docs/technique-cascaded.md). Default on.
   */
  vtkCausticsSettingMacro(Settings, MarchHiddenStarts, bool);
  vtkBooleanMacro(MarchHiddenStarts, bool);
  ///@}

  ///@{
  /** Most pixels one march visits in one view, in [8, 8192]. Default 512. */
  vtkCausticsSettingClampMacro(Settings, MarchSteps, int, 8, 8192);
  ///@}

  ///@{
  /** Specular events a photon may meet after emission, in [1, 32]. Default 8. */
  vtkCausticsSettingClampMacro(Settings, MaximumEvents, int, 1, 32);
  ///@}

  ///@{
  /**
   * Splat radius in photon spacings of the unoccluded beam on the receiver, in
   * [0.5, 16]. Default 2.
   */
  vtkCausticsSettingClampMacro(Settings, KernelSpacings, double, 0.5, 16.0);
  ///@}

  ///@{
  /**
   * Volume caustics in a scattering medium (vtkCausticsVolumeLines, 003 §4-5, fed by
   * this technique's photon pieces after their first specular event): the standard
   * deviation of the Gaussian of the volume layer in pixels (0: none; default 1.5), and
   * the pieces of a segment in a density grid (003 §5.2; 0 marches per fragment;
   * default 8). Without a scattering medium no volume stage runs.
   */
  vtkCausticsSettingClampMacro(Settings, VolumeBlurPixels, double, 0.0, 16.0);
  vtkCausticsSettingClampMacro(Settings, VolumeSubSegments, int, 0, 64);
  ///@}

  ///@{
  /**
   * Index of the next frame's sample set (the R2 rotation and the roulette's seed);
   * it advances by one every frame. Set it to repeat a frame. Default 0.
   */
  vtkSetMacro(FrameIndex, unsigned int);
  vtkGetMacro(FrameIndex, unsigned int);
  ///@}

#ifndef __VTK_WRAP__
  /** Its appended volume segments (capacity, sizing, count; for tests). */
  const caustics::gl::VolumeSegmentList* GetVolumeSegmentList() const override;
#endif

protected:
  vtkCausticsCascadedPhotonPass();
  ~vtkCausticsCascadedPhotonPass() override;

  CausticNeeds GetCausticNeeds() override;
  PhotonStorage GetPhotonStorage() override;
  bool RenderCausticIrradiance(const FrameInputs& in) override;
  /** The volume caustics of the photons' stretches in air (a scattering medium only). */
  bool RenderVolumeRadiance(const FrameInputs& in, vtkTextureObject* target) override;
  bool WritesPhotonVariance() override { return true; } // the shared deposit stages
  void ReleaseTechniqueResources(vtkWindow* w) override;

#ifndef __VTK_WRAP__
  /**
   * Where the last frame's photons' light went (GetLastFramePhotonStatistics), summed
   * over the lights: FluxHits landed; FluxEscaped left the light's and the camera's views, or
   * landed on a receiver's side the camera does not see; FluxLostInside was on a path the cascade
   * cannot follow: a march that starts hidden in the camera's view (Fig. 7), a refractor's exit
   * outside the light's view, the light's view left with CameraStage off, MaximumEvents reached.
   * FluxIn is after the Fresnel roulette of emission; FluxAbsorbed is not counted.
   */
  const caustics::hcm::StatisticsBuffer* GetStatisticsBuffer() override;
  // The light's view holds the refractors' nearest and farthest faces only.
  bool FollowsLightBetweenRefractors() const override
  {
    return false;
  }
#endif

  caustics::CascadedSettings Settings;
  unsigned int FrameIndex = 0;

private:
  vtkCausticsCascadedPhotonPass(const vtkCausticsCascadedPhotonPass&) = delete;
  void operator=(const vtkCausticsCascadedPhotonPass&) = delete;

  bool Emit(const FrameInputs& in, int light);
  bool RenderLightLayers(const FrameInputs& in, int light);
  bool Trace(const FrameInputs& in, int light);
  bool Splat(const FrameInputs& in);
  bool DrawVolumeLines(const FrameInputs& in);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
