/**
 * @class   vtkCausticsHierarchicalCausticMapPass
 * @brief   Caustics by hierarchical caustic maps (Wyman 2008), one multi-resolution map per light.
 *
 * Implements 001_7c07a484f7a872bb.txt on the frame of vtkCausticsRenderPass,
 * which renders the light buffers (reflective shadow maps aimed at the specular
 * actors, LightBufferResolution texels per side: the photon buffer's size N).
 * For every light whose view holds a specular actor (others run no photon stage):
 * 1. Photon buffer (§2, Fig. 2): vtkCausticsPhotonEmitter makes one photon per
 *    light-buffer texel after its first specular interaction (N x 2N with the
 *    Fresnel-reflected branch); vtkCausticsPhotonBuffer follows refracted photons
 *    to the refractor's back faces as the light sees them and out, and finds where
 *    every photon lands on a receiver: its hit, flux, and the texel's measure
 *    omega_i.
 * 2. Gather (§3, vtkCausticsPhotonBufferHierarchy): the validity mipmap of the
 *    photon buffer is traversed from 16^2 down, discarding subtrees without a valid
 *    photon (GATHER_HIERARCHICAL) or every photon is visited (GATHER_FLAT, the
 *    Wyman & Davis 2006 baseline); converging photons are clustered at the last
 *    level or at all levels (§3.2, intensity modifier 4^k); each splat gets its
 *    radius from the beam's divergence (Eq. 2, max-distance approximation) and the
 *    level of the multi-resolution map its size calls for (§3.3), or the constant
 *    baseline size. All on the GPU with compute shaders and indirect dispatch.
 * 3. Caustic map (vtkCausticsCausticMap): the splat lists are drawn with indirect
 *    draws, photons fetched by index (§4), with energy-normalized kernels into the
 *    levels of the light's map (irradiance, W/m^2).
 * 4. Final render: each light's map is projected onto the camera's receivers like
 *    a shadow map, with a visibility test against the map's own receivers, and the
 *    levels summed (Eq. 3); the lights add up in CausticFramebuffer.
 * 5. Volume caustics, with a scattering medium only: the photon buffer's trace appends
 *    each photon's pieces in air (mirror to mirror to receiver) and the shared
 *    line-based stage (caustics::gl::VolumeSegmentList, vtkCausticsVolumeLines,
 *    003 §4-5) draws them, light after light, into the volume layer. Under an open
 *    water sheet the medium is left out, as in the reference.
 * Stages are timed as "hcm photon buffer" (with "hcm emit", "hcm light layers",
 * "hcm trace" and, with a scattering medium, "hcm volume lines" inside), "hcm gather"
 * (with "hcm traversal" and "hcm splat" inside), "hcm final render" and, with a
 * scattering medium, "hcm volume blur"; with synchronous timings each stage ends with
 * glFinish, so that its CPU time is its wall time. GPU counters (photons processed per
 * level, valid photons, clusters, splats per level, flux of the splats needing
 * level 4+) are read only on request (GetCounters). See docs/technique-caustic-maps.md.
 */
#ifndef vtkCausticsHierarchicalCausticMapPass_h
#define vtkCausticsHierarchicalCausticMapPass_h

#include "vtkCausticsRenderPass.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsCausticMapSettings.h" // For caustics::CausticMapSettings

#include <memory> // For std::unique_ptr

