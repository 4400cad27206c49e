/**
 * @class   vtkCausticsScreenSpacePhotonPass
 * @brief   Caustics by screen-space photon tracing with layered depth images.
 *
 * The technique of Krüger, Bürger and Westermann, "Interactive Screen-Space
 * Accurate Photon Tracing on GPUs" (EGSR 2006; 000_54cf099eeccf42d9.txt), on the
 * frame of vtkCausticsRenderPass. Per frame, after the base pass's G-buffers and
 * light buffers:
 * 1. layered depth image (§2.2): vtkCausticsLayeredDepth peels the scene from the
 *    camera, as many layers as its depth complexity (counted on the GPU), at most
 *    MaximumNumberOfLayers;
 * 2. per light, first transfer map (§2): vtkCausticsPhotonEmitter turns the light
 *    buffer (N x N texels, N = LightBufferResolution) into photons after their
 *    first specular interaction; they are compacted into a list on the GPU;
 * 3. line tracing (§2.1): vtkCausticsScreenSpaceLineTracer rasterizes every
 *    photon ray as a line in its own texture row and finds its first hit in any
 *    layer (within IntersectionTolerance), with a log-step reduction per row;
 * 4. specular transfer (§2.3): photons that hit reflectors or refractors are
 *    reflected or refracted (exact Fresnel, total internal reflection) into the
 *    next transfer map; steps 3-4 repeat for up to MaximumBounces specular events.
 *    Photons end at the first receiver they meet, so caustics are shadowed (§1.2).
 *    Where the camera view traces glass and mirrors as triangles
 *    (GetScreenSpaceRefraction()->ExactSpecularGeometry: by default where one is not a
 *    convex solid), a glass or mirror hit is the triangle's (vtkCausticsSpecularHierarchy)
 *    and a photon inside such glass crosses it from triangle to triangle within the
 *    bounce, up to 8 events a path;
 * 5. splatting (§3.1): photons on receivers are splatted by
 *    vtkCausticsPhotonSplatter, receiver-oriented and energy-normalized: each
 *    deposits exactly its flux, so the result is irradiance in W/m^2;
 * 6. god-rays (§3.2): with a vtkCausticsMedium on the renderer, every photon
 *    segment in the medium is drawn as a line of in-scattered radiance, W/(m^2 sr)
 *    (vtkCausticsVolumeLines, 003 §4-5), Gaussian-blurred, into VolumeTexture;
 * 7. screen-space refraction (§4, after the direct irradiance): pixels that see a
 *    refractor are traced through its own layers, refracted at the exit and looked
 *    up in the scene (vtkCausticsScreenSpaceRefraction); the composite shows that
 *    colour instead of VTK's. This is the base pass's camera-view stage, shared
 *    with every technique (vtkCausticsRenderPass::SetRefractionTracing).
 * Nothing runs (plain VTK cost) when no light reaches a specular actor or, with
 * SkipOffscreenSpecular, when none is inside the camera's view: the needs this
 * pass declares to the base pass (GetCausticNeeds()), which tests them. Every step
 * is a timed stage ("ssp ..."); nothing is read back during a frame.
 *
 * Limits (the paper's, §1.2): surfaces outside the traced view (TraceView), seen edge-on or
 * smaller than a pixel are not hit; refraction tracing sees only what the opaque
 * G-buffer shows (§4).
 */
#ifndef vtkCausticsScreenSpacePhotonPass_h
#define vtkCausticsScreenSpacePhotonPass_h

#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpaceSettings.h" // For caustics::ScreenSpaceSettings
#include "vtkRenderingCausticsModule.h"     // For export macro

#include <memory> // For std::unique_ptr

