/**
 * @class   vtkCausticsImpostorPhotonPass
 * @brief   Caustics via distance impostors: photons traced against the cube maps of
 *          the specular objects and their surroundings.
 *
 * Szirmay-Kalos, Aszodi, Lazanyi and Premecz, "Approximate Ray-Tracing on the GPU
 * with Distance Impostors" (004_4da4b323b51d1415.txt), §5 (caustic generation: the
 * light's view gives the photons' first hits, the refractor and environment maps
 * their paths, the hits are splatted), on the shared photon core. Per light,
 * Render() follows the paper's steps:
 * 1. the first hit (§5, "photon hits are identified"): the shared
 *    vtkCausticsPhotonEmitter takes every light-buffer texel whose first surface is
 *    specular through its first interaction (both Fresnel branches of a refractor,
 *    so the light's flux is all accounted for);
 * 2. the maps (§3-4): the base pass's vtkCausticsDistanceImpostors
 *    (GetDistanceImpostors()), brought up to date (they are redrawn only when the
 *    geometry, a light or an albedo changes, and shared with the camera view);
 * 3. the trace (§4-5, glsl/vtkCausticsImpostorPhotonTraceCS.glsl), one thread per
 *    emitted photon: inside a refractor, Hit() against its refractor map gives the
 *    exit point and normal (and against the environment map, whichever is nearer:
 *    an open refractor has no exit below); at every interface the shared
 *    CausticsSurfaceInteraction chooses reflection or refraction by Russian
 *    roulette on the exact Fresnel weights (flux divided by the probability, so the
 *    estimate is unbiased; total internal reflection stays inside), Beer-Lambert on
 *    every chord; in air, Hit() against the environment map of the kind of object
 *    the photon left (the refractors' map holds receivers and mirrors, the mirrors'
 *    holds receivers and refractors) gives the next surface in world coordinates,
 *    whether the camera or the light sees it or not; mirrors reflect, refractors
 *    are entered, up to MaximumEvents; a participating medium attenuates every
 *    stretch in air; a receiver lit on the side the camera sees ends the photon;
 * 4. reconstruction (§5, "the photon hits are splatted"): each landed photon's kernel
 *    radius grows to the spacing of its landed grid neighbours where the light
 *    spreads out (the shared vtkCausticsPhotonSpacing; the splats are
 *    energy-normalized, so only the blur changes), then the landed photons, in the
 *    shared photon record layout, go to the shared vtkCausticsPhotonSplatter
 *    (energy-normalized splats or caustic triangles, GetSplatter()), W/m^2 at the
 *    receivers the camera sees;
 * 5. receivers the camera sees only in a mirror or through glass (E-S-D-S-L paths):
 *    each landed photon's flux also goes to the environment-map texel that shows
 *    where it landed, and the light each specular texel of the light's view blocks
 *    comes off the texel where it would have landed (the caustic store,
 *    vtkCausticsDistanceImpostors::BeginCaustic); the shared camera view shades
 *    such hits with albedo x (the map's direct irradiance + that net caustic
 *    irradiance, flux over the texel's area on the surface).
 * Where the camera view traces glass and mirrors as triangles (the base pass's
 * GetScreenSpaceRefraction()->ExactSpecularGeometry: by default where one is not a
 * convex solid), the photons do too (vtkCausticsSpecularHierarchy): every specular
 * surface is the nearest triangle, the maps give the receivers around them.
 * Limits: one reference point per map, so surfaces hidden from it are missed
 * (vtkCausticsDistanceImpostors); against the maps alone (convex solids, or that
 * setting off), so are the insides of non-convex refractors, and a photon that leaves
 * a refractor does not meet that refractor again (its environment map does not hold
 * it), nor a mirror the mirror it left; the caustic store is a
 * histogram of one cube-map texel's resolution and counts in 1/4096 of the first
 * light's largest photon flux.
 */
#ifndef vtkCausticsImpostorPhotonPass_h
#define vtkCausticsImpostorPhotonPass_h

#include "vtkCausticsRenderPass.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsImpostorPhotonSettings.h" // For caustics::ImpostorPhotonSettings