class vtkCausticsCausticMap;
class vtkCausticsPhotonBuffer;
class vtkCausticsPhotonBufferHierarchy;
class vtkImageData;
namespace caustics
{
struct LightView;
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsHierarchicalCausticMapPass
  : public vtkCausticsRenderPass
{
public:
  static vtkCausticsHierarchicalCausticMapPass* New();
  vtkTypeMacro(vtkCausticsHierarchicalCausticMapPass, vtkCausticsRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The modes of caustics::CausticMapSettings (documented there), for the VTK API.
  enum GatherModes
  {
    GATHER_FLAT = caustics::CausticMapSettings::GATHER_FLAT,
    GATHER_HIERARCHICAL = caustics::CausticMapSettings::GATHER_HIERARCHICAL
  };
  enum ClusterModes
  {
    CLUSTER_NONE = caustics::CausticMapSettings::CLUSTER_NONE,
    CLUSTER_LAST_LEVEL = caustics::CausticMapSettings::CLUSTER_LAST_LEVEL,
    CLUSTER_ALL_LEVELS = caustics::CausticMapSettings::CLUSTER_ALL_LEVELS
  };
  enum SplatModes
  {
    SPLAT_CONSTANT = caustics::CausticMapSettings::SPLAT_CONSTANT,
    SPLAT_VARYING_SINGLE = caustics::CausticMapSettings::SPLAT_VARYING_SINGLE,
    SPLAT_VARYING_MULTIRES = caustics::CausticMapSettings::SPLAT_VARYING_MULTIRES
  };

  // The knobs below live in one caustics::CausticMapSettings value, which the
  // stages take by const reference each frame (GetSettings()).

  ///@{
  /**
   * How the photon buffer is gathered: GATHER_HIERARCHICAL (the validity mipmap's
   * traversal, §3.1) or GATHER_FLAT (every photon, the Wyman & Davis 2006
   * baseline). Default GATHER_HIERARCHICAL.
   */
  vtkCausticsSettingClampMacro(Settings, GatherMode, int, GATHER_FLAT, GATHER_HIERARCHICAL);
  ///@}

  ///@{
  /**
   * Clustering of converging photons (hierarchical gather only): CLUSTER_NONE,
   * CLUSTER_LAST_LEVEL or CLUSTER_ALL_LEVELS (§3.2). Default CLUSTER_LAST_LEVEL
   * (the paper's fastest).
   */
  vtkCausticsSettingClampMacro(Settings, ClusterMode, int, CLUSTER_NONE, CLUSTER_ALL_LEVELS);
  ///@}

  ///@{
  /**
   * Splat sizes: SPLAT_CONSTANT (ConstantSplatRadius pixels, one map level, the
   * paper's baseline), SPLAT_VARYING_SINGLE (Eq. 2 radius, one level) or
   * SPLAT_VARYING_MULTIRES (Eq. 2 radius into the multi-resolution map, §3.3).
   * Default SPLAT_VARYING_MULTIRES.
   */
  vtkCausticsSettingClampMacro(Settings, SplatMode, int, SPLAT_CONSTANT, SPLAT_VARYING_MULTIRES);
  ///@}

  ///@{
  /**
   * How the landed photons become irradiance: RECONSTRUCTION_SPLATS, the paper's
   * splats (SplatMode) into the map, projected onto the camera's receivers;
   * RECONSTRUCTION_TRIANGLES, the shared reconstruction's caustic triangles
   * (vtkCausticsPhotonSplatter) straight into the camera's view, as the other
   * techniques draw them, with the Eq. 2 radii for the splats of the flux of the
   * triangles refused: no map texel limits them. Default splats.
   */
  enum
  {
    RECONSTRUCTION_SPLATS = 0,
    RECONSTRUCTION_TRIANGLES = 1
  };
  vtkCausticsSettingClampMacro(Settings, Reconstruction, int, 0, 1);
  void SetReconstructionToSplats() { this->SetReconstruction(RECONSTRUCTION_SPLATS); }
  void SetReconstructionToTriangles() { this->SetReconstruction(RECONSTRUCTION_TRIANGLES); }
  ///@}

  ///@{
  /**
   * Texels per side of each light's caustic map (its finest level), in [16, 8192].
   * The map looks from the light at the part of the scene the camera sees
   * (MinimumMapIncidence). Default 512.
   */
  vtkCausticsSettingClampMacro(Settings, CausticMapResolution, int, 16, 8192);
  ///@}

  ///@{
  /**
   * Nodes per side of the mipmap level the traversal starts from (the first level
   * at most this wide; the paper's 16^2), in [1, 4096]. Default 16.
   */
  vtkCausticsSettingClampMacro(Settings, TraversalStartResolution, int, 1, 4096);
  ///@}

  ///@{
  /**
   * Kernel radius over the photon spacing on the receiver (Eq. 2's radius in units
   * of the unoccluded footprint's), in [0.25, 16]. Default 2: on a regular photon
   * grid the summed kernels then ripple by 8 % peak to peak (1.5: 17 %, 1: 66 %),
   * see docs/technique-caustic-maps.md.
   */
  vtkCausticsSettingClampMacro(Settings, SplatScale, double, 0.25, 16.0);
  ///@}

  ///@{
  /**
   * The photon spacing of Eq. 2 (beyond the paper). The paper takes the largest
   * distance to the four adjacent photons on the same receiver, which is right for a
   * beam spread evenly but makes a beam squeezed along one axis (a fold, a mirror's
   * nephroid) as wide as its long axis: the caustic is blurred across. The spacing is
   * the beam's mean width, the geometric mean of its largest distances along the
   * grid's two axes, but at least this fraction of the largest distance, so that kernels still overlap along the long axis. In [0.05, 1];
   * 1 is the paper's max distance. Default 0.5 (docs/technique-caustic-maps.md, §4).
   */
  vtkCausticsSettingClampMacro(Settings, MaxDistanceFraction, double, 0.05, 1.0);
  ///@}

  ///@{
  /**
   * Kernel radius of SPLAT_CONSTANT, in finest-level caustic map pixels, in
   * [0.5, 64]. Default 1.5 (the paper's 3^2-pixel splats).
   */
  vtkCausticsSettingClampMacro(Settings, ConstantSplatRadius, double, 0.5, 64.0);
  ///@}

  ///@{
  /**
   * Largest splat diameter, in pixels of its caustic map level, before it moves one
   * level coarser (§3.3: 5.0 "gave the best performance"), in [1, 64]. Default 5.
   */
  vtkCausticsSettingClampMacro(Settings, SplatSizeThreshold, double, 1.0, 64.0);
  ///@}

  ///@{
  /**
   * Smallest splat radius in pixels of its map level, in [1, 16]: a narrower kernel
   * falls between pixel centres and loses energy. Clusters get this radius (the
   * constant one with SPLAT_CONSTANT). Default 1.5.
   */
  vtkCausticsSettingClampMacro(Settings, MinimumSplatRadius, double, 1.0, 16.0);
  ///@}

  ///@{
  /**
   * Smallest radius of the varying splats and of the clusters, in pixel footprints
   * of the camera (the square root of a pixel's area on the receiver where the
   * photon lands, as the reference's kernel), in [0, 16]; 0 turns it off. Default 1.
   * A kernel narrower than a camera pixel puts detail into the caustic map that the
   * image cannot show: the final render samples the map at one point per pixel, so
   * that detail aliases into noise, the more the finer the map. With this floor the
   * map is filtered to the image's resolution and its result no longer depends on
   * the map's (SPLAT_CONSTANT, the paper's baseline, ignores it).
   */
  vtkCausticsSettingClampMacro(Settings, MinimumCameraSplatRadius, double, 0.0, 16.0);
  ///@}

  ///@{
  /** Largest splat radius in pixels of its map level (bounds the cost), in [2, 360]. Default 32. */
  vtkCausticsSettingClampMacro(Settings, MaximumSplatRadius, double, 2.0, 360.0);
  ///@}

  ///@{
  /**
   * Drop splats that need map level 4 or coarser, as the paper does, instead of
   * splatting them into level 3; their flux is counted either way (GetCounters).
   * Default off.
   */
  vtkCausticsSettingMacro(Settings, DropCoarseSplats, bool);
  vtkBooleanMacro(DropCoarseSplats, bool);
  ///@}

  ///@{
  /**
   * Refractive interfaces a photon may meet inside a refractor after entering it
   * (total internal reflections + the exit), in [1, 32]. Default 8.
   */
  vtkCausticsSettingClampMacro(Settings, MaximumInternalEvents, int, 1, 32);
  ///@}

  ///@{
  /**
   * Mirrors a photon in air may meet after its emission (each reflects it with the
   * conductor's Fresnel reflectance; the paper's photons stop at the first diffuse
   * surface they meet and pass through any further specular one), in [0, 16]. 0:
   * a mirror in the way stops the photon. Default 3 (as screen-space's bounces).
   */
  vtkCausticsSettingClampMacro(Settings, MaximumReflections, int, 0, 16);
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
   * A second caustic map for the receivers hidden from the light by nearer receivers
   * (vtkCausticsCausticMap, peeled behind the first map's): refraction and mirrors
   * bend light onto them, e.g. the floor along a pool's sunlit wall. Off, photons
   * bound there are lost (counted as escaped). Costs a second set of receiver levels,
   * a splat of the photons that land there and a second final-render pass. Default on.
   */
  vtkCausticsSettingMacro(Settings, HiddenReceivers, bool);
  vtkBooleanMacro(HiddenReceivers, bool);
  ///@}

  ///@{
  /** Emit a refractor's Fresnel-reflected part as a second photon branch. Default on. */
  vtkCausticsSettingMacro(Settings, SplitFresnel, bool);
  vtkBooleanMacro(SplitFresnel, bool);
  ///@}

  ///@{
  /**
   * The least angle, in degrees, at which the caustic map's view sees the receivers
   * (default 45, [0, 90]). The map lives in the light's view (§2); a light that meets
   * the receivers beyond the specular actors at a smaller angle
   * (GetReceiverIncidence()) sees them nearly edge-on, with no texels for the caustic
   * to land on (a sun parallel to the floor drew nothing). The map's view is then
   * turned about that receiver point, towards its normal, to this angle; photons
   * still come from the light. 0 keeps the paper's light view always.
   */
  vtkCausticsSettingClampMacro(Settings, MinimumMapIncidence, double, 0.0, 90.0);
  ///@}

#ifndef __VTK_WRAP__
  /** All the knobs above, as the stages receive them. */
  const caustics::CausticMapSettings& GetSettings() const
  {
    return this->Settings;
  }
#endif

  /** Lights of the last frame (traced or not). */
  int GetNumberOfLights() const;

  /** True when light i ran the photon stages in the last frame (its view holds a specular actor).
   */
  bool GetLightTraced(int i) const;

  /**
   * The angle in degrees at which light i meets the receivers beyond the reflectors
   * and refractors (caustics::ReceiverIncidenceAngle: 90 head-on, 0 grazing). Under
   * MinimumMapIncidence the caustic map's view is turned to it.
   */
  double GetReceiverIncidence(int i) const;
#ifndef __VTK_WRAP__
  /** The view light i's caustic map was stored in, in the last frame (null if out of range). */
  const caustics::LightView* GetMapView(int i) const;
  /** Scene size over its specular actors' beyond which the frame warns (and "best" avoids it). */
  static constexpr double SCENE_SCALE_LIMIT = 20.0;
#endif

#ifndef __VTK_WRAP__
  /** Per-frame GPU counters of one light: the photon buffer's and the gather's. */
  struct Counters
  {
    long long Photons = 0;    ///< photons emitted
    long long Hits = 0;       ///< photons that landed on a receiver (valid photons)
    long long HiddenHits = 0; ///< of them, on a hidden receiver (HiddenReceivers)
    long long LostInside = 0; ///< no exit found inside a refractor
    long long Escaped = 0;    ///< left the caustic map's view
    long long Stored = 0;     ///< no receiver layer landed it; the caustic store did
    double FluxIn = 0.0;      ///< W emitted (summed over RGB)
    double FluxHits = 0.0;    ///< W that landed on receivers
    double FluxLostInside = 0.0;
    double FluxEscaped = 0.0;
    double FluxStored = 0.0;
    double FluxInternalReflection = 0.0; ///< reflected back inside at exits, not followed
    double FluxAbsorbed = 0.0;
    int StartLevel = 0;              ///< first traversal level (0: flat)
    long long Processed[16] = { 0 }; ///< items processed per level (0 = photons)
    long long TotalProcessed = 0;
    long long Valid = 0; ///< valid photons counted by the gather
    long long Clusters = 0;
    long long ClusteredPhotons = 0;
    long long Splats[4] = { 0, 0, 0, 0 };
    long long CoarseSplats = 0;
    double SplatFlux[4] = { 0.0, 0.0, 0.0, 0.0 };
    double CoarseFlux = 0.0;
    double CoarseFluxFraction = 0.0;  ///< flux of splats needing level 4+ / gathered flux
    double DroppedFluxFraction = 0.0; ///< flux dropped (DropCoarseSplats) / gathered flux
  };

  /**
   * Reads light i's counters of the last frame (stalls the GPU: for tests and
   * benchmarks, never in a render loop). False if the light ran no photon stage.
   */
  bool GetCounters(int i, Counters& counters);

  /**
   * The photon buffers' statistics of the lights that ran a photon stage, summed
   * (stalls). Not followed: photons whose exit from a refractor was not found within
   * MaximumInternalEvents, and light reflected back inside at exits beyond them.
   */
  bool GetLastFramePhotonStatistics(caustics::PhotonStatistics& statistics) override;
#endif

  ///@{
  /** Convenience readers of GetCounters() (each stalls the GPU). */
  vtkIdType GetNumberOfProcessedPhotons(int light);
  vtkIdType GetNumberOfValidPhotons(int light);
  vtkIdType GetNumberOfClusters(int light);
  vtkIdType GetNumberOfSplats(int light, int level);
  double GetDroppedFluxFraction(int light);
  ///@}

  /**
   * Reads level `level` of light `light`'s caustic map (irradiance, W/m^2, array
   * "CausticMap", 3 components) into `output`. For tests; stalls the GPU.
   */
  bool ReadCausticMap(int light, int level, vtkImageData* output);

  /**
   * Reads light `light`'s photon buffer into `output`: arrays "HitPosition" (xyz, w
   * = path length, > 0 for a valid photon), "HitNormal" and "HitFlux" (rgb W, w =
   * omega_i). For tests; stalls the GPU.
   */
  bool ReadPhotonBuffer(int light, vtkImageData* output);

  /** Stage objects of light i (for tests and tools), null when out of range. */
  vtkCausticsPhotonBuffer* GetPhotonBuffer(int i);
  vtkCausticsPhotonBufferHierarchy* GetHierarchy(int i);
  vtkCausticsCausticMap* GetCausticMap(int i);

#ifndef __VTK_WRAP__
  /** Its appended volume segments (capacity, sizing, count; for tests). */
  const caustics::gl::VolumeSegmentList* GetVolumeSegmentList() const override;
#endif

protected:
  /**
   * The map covers the part of the scene the camera sees: the caustic's peak loses
   * detail once that part is more than SCENE_SCALE_LIMIT times the specular actors'
   * size (docs/reliability.md, "Far-away actors").
   */
  double GetSceneScaleLimit() override { return SCENE_SCALE_LIMIT; }
  // A photon that left a refractor meets receivers and mirrors only (the map's).
  bool FollowsLightBetweenRefractors() const override
  {
    return false;
  }
  /** The photon trace (vtkCausticsPhotonBuffer) attenuates photons by the mean density. */
  vtkCausticsHierarchicalCausticMapPass();
  ~vtkCausticsHierarchicalCausticMapPass() override;

  /** A light must reach a specular actor (the base pass tests it). */
  CausticNeeds GetCausticNeeds() override;
  PhotonStorage GetPhotonStorage() override;
  bool RenderCausticIrradiance(const FrameInputs& in) override;
  /** The volume caustics of the photons' pieces in air (a scattering medium only). */
  bool RenderVolumeRadiance(const FrameInputs& in, vtkTextureObject* target) override;
  bool WritesPhotonVariance() override { return true; } // the shared deposit stages
  void ReleaseTechniqueResources(vtkWindow* w) override;

  /** StartStage/StopStage that wait for the GPU when the timings are synchronous. */

  // The frame's steps (see the class description).
  void PrepareLights(vtkOpenGLRenderWindow* renWin);
  bool RenderPhotonBuffers(vtkOpenGLRenderWindow* renWin);
  bool GatherCausticMaps(vtkOpenGLRenderWindow* renWin);
  bool RenderFinal(vtkOpenGLRenderWindow* renWin);
  bool DrawVolumeLines(const FrameInputs& in); // one light's traced pieces

  caustics::CausticMapSettings Settings;

private:
  vtkCausticsHierarchicalCausticMapPass(const vtkCausticsHierarchicalCausticMapPass&) = delete;
  void operator=(const vtkCausticsHierarchicalCausticMapPass&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