class vtkCausticsLayeredDepth;
class vtkCausticsPhotonEmitter;
class vtkCausticsPhotonSplatter;
class vtkCausticsScreenSpaceLineTracer;
class vtkImageData;
class vtkTextureObject;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsScreenSpacePhotonPass : public vtkCausticsRenderPass
{
public:
  static vtkCausticsScreenSpacePhotonPass* New();
  vtkTypeMacro(vtkCausticsScreenSpacePhotonPass, vtkCausticsRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Most depth layers peeled from the camera, in [1, 16]. Default 8 (§2.2). */
  vtkCausticsSettingClampMacro(Settings, MaximumNumberOfLayers, int, 1, 16);
  ///@}

  ///@{
  /** One layered depth image per object instead of one for the scene (§2.2). Default off. */
  vtkCausticsSettingMacro(Settings, PerObjectLayers, bool);
  vtkBooleanMacro(PerObjectLayers, bool);
  ///@}

  ///@{
  /** Most specular events (reflections, refractions) of a photon path, in [1, 8]. Default 3. */
  vtkCausticsSettingClampMacro(Settings, MaximumBounces, int, 1, 8);
  ///@}

  ///@{
  /**
   * Intersection tolerance in metres (the paper's world-space epsilon, §5); 0 uses
   * RelativeIntersectionTolerance x the diagonal of the part of the scene the camera
   * sees, with the reflectors and refractors (caustics::VisibleScale). Default 0.
   */
  vtkCausticsSettingClampMacro(Settings, IntersectionTolerance, double, 0.0, 1.0e6);
  ///@}

  ///@{
  /** Intersection tolerance as a fraction of caustics::VisibleScale. Default 0.001. */
  vtkCausticsSettingClampMacro(Settings, RelativeIntersectionTolerance, double, 1.0e-6, 0.1);
  ///@}

  ///@{
  /** Fewest fragments per traced line (§2.1). Default 8. */
  vtkCausticsSettingClampMacro(Settings, MinimumLineLength, int, 1, 256);
  ///@}

  ///@{
  /** Rows of the line-tracing target: photons per batch (§2.1). Default 8192. */
  vtkCausticsSettingClampMacro(Settings, RowsPerBatch, int, 16, 16384);
  ///@}

  ///@{
  /**
   * Splat kernel radius in metres; 0 (default) uses SplatRadiusPixels pixel
   * footprints on the receiver, the reference renderer's rule.
   */
  vtkCausticsSettingClampMacro(Settings, SplatRadius, double, 0.0, 1.0e6);
  ///@}

  ///@{
  /** Splat kernel radius in pixel footprints when SplatRadius is 0. Default 2. */
  vtkCausticsSettingClampMacro(Settings, SplatRadiusPixels, double, 0.5, 64.0);
  ///@}

  ///@{
  /**
   * With SplatRadius 0, the radius is also at least this many times the spacing of
   * the photon's neighbours in the light grid that reached the same receiver in the
   * same bounce, so that sparse photons do not print the grid (0: pixel rule only).
   * Default 2.
   */
  vtkCausticsSettingClampMacro(Settings, SplatRadiusSpacings, double, 0.0, 16.0);
  ///@}

  ///@{
  /**
   * How the landed photons become irradiance (the shared reconstruction,
   * vtkCausticsPhotonSplatter): RECONSTRUCTION_SPLATS, one kernel per photon with
   * the radius rules above; RECONSTRUCTION_TRIANGLES, caustic triangles between
   * neighbouring photons that landed together, with splats where they diverge.
   * Default splats.
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
  /** Draw god-rays when the renderer has a scattering medium (§3.2). Default on. */
  vtkCausticsSettingMacro(Settings, GodRays, bool);
  vtkBooleanMacro(GodRays, bool);
  ///@}

  ///@{
  /**
   * Standard deviation of the god-rays' Gaussian blur in pixels (§3.2: constant
   * screen-space support); 0 turns the blur off. Default 1.5.
   */
  vtkCausticsSettingClampMacro(Settings, GodRayBlurPixels, double, 0.0, 16.0);
  ///@}

  ///@{
  /**
   * Pieces each god-ray segment is split into in a heterogeneous medium
   * (vtkCausticsVolumeLines, 003 §5.2): the light-side optical depth is marched once
   * per segment and interpolated linearly within a piece. A homogeneous medium draws
   * one piece (exact). 0: march the density per fragment instead (the former
   * god-rays, many times slower; for comparison). Default 8.
   */
  vtkCausticsSettingClampMacro(Settings, VolumeSubSegments, int, 0, 64);
  ///@}


  ///@{
  /**
   * The view photons are traced in (vtkCausticsTraceView.h):
   * - TRACE_VIEW_AUTOMATIC (0, default): the camera's own view when its frustum
   *   holds every specular actor, otherwise a fitted view;
   * - TRACE_VIEW_CAMERA (1): always the camera's, as the paper does. A refractor
   *   or mirror outside the frame then does not bend the photons that pass it;
   * - TRACE_VIEW_FITTED (2): always an orthographic view along the camera's
   *   direction around the specular actors and the part of the scene in view.
   * The fitted view makes the caustic independent of the framing, at the
   * resolution of the fitted region. GetLastTraceViewFitted() tells which ran.
   */
  enum
  {
    TRACE_VIEW_AUTOMATIC = 0,
    TRACE_VIEW_CAMERA = 1,
    TRACE_VIEW_FITTED = 2
  };
  vtkCausticsSettingClampMacro(Settings, TraceView, int, 0, 2);
  void SetTraceViewToAutomatic() { this->SetTraceView(TRACE_VIEW_AUTOMATIC); }
  void SetTraceViewToCamera() { this->SetTraceView(TRACE_VIEW_CAMERA); }
  void SetTraceViewToFitted() { this->SetTraceView(TRACE_VIEW_FITTED); }
  /** True when the last frame traced its photons in the fitted view, not the camera's. */
  vtkGetMacro(LastTraceViewFitted, bool);
  /**
   * True when the last frame traced its photons in the camera's view (TRACE_VIEW_CAMERA)
   * while a reflector or refractor lay outside it: photons that pass it were not bent
   * or reflected, and the caustic depends on the framing. The pass warns once each time
   * this becomes true; the photon statistics cannot see it (those photons land).
   */
  vtkGetMacro(LastTraceViewMissedSpecular, bool);
  ///@}

  ///@{
  /**
   * Skip the caustic stages when no specular actor is inside the camera's view
   * frustum. A specular actor outside the view can still focus light onto a
   * receiver in view (the traced view then is the fitted one), so this trades the
   * correct image for speed. Default off.
   */
  vtkCausticsSettingMacro(Settings, SkipOffscreenSpecular, bool);
  vtkBooleanMacro(SkipOffscreenSpecular, bool);
  ///@}

  ///@{
  /** The stages, for tests and the benchmark (configured by this pass each frame). */
  vtkCausticsLayeredDepth* GetLayeredDepth();
  vtkCausticsScreenSpaceLineTracer* GetLineTracer();
  vtkCausticsPhotonEmitter* GetEmitter();
  vtkCausticsPhotonSplatter* GetSplatter();
  ///@}

  /** The intersection tolerance (m) the last frame used. */
  vtkGetMacro(LastTolerance, double);

  /**
   * Shadow rays traced in screen space (§5, Fig. 11), for accuracy studies: from
   * every receiver pixel of the last frame's camera G-buffer towards light `light`,
   * through the last frame's layered depth image. `output` gets the point-data
   * array "Shadow": 1 shadowed, 0 lit, -1 no receiver. Stalls the GPU (read-back):
   * never in a render loop. Returns false, with an error, when the last frame made
   * no layered depth image or the light does not exist.
   */
  bool TraceShadowRays(int light, vtkImageData* output);

protected:
  /**
   * The hit tolerance is 1e-3 of the size of what the camera sees: past 500 times
   * the specular actors' size it reaches the caustic's detail (docs/reliability.md,
   * "Far-away actors").
   */
  double GetSceneScaleLimit() override { return 500.0; }
  vtkCausticsScreenSpacePhotonPass();
  ~vtkCausticsScreenSpacePhotonPass() override;

  /**
   * A light must reach a specular actor and, with SkipOffscreenSpecular, one must
   * be inside the camera's view; the base pass tests both (before the snapshot too).
   */
  CausticNeeds GetCausticNeeds() override;
  PhotonStorage GetPhotonStorage() override;
  bool RenderCausticIrradiance(const FrameInputs& in) override;
  bool WritesPhotonVariance() override { return true; } // the shared deposit stages
  bool RenderVolumeRadiance(const FrameInputs& in, vtkTextureObject* target) override;
  double GetViewTolerance(double sceneScale) override;
  void ReleaseTechniqueResources(vtkWindow* w) override;

#ifndef __VTK_WRAP__
  /**
   * Where the last frame's photons' light went (GetLastFramePhotonStatistics), summed
   * over the lights:
   * FluxHits landed; FluxEscaped left the view the photons are traced in (out of the
   * scene, or off that view's screen) or lit a receiver's side the camera does not
   * see; FluxLostInside was lost: MaximumBounces reached on glass or a mirror, the
   * events of a path through glass traced as triangles used up, or a full transfer
   * map. FluxIn is counted at emission, before the medium; FluxAbsorbed is not.
   */
  const caustics::hcm::StatisticsBuffer* GetStatisticsBuffer() override;
#endif

  // Steps (see the class description).
  void PrepareView(const FrameInputs& in);
  /** The union of the photon frusta's focus boxes (LightView::focus) over the lights
   * that reach a specular actor; false when there is none. */
  bool PhotonFocus(const FrameInputs& in, double box[6]) const;
  bool TraceLight(const FrameInputs& in, int light, bool godRays);
  bool RenderLayers(vtkOpenGLRenderWindow* renWin);
  bool EmitPhotons(vtkOpenGLRenderWindow* renWin, int light);
  bool TracePhotons(vtkOpenGLRenderWindow* renWin, int light, int bounce);
  bool TransferPhotons(vtkOpenGLRenderWindow* renWin, int light, int bounce);
  bool SplatPhotons(vtkOpenGLRenderWindow* renWin, int light, int bounce);
  bool DrawGodRays(vtkOpenGLRenderWindow* renWin, int light, int bounce);
  bool WriteVolumeSegments(vtkOpenGLRenderWindow* renWin);

  caustics::ScreenSpaceSettings Settings;
  double LastTolerance = 0.0;
  bool LastTraceViewFitted = false;
  bool LastTraceViewMissedSpecular = false;

private:
  vtkCausticsScreenSpacePhotonPass(const vtkCausticsScreenSpacePhotonPass&) = delete;
  void operator=(const vtkCausticsScreenSpacePhotonPass&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