#include <memory> // For std::unique_ptr

class vtkCausticsPhotonSplatter;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsImpostorPhotonPass : public vtkCausticsRenderPass
{
public:
  static vtkCausticsImpostorPhotonPass* New();
  vtkTypeMacro(vtkCausticsImpostorPhotonPass, vtkCausticsRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

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
   * Kernel radii from the landed photons' grid neighbours (vtkCausticsPhotonSpacing,
   * MEAN_DISTANCE): a photon's radius grows to KernelSpacings times the mean distance to
   * its neighbours where the light spreads out, never below the unoccluded radius.
   * Neighbours farther than SpreadStretch unoccluded spacings (another path, a
   * silhouette) do not count; 0 counts any, 1 turns the widening off. In [0, 1e6].
   * Default 64. (Until 2026-12-05 it was 8: a low sun through the ball lens spreads
   * its photons further apart than that past the focus, and the splats printed the
   * photon grid there as dots and rings, 20 % relative L2.)
   */
  vtkCausticsSettingClampMacro(Settings, SpreadStretch, double, 0.0, 1e6);
  ///@}

  ///@{
  /**
   * Index of the next frame's Russian roulette seed; it advances by one every frame,
   * so successive frames are independent estimates. Set it to repeat a frame.
   * Default 0.
   */
  vtkSetMacro(FrameIndex, unsigned int);
  vtkGetMacro(FrameIndex, unsigned int);
  ///@}

  /** The shared reconstruction (splats or caustic triangles, its radius limits). */
  vtkCausticsPhotonSplatter* GetSplatter();

  ///@{
  /**
   * How the landed photons become irradiance: the shared splatter's Reconstruction,
   * vtkCausticsPhotonSplatter::SPLATS (0) or TRIANGLES (1, caustic triangles between
   * neighbouring photons of the light's grid, drawn in the camera's view). Against
   * each pixel's mean irradiance the triangles are the closer on the ring and the
   * bunny, the splats on the ball lens (docs/technique-distance-impostors.md).
   * Default splats.
   */
  void SetReconstruction(int mode);
  int GetReconstruction();
  void SetReconstructionToSplats() { this->SetReconstruction(0); }
  void SetReconstructionToTriangles() { this->SetReconstruction(1); }
  ///@}

protected:
  vtkCausticsImpostorPhotonPass();
  ~vtkCausticsImpostorPhotonPass() override;

  CausticNeeds GetCausticNeeds() override;
  PhotonStorage GetPhotonStorage() override;
  bool RenderCausticIrradiance(const FrameInputs& in) override;
  bool WritesPhotonVariance() override { return true; } // the shared deposit stages
  void ReleaseTechniqueResources(vtkWindow* w) override;

#ifndef __VTK_WRAP__
  /**
   * Where the last frame's photons' light went (GetLastFramePhotonStatistics), summed
   * over the lights: FluxHits landed; FluxEscaped left the scene (no surface ahead in
   * the maps or the triangles) or lit a receiver's side the camera does not see;
   * FluxLostInside was lost: a map texel with no surface, a surface that is neither
   * glass, mirror nor receiver, MaximumEvents reached. FluxIn is after the emitter's
   * Fresnel split, before the medium; FluxAbsorbed is not counted.
   */
  const caustics::hcm::StatisticsBuffer* GetStatisticsBuffer() override;
  // A refractor's environment map holds receivers and mirrors, not other glass.
  bool FollowsLightBetweenRefractors() const override
  {
    return false;
  }
#endif

  caustics::ImpostorPhotonSettings Settings;
  unsigned int FrameIndex = 0;

private:
  vtkCausticsImpostorPhotonPass(const vtkCausticsImpostorPhotonPass&) = delete;
  void operator=(const vtkCausticsImpostorPhotonPass&) = delete;

  bool Emit(const FrameInputs& in, int light);
  bool UpdateMaps(const FrameInputs& in);
  bool Trace(const FrameInputs& in, int light);
  bool Spread(const FrameInputs& in);
  bool Splat(const FrameInputs& in);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
