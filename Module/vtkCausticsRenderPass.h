/**
 * @class   vtkCausticsRenderPass
 * @brief   The caustics frame: VTK's own image plus physically based caustic light.
 *
 * Composes into a normal VTK scene like vtkSSAOPass: set a delegate (by default
 * a vtkRenderStepsPass is made) and install the pass on the renderer. Render() is
 * the only frame, for every technique (a subclass fills in hooks). One frame:
 * 1. BeginFrame: the FrameResult is reset (the one place), the frame's size,
 *    camera-independent inputs and the renderer's background are noted.
 * 2. Early skip: if the technique allows it (CausticNeeds::EarlySkip), a cheap
 *    test on VTK's own actors and lights, before the scene snapshot, finds that
 *    nothing can need caustics (no specular actor; with LitSpecular, no light
 *    reaching one; with SpecularInView, none in the camera's view): the delegate
 *    renders straight into the current framebuffer, plain VTK cost.
 * 3. PrepareScene: vtkCausticsSceneExtractor refreshes the scene snapshot (cached
 *    per actor) and the FrameInputs are completed (world-to-clip).
 * 4. NeedsCaustics: the same needs on the snapshot (specular actor, receiver,
 *    light with power, and the technique's CausticNeeds). If nothing needs
 *    caustics and no extra output is requested (ComputeDirectIrradiance,
 *    KeepBuffers), plain VTK again.
 * 5. RenderDelegate: VTK's image (colour, depth) into textures;
 *    vtkCausticsSceneGeometry sends what changed to the GPU;
 *    RenderCameraGBuffers: camera G-buffers of the opaque roles (receivers,
 *    reflectors) and of the refractors (vtkCausticsGBuffer).
 * 6. If caustics are needed: RenderLightBuffers (per-light reflective shadow maps
 *    aimed at the specular actors, vtkCausticsLightBuffers FOCUS_SEEN), then
 *    with CausticFramebuffer bound and cleared the technique's hooks
 *    RenderCausticIrradiance (transport and reconstruction: W/m^2 at each
 *    pixel's visible opaque surface point before albedo) and
 *    RenderVolumeRadiance (optional, W/(m^2 sr) into VolumeTexture); with Denoise
 *    on, the caustic irradiance is then denoised in place (vtkCausticsSVGFDenoiser,
 *    SVGF as in 002_97e66a5090de9b07.txt §3.3; stage "denoise").
 * 7. RenderDirectIrradiance (ComputeDirectIrradiance, SpecularShadows in a frame
 *    with caustics, or a technique asking with EnsureDirectIrradiance): direct
 *    irradiance, W/m^2, with shadow maps aimed at the whole scene, and the part of
 *    VTK's shading that reflectors and refractors block.
 *    With a scattering medium, vtkCausticsAirlight then adds the airlight and volume
 *    shadows of the direct light (003_653219b45420e98f.txt §3) to the volume layer,
 *    whatever the technique (stage "airlight").
 * 8. RenderTechniqueColor hook (after a frame with caustics): an optional display
 *    colour per pixel; where its alpha is 1 it replaces VTK's colour (e.g.
 *    refraction traced through glass).
 * 9. Composite: VTK's colour (or the technique's) - albedo x the blocked shading
 *    (SpecularShadows) + albedo x caustic irradiance on receivers, in VTK's display
 *    convention (VTK shades a Lambertian surface as
 *    albedo x light intensity x cos, i.e. pi x radiance for irradiance in W/m^2),
 *    + pi x the volume radiance the technique wrote, with VTK's depth, into the
 *    framebuffer the pass was called with.
 * What the frame made is its FrameResult (GetLastFrameHadCaustics(), ReadBuffer()).
 * Each stage is timed (GetTimings()). Intermediate buffers can be read back as
 * vtkImageData with ReadBuffer(), for tests and debugging only.
 *
 * Adding a technique: subclass and override the hooks (protected): what it needs
 * (GetCausticNeeds(), NeedsCaustics()), its transport and reconstruction
 * (RenderCausticIrradiance(), drawing into the bound CausticFramebuffer), its extra
 * outputs (RenderVolumeRadiance(), RenderTechniqueColor()) and
 * ReleaseTechniqueResources(). Every hook gets the frame's const FrameInputs (size,
 * camera, scene snapshot, geometry, G-buffers, light buffers); no technique renders
 * a frame, skips, or classifies actors itself. vtkCausticsStraightPhotonPass is the
 * smallest example. See docs/architecture.md.
 */
#ifndef vtkCausticsRenderPass_h
#define vtkCausticsRenderPass_h

#include "vtkImageProcessingPass.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h"         // For vtkNew members
#include "vtkWeakPointer.h" // For the last window

#include <cstdint> // For std::uint64_t
#include <memory>  // For std::unique_ptr
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkCausticsAirlight;
class vtkCausticsCameraOpticalDepth;
class vtkCausticsDistanceImpostors;
class vtkCausticsGBuffer;
class vtkCausticsLayeredDepth;
class vtkCausticsScreenSpaceRefraction;
class vtkCausticsSpecularHierarchy;
class vtkCausticsLightBuffers;
class vtkCausticsPhotonSplatter;
class vtkCausticsSceneExtractor;
class vtkCausticsSceneGeometry;
class vtkCausticsSVGFDenoiser;
class vtkCausticsTimings;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkRenderer;
class vtkTextureObject;

namespace caustics
{
struct PhotonGrid;
struct PhotonRecords;
struct PhotonStatistics;
namespace hcm
{
class StatisticsBuffer;
}
struct SceneData;
namespace gl
{
class MediumBuffer;
class VolumeSegmentList;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsRenderPass : public vtkImageProcessingPass
{
public:
  static vtkCausticsRenderPass* New();
  vtkTypeMacro(vtkCausticsRenderPass, vtkImageProcessingPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /** Texels per side of each light's photon buffers, in [1, 8192]. Default 256. */
  vtkSetClampMacro(LightBufferResolution, int, 1, 8192);
  vtkGetMacro(LightBufferResolution, int);
  ///@}

  ///@{
  /** Texels per side of each light's shadow map (direct irradiance). Default 1024. */
  vtkSetClampMacro(ShadowMapResolution, int, 16, 8192);
  vtkGetMacro(ShadowMapResolution, int);
  ///@}

  ///@{
  /**
   * Compute the direct irradiance buffer (ReadBuffer("DirectIrradiance")) every frame.
   * Costs one shadow map and one full-screen pass per light. Default off.
   */
  vtkSetMacro(ComputeDirectIrradiance, bool);
  vtkGetMacro(ComputeDirectIrradiance, bool);
  vtkBooleanMacro(ComputeDirectIrradiance, bool);
  ///@}

  ///@{
  /**
   * Reflectors and refractors cast shadows on VTK's colour. VTK shades receivers as
   * if direct light went through glass and mirrors; the light they pass on arrives
   * as the caustic, so with caustics the composite takes off the part of VTK's
   * diffuse shading they block (part of ReadBuffer("LostShading"), with VTK's own
   * light falloff, from the direct irradiance's shadow maps). With a medium
   * (vtkCausticsMedium), what it takes between the light and the surface comes off
   * too, and every surface is dimmed by the medium towards the camera. Off: VTK's colour plus the
   * caustic, which counts the light through glass twice. On in the techniques that
   * carry light through reflectors and refractors (they set it in their
   * constructors); off in this base pass ("none"), whose caustic is zero.
   */
  vtkSetMacro(SpecularShadows, bool);
  vtkGetMacro(SpecularShadows, bool);
  vtkBooleanMacro(SpecularShadows, bool);
  ///@}

  ///@{
  /**
   * Keep the G-buffers, light buffers and the HDR final colour readable after the
   * frame even when nothing needs caustics (for the CLI, tests and debugging).
   * Off by default: a frame without caustics then costs what plain VTK costs.
   */
  vtkSetMacro(KeepBuffers, bool);
  vtkGetMacro(KeepBuffers, bool);
  vtkBooleanMacro(KeepBuffers, bool);
  ///@}

  ///@{
  /**
   * Denoise the caustic irradiance over space and time (SVGF,
   * vtkCausticsSVGFDenoiser, 002_97e66a5090de9b07.txt §3.3) right after the
   * technique made it, before direct light and composite; ReadBuffer
   * ("CausticIrradiance") is then the denoised irradiance (W/m^2), and
   * ReadBuffer("RawCausticIrradiance") the technique's. The history is dropped on
   * the first frame, a resize, a frame without denoising before, a change of the
   * scene's structure (meshes, materials, lights), a camera cut (too few pixels
   * reproject) or ResetDenoiserHistory(). Off in this base pass; techniques whose
   * irradiance is noisy per frame turn it on. Knobs: GetDenoiser().
   */
  vtkSetMacro(Denoise, bool);
  vtkGetMacro(Denoise, bool);
  vtkBooleanMacro(Denoise, bool);
  /** The denoising stage and its settings (vtkCausticsSVGFDenoiser's Set/Get methods). */
  vtkCausticsSVGFDenoiser* GetDenoiser();
  /** Drops the denoiser's history: the next frame starts afresh (e.g. a scripted cut). */
  void ResetDenoiserHistory();
  ///@}

  ///@{
  /**
   * Average the caustic over the frames of a still scene (vtkCausticsProgressiveMean):
   * while nothing a frame depends on changes (meshes, materials, lights, medium, the
   * camera and viewport, this pass's settings), frame k moves the light buffers' texel
   * grid by a sub-texel offset, so that its photons are a new set, and the caustic
   * irradiance and the volume radiance are the mean of the frames so far. After
   * ProgressiveFrames frames the mean is held and the caustic stages are skipped.
   * The first frame after a change is the same image as with 1. A change made through
   * a stage object (GetDenoiser(), a technique's splatter, ...) is not seen: call
   * ResetProgressive() after one. Techniques that accumulate by themselves
   * (cpu-progressive) ignore it. In [1, 4096]; 1: off. Default 1.
   */
  vtkSetClampMacro(ProgressiveFrames, int, 1, 4096);
  vtkGetMacro(ProgressiveFrames, int);
  /** Frames in the mean of the last frame (1 without averaging, 0 without caustics). */
  int GetFramesAveraged() const;
  /** Drops the mean: the next frame starts a new one. */
  void ResetProgressive();
  ///@}

  ///@{
  /** Metallic actors rougher than this are receivers. Default 0.3. */
  void SetRoughnessCutoff(double cutoff);
  double GetRoughnessCutoff();
  ///@}

  /**
   * The size of the part of the last snapshot's scene that the camera sees (with its
   * reflectors and refractors) over its reflectors' and refractors' (bounding-box
   * diagonals, caustics::VisibleOverSpecular; 0 without specular actors). See
   * GetSceneScaleLimit().
   */
  double GetLastSceneScaleRatio();

  /** Per-stage GPU and CPU times of the last frames. */
  vtkCausticsTimings* GetTimings();

  /** The scene snapshot of the last frame that took one. */
  vtkCausticsSceneExtractor* GetSceneExtractor();

  ///@{
  /** Shared stages of the last frame, for techniques built beside this pass and tests. */
  vtkCausticsSceneGeometry* GetGeometry();
  vtkCausticsGBuffer* GetCameraGBuffer();
  vtkCausticsGBuffer* GetRefractiveGBuffer();
  vtkCausticsLightBuffers* GetLightBuffers();
  ///@}

  /** True if the last frame ran the caustic stages. */
  bool GetLastFrameHadCaustics() const;

  ///@{
  /**
   * GPU bytes of the heterogeneous medium's density grid (NanoVDB, only the active
   * tiles and leaves), and the bytes a dense float grid over the same active bounds
   * would take (caustics::DensityGrid::GetDenseBytes). 0 without a density grid.
   */
  vtkIdType GetMediumGridBytes() const;
  vtkIdType GetMediumDenseBytes() const;
  ///@}

  /**
   * The most of the last frame's caustic that light lost on paths the technique
   * cannot follow could be, 0..1 (caustics::PhotonStatistics::LostShareBound of
   * GetLastFramePhotonStatistics); -1 when the technique keeps no statistics or the
   * frame traced no photon. Stalls the GPU: for tools and tests, never per frame.
   */
  double GetLastFrameLostLightBound();

#ifndef __VTK_WRAP__
  /**
   * Where the light the last frame's photons carried went, summed over the lights
   * (caustics::PhotonStatistics: landed, left the views the technique follows, on
   * paths it could not follow). Techniques that count it (caustic maps, cascaded,
   * screen-space, impostors: GetStatisticsBuffer) return true; the others false. Reads GPU
   * counters, so it stalls: for tests and tools that report it (caustics-render warns when the
   * share not followed is over 2 %), never per frame in a render loop.
   */
  virtual bool GetLastFramePhotonStatistics(caustics::PhotonStatistics& statistics);
#endif

#ifndef __VTK_WRAP__
  /**
   * The volume segments the technique's tracer appends for the volume caustics
   * (caustic maps, cascaded: their capacity, its sizing, the last trace's count), or
   * null (the base class; screen-space draws its rays directly). For tests.
   */
  virtual const caustics::gl::VolumeSegmentList* GetVolumeSegmentList() const
  {
    return nullptr;
  }

  /**
   * GPU objects and memory the caustics stages hold, from their own bookkeeping
   * (counted where the module makes its GL objects: the textures of
   * caustics::gl::EnsureTexture and of the screen-space stages, the buffer objects
   * of caustics::gl::StorageBuffer, the screen-space stages' framebuffers). Figures
   * are for every caustics pass of the process together; VTK's own objects (the
   * delegate's, vtkOpenGLFramebufferObject names, shader programs) are not counted.
   * After ReleaseGraphicsResources() of every pass, all are zero.
   */
  struct GraphicsMemory
  {
    long long Textures = 0;     ///< live textures
    long long TextureBytes = 0; ///< their storage (level 0), bytes
    long long Buffers = 0;      ///< live buffer objects
    long long BufferBytes = 0;  ///< their storage, bytes
    long long Framebuffers = 0; ///< live framebuffers the module made itself
    long long Objects() const { return this->Textures + this->Buffers + this->Framebuffers; }
    long long Bytes() const { return this->TextureBytes + this->BufferBytes; }
  };
  static GraphicsMemory GetGraphicsMemory();
#endif
  ///@{
  /** GetGraphicsMemory() for wrapped languages: objects and bytes in all. */
  static long long GetGraphicsObjects();
  static long long GetGraphicsBytes();
  ///@}

  ///@{
  /**
   * The camera's view of glass and water, shared by every technique: viewing
   * rays refracted and reflected through the refractors in screen space
   * (000_54cf099eeccf42d9.txt §4, vtkCausticsScreenSpaceRefraction) against a
   * layered depth image of the refractors, so they show what lies behind them,
   * caustics included; and mirrors reflect what the camera sees (conductor
   * Fresnel, up to RefractionEvents mirrors; VTK draws a metal without an
   * environment dark). Off, refractors are drawn by VTK as opaque surfaces.
   * On in every technique that carries light through glass (screen-space,
   * caustic maps); off in this plain pass ("none"), which carries none, so the
   * floor under water would show black. RefractionEvents: interfaces a viewing
   * ray may cross, [2, 16], default 8 (the reference's; 4 until 2026-12-05, when
   * the glass bunny's paths ended dark: 57.5 % relative L2 against 42.5 %).
   * RefractorLayers: surfaces along each pixel the layered depth image holds for
   * the march, [1, 16], default 8; one where the stage traces the glass and mirror
   * triangles instead (vtkCausticsScreenSpaceRefraction::ExactSpecularGeometry).
   * A technique may replace the stage (RenderTechniqueColor()).
   */
  vtkSetMacro(RefractionTracing, bool);
  vtkGetMacro(RefractionTracing, bool);
  vtkBooleanMacro(RefractionTracing, bool);
  vtkSetClampMacro(RefractionEvents, int, 2, 16);
  vtkGetMacro(RefractionEvents, int);
  vtkSetClampMacro(RefractorLayers, int, 1, 16);
  vtkGetMacro(RefractorLayers, int);
  /** The refractors' layered depth image of the last frame that traced refraction. */
  vtkCausticsLayeredDepth* GetRefractorLayeredDepth();
  /** The camera-view stage itself (its knobs, e.g. InternalReflections). */
  vtkCausticsScreenSpaceRefraction* GetScreenSpaceRefraction();
  ///@}

  /**
   * The stage that integrates a heterogeneous medium's optical depth from the camera
   * once per frame (its knobs: Enabled, PixelsPerColumn, Slices).
   */
  vtkCausticsCameraOpticalDepth* GetCameraOpticalDepth();

  /**
   * The airlight and volume shadows of the direct light (003_653219b45420e98f.txt §3,
   * vtkCausticsAirlight), shared by every technique: in a frame with caustics and a
   * scattering medium it adds W/(m^2 sr) to the volume layer (ReadBuffer
   * ("VolumeRadiance"), beside the technique's volume caustic), timed as "airlight";
   * without a medium it does not run. Its knobs: Enabled, Steps, LightSteps.
   */
  vtkCausticsAirlight* GetAirlight();

  ///@{
  /**
   * How the camera view of glass and mirrors (RefractionTracing) follows a ray after
   * the first surface: SCREEN_SPACE, the march against the camera's layered depth
   * (000 §4); DISTANCE_IMPOSTORS, Hit() against cube maps of distances around the
   * specular objects (004 §2-4, vtkCausticsDistanceImpostors, rendered only when
   * the geometry changes), which see what the screen does not; BOTH, the march and,
   * where it leaves the view or the scene, the impostors.
   * Default BOTH: it halves the ball lens's error against the reference and keeps every
   * screen-space answer (docs/technique-distance-impostors.md: the measurement).
   */
  enum CameraViewMethods
  {
    SCREEN_SPACE = 0,
    DISTANCE_IMPOSTORS = 1,
    BOTH = 2
  };
  vtkSetClampMacro(CameraViewMethod, int, SCREEN_SPACE, BOTH);
  vtkGetMacro(CameraViewMethod, int);
  /** The maps of DISTANCE_IMPOSTORS and BOTH (their resolution and search knobs). */
  vtkCausticsDistanceImpostors* GetDistanceImpostors();
  ///@}

  ///@{
  /**
   * GPU memory (bytes) the technique may use, checked by CheckResources(). 0
   * (default): what the driver reports, or half the physical memory for a software
   * OpenGL such as llvmpipe (its buffers live there), or no limit if neither is known.
   */
  vtkSetClampMacro(MaximumGPUMemory, double, 0.0, 1.0e18);
  vtkGetMacro(MaximumGPUMemory, double);
  ///@}

  /**
   * Whether `window`'s OpenGL context (made current) can hold this technique at the
   * current LightBufferResolution, before anything is allocated: the photon grid's
   * rows against the largest texture, the technique's largest shader storage buffer
   * against the largest storage block the shaders can see, and its estimated memory
   * against MaximumGPUMemory. On failure GetResourceError() is one line naming the
   * limit and the largest LightBufferResolution that fits. Render() checks the same
   * every frame and renders without caustics (reporting the error once) when it
   * fails; a program can call it first and refuse to start.
   */
  bool CheckResources(vtkRenderWindow* window);
  /** Why the last CheckResources() failed; empty when it passed. */
  const char* GetResourceError() const;

  /**
   * Bytes of GPU memory the volume caustics' segment lists may take: the budget of
   * CheckResources() (MaximumGPUMemory, or the device's) less the technique's own
   * estimate, as of the last check; 0 when no budget is known (the lists are then
   * bounded by the storage block size alone).
   */
  double GetVolumeSegmentBudget() const;

  /**
   * Reads an intermediate buffer of the last frame into `output` (point-data array
   * named `name`). Names: FinalColor, CausticIrradiance (denoised with Denoise on),
   * RawCausticIrradiance (the technique's, before denoising), PhotonHalfSetDifference
   * (beside the raw estimate when WritesPhotonVariance(): the difference, W/m^2, of
   * the luminance estimates of the frame's two halves of photons; its square is the
   * variance of the raw estimate), DirectIrradiance,
   * VolumeRadiance, TechniqueColor, Position, Normal, Albedo, Depth, ReceiverMask,
   * RefractivePosition, RefractiveNormal, RefractiveDepth, and per light i
   * LightPosition:i, LightNormal:i, LightFlux:i, LightDepth:i. Returns false (with
   * an error) for an unknown name or a buffer the last frame did not make.
   * Stalls the GPU: never call it inside a render loop that must be fast.
   */
  bool ReadBuffer(const char* name, vtkImageData* output);

protected:
  vtkCausticsRenderPass();
  ~vtkCausticsRenderPass() override;

  /**
   * What a frame gives the technique's hooks, built once per frame (size and
   * background at its start, the camera once the snapshot is taken). The objects
   * pointed to belong to the pass; their contents are this frame's once the stage
   * that makes them ran (light buffers: before RenderCausticIrradiance).
   */
  struct FrameInputs
  {
    vtkOpenGLRenderWindow* Window = nullptr;
    vtkRenderer* Renderer = nullptr;
    int Width = 0; ///< pixels of the renderer's (tiled) viewport
    int Height = 0;
    int Origin[2] = { 0, 0 };
    float WorldToClip[16] = {};                 ///< the camera, column-major (as GL wants it)
    const caustics::SceneData* Scene = nullptr; ///< the snapshot (the extractor's)
    double Background[3] = { 0.0, 0.0, 0.0 };   ///< the renderer's: what escaping rays see
    vtkCausticsSceneGeometry* Geometry = nullptr;
    vtkCausticsGBuffer* CameraGBuffer = nullptr;     ///< receivers and reflectors
    vtkCausticsGBuffer* RefractiveGBuffer = nullptr; ///< refractors
    vtkCausticsLightBuffers* LightBuffers = nullptr; ///< aimed at the specular actors
    vtkTextureObject* DelegateColor = nullptr;       ///< VTK's image, RGBA32F
    vtkTextureObject* DelegateDepth = nullptr;
    vtkTextureObject* CausticIrradiance = nullptr; ///< RGBA32F, W/m^2 (the technique's output)
    vtkTextureObject* DirectIrradiance = nullptr;  ///< RGBA32F, W/m^2 (when the result has it)
    /** The medium's density grid on the GPU (caustics::gl::SetMediumDefine/Uniforms). */
    const caustics::gl::MediumBuffer* MediumGrid = nullptr;
    /** Its optical depth from the camera, built after the camera G-buffers (valid with a grid). */
    vtkCausticsCameraOpticalDepth* CameraOpticalDepth = nullptr;
    /** The material of the closed refractor the eye is in, or -1 (air, a parallel view). */
    int EyeMaterial = -1;
    /** The receivers' axis-aligned bounds (xmin, xmax, ...), valid with HasReceiverBounds. */
    double ReceiverBounds[6] = { 0, 0, 0, 0, 0, 0 };
    bool HasReceiverBounds = false;
  };

  /** What the frame produced; reset at the start of every Render(). */
  struct FrameResult
  {
    bool Buffers = false;        ///< camera G-buffers (ReadBuffer works)
    bool Caustics = false;       ///< the caustic stages ran and succeeded
    bool Direct = false;         ///< direct irradiance
    bool Volume = false;         ///< the technique wrote volume radiance
    bool TechniqueColor = false; ///< the technique wrote display colours
    bool Denoised = false;       ///< the caustic irradiance was denoised (Denoise)
  };

  /**
   * What must hold for the technique to have anything to do, beyond a specular
   * actor, a receiver and a light with power. Tested by the base pass on the
   * snapshot and, when EarlySkip is on, cheaply on VTK's actors before it.
   */
  struct CausticNeeds
  {
    bool LitSpecular = false;    ///< a light reaches the specular actors' bounds
    bool SpecularInView = false; ///< a specular actor meets the camera's view frustum
    bool EarlySkip = true;       ///< the pre-snapshot test may skip the frame
    bool LightBuffers = true;    ///< the technique reads the light buffers (else not rendered)
  };

  ///@{
  /**
   * Hooks: what the technique needs. GetCausticNeeds() declares it (the base
   * class needs nothing more than the scene: a specular actor, a receiver, a light
   * with power); NeedsCaustics() is the test on the snapshot, and may be extended.
   */
  virtual CausticNeeds GetCausticNeeds();
  virtual bool NeedsCaustics(const FrameInputs& in);
  ///@}

  /**
   * What the technique stores beyond the shared stages (light buffers, emission),
   * per photon slot of one light's grid (N x 2N slots, N = LightBufferResolution),
   * and what it allocates independently of the grid, for CheckResources().
   */
  struct PhotonStorage
  {
    double BytesPerPhoton = 0.0;         ///< every buffer and texture that grows with the grid
    double LargestBufferPerPhoton = 0.0; ///< its largest single shader storage buffer
    double FixedBytes = 0.0;             ///< what does not grow with the grid (layers, maps)
    bool PerLight = false;               ///< one set per light (else reused light after light)
  };
  /** Hook: the technique's storage (the base class: none). */
  virtual PhotonStorage GetPhotonStorage();

  /**
   * Hook, the technique: add caustic irradiance (W/m^2 per channel, before albedo)
   * of the visible opaque surface at each camera pixel into CausticFramebuffer
   * (bound, cleared to zero, additive blending off: subclasses choose). Returns
   * false on failure. The base class has no technique and leaves it at zero.
   */
  virtual bool RenderCausticIrradiance(const FrameInputs& in);

  /**
   * Hook: whether RenderCausticIrradiance() writes, in alpha, the difference of the
   * luminance estimates of the frame's two halves of photons, whose square is the
   * estimate's variance (summed CausticsDeposit() of glsl/vtkCausticsCommon.glsl, as
   * the shared splat, triangle and caustic-map stages do). The denoiser uses it for short
   * histories; without it it estimates the variance from the neighbours. Default
   * false: a technique that writes anything else in alpha must not claim it.
   */
  virtual bool WritesPhotonVariance() { return false; }

  /**
   * Hook, optional, right after a successful RenderCausticIrradiance(): write
   * in-scattered volume radiance (RGBA32F, W/(m^2 sr), Width x Height) into
   * `target`. Returns true if it wrote it this frame. The base class writes nothing.
   */
  virtual bool RenderVolumeRadiance(const FrameInputs& in, vtkTextureObject* target);

  /**
   * Hook, optional, after the caustic and direct irradiance of a frame with
   * caustics: write display colours (VTK's units, linear) into `target` (RGBA32F,
   * Width x Height); the composite shows them instead of VTK's colour where alpha
   * is 1. Returns true if it wrote the texture this frame. The base class traces
   * the camera's view through the refractors (RefractionTracing).
   */
  virtual bool RenderTechniqueColor(const FrameInputs& in, vtkTextureObject* target);

  /**
   * World-space hit tolerance (m) of the camera-view stage in a scene of the
   * given size: 1e-3 of it. Techniques with their own tolerance knob return it.
   */
  virtual double GetViewTolerance(double sceneScale);

  /**
   * How many times larger than its reflectors and refractors (bounding-box
   * diagonals) the part of the scene the camera sees may be before the technique's
   * caustics lose detail, since its resolution follows that part's size
   * (GetLastSceneScaleRatio()). Beyond it, a frame warns once. 0: no limit (the
   * base pass draws no caustic).
   */
  virtual double GetSceneScaleLimit() { return 0.0; }

  /**
   * Hook: whether the technique's photons go on from one refractor into another that
   * lies beyond it along the light (a lens stack, a glass on a glass shelf), or count
   * the light they cannot follow there in their photon statistics. Where it returns
   * false and two refractors lie in line along a light (caustics::RefractorsInLine),
   * a frame warns once: the caustic beyond the second is missing or misplaced, and
   * nothing else would say so. Default true.
   */
  virtual bool FollowsLightBetweenRefractors() const
  {
    return true;
  }

  /**
   * Hook: whether the technique averages a still scene's frames by itself (its own
   * progressive accumulation); ProgressiveFrames then leaves its frames alone. Default false.
   */
  virtual bool AveragesFramesItself() const { return false; }

  /**
   * Hook: appends to `key` the settings of the technique's own stage objects that
   * ProgressiveFrames must restart on (the pass's own settings are in it already:
   * its modification time). Default: nothing.
   */
  virtual void AppendProgressiveKey(std::vector<std::uint64_t>& key);

#ifndef __VTK_WRAP__
  /**
   * Hook: the technique's photon statistics of the last frame, which
   * GetLastFramePhotonStatistics reads; null (the default) when it keeps none.
   */
  virtual const caustics::hcm::StatisticsBuffer* GetStatisticsBuffer()
  {
    return nullptr;
  }
#endif

  /** Hook: frees the technique's own GL objects (called by ReleaseGraphicsResources). */
  virtual void ReleaseTechniqueResources(vtkWindow* w);

  /**
   * Hook: the technique's stages that take a density grid's mean density instead of
   * following it (named in the warning a frame with a grid gives once); null when every
   * stage follows the grid (the base pass's direct light and composite do).
   */
  virtual const char* GetMeanDensityStages() { return nullptr; }

  /** Whether the composite takes light off VTK's shading (SpecularShadows or a medium). */
  bool CorrectsVTKShading() const;

  /**
   * For techniques that need the direct irradiance this frame: runs the direct
   * stage (timed as `stage`) unless the frame already has it. True if it has.
   */
  bool EnsureDirectIrradiance(const char* stage);

  /**
   * The shared caustic-store stage (timed "caustic store"): every photon technique
   * calls it after its transport, with its landed photon records
   * (vtkCausticsPhotonGrid.h layout, `width` x `height`) and the largest flux one
   * photon of the grid carries; `shadow` once per light (a technique that lands its
   * photons bounce after bounce stores every bounce's, the shadow with one of them).
   * Each landed photon's flux (and the light's shadow, only where the maps' radiance
   * could not take it from the shadow maps) goes to the distance impostors'
   * caustic store
   * (vtkCausticsDistanceImpostors::StoreCaustic), which the camera view reads at map
   * hits the camera does not see (a floor seen only in a mirror or through glass).
   * Nothing runs (and the store reads as zero) in a frame whose camera view reads no
   * map hit: RefractionTracing off, CameraViewMethod SCREEN_SPACE or no specular
   * triangles. Returns false on a GL failure.
   */
  bool StoreCaustic(const FrameInputs& in, int light, const caustics::PhotonRecords& landed,
    int width, int height, double maximumPhotonFlux, bool shadow = true);
  /**
   * The shared camera-view reconstruction: `splatter` splats the landed photon records
   * of `grid` (kernel radii in `kernelRadius`) into the caustic framebuffer the base
   * pass bound, over the camera's G-buffer, with the frame's receiver bounds
   * (vtkCausticsPhotonSplatter::SetReceiverBounds). Returns false on a GL failure.
   */
  bool SplatInCameraView(const FrameInputs& in, vtkCausticsPhotonSplatter* splatter,
    const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
    vtkTextureObject* kernelRadius);
  /** Whether this frame's camera view reads the caustic store (StoreCaustic() runs). */
  bool GetStoresCaustic() const { return this->StoresCaustic; }
  /**
   * The distance impostors, their caustic store opened for this frame (its fixed
   * point from `maximumPhotonFlux`, as StoreCaustic() sets it), for a trace that
   * deposits into it the photons its own receivers do not land
   * (vtkCausticsPhotonBuffer::SetCausticStore); null in a frame that stores no
   * caustic (GetStoresCaustic()) or whose store would hold blocked light besides
   * the photons' (maps' radiance without the shadows).
   */
  vtkCausticsDistanceImpostors* OpenCausticStore(double maximumPhotonFlux);
  /**
   * The camera view's hierarchy of glass and mirror triangles where it traces them
   * (its ExactSpecularGeometry: by default where one is not a convex solid), so that a
   * technique's photons meet the same surfaces; null where it does not.
   */
  vtkCausticsSpecularHierarchy* GetTracedSpecularGeometry(const caustics::SceneData& scene);

  /**
   * Brings the distance impostors' maps up to date (only when the scene changed),
   * their radiance shadowed by the direct irradiance stage's shadow maps, which it
   * draws first if they are not: the one way every technique updates them, timed as
   * "distance impostors". False on a GL failure.
   */
  bool UpdateImpostors(const FrameInputs& f);

  ///@{
  /** The last frame's inputs and result (valid after Render(); for later queries). */
  const FrameInputs& GetFrameInputs() const;
  const FrameResult& GetFrameResult() const;
  /** The window of the last frame; null once the graphics resources are released. */
  vtkOpenGLRenderWindow* GetLastWindow();
  ///@}

  // Timed stage helpers.
  void StartStage(const char* name);
  void StopStage(const char* name);
  /**
   * StartStage/StopStage that, with synchronous timings (benchmarks, tests), also
   * wait for the GPU: the stage starts on an idle GPU and ends when its work is
   * done, so its CPU time is its wall time on any implementation (Mesa's llvmpipe
   * runs compute dispatches at once but timestamps them only when it flushes its
   * rasterizer). For the techniques' compute stages.
   */
  void BeginStage(const char* name);
  void EndStage(const char* name);

private:
  vtkCausticsRenderPass(const vtkCausticsRenderPass&) = delete;
  void operator=(const vtkCausticsRenderPass&) = delete;

  // Steps of Render() (see the class description).
  void BeginFrame(const vtkRenderState* s);
  bool CannotNeedCaustics(vtkRenderer* renderer, const CausticNeeds& needs);
  bool PrepareScene(vtkRenderer* renderer);
  bool SceneNeedsCaustics(const CausticNeeds& needs);
  bool SupportsCaustics(vtkOpenGLRenderWindow* renWin, bool buffers);
  void RenderPlainVTK(const vtkRenderState* s);
  void RenderFrame(const vtkRenderState* s, bool caustics);
  void RenderDelegate(const vtkRenderState* s);
  bool RenderCameraGBuffers();
  bool RenderLightBuffers();
  bool RenderCaustics();
  bool DenoiseCaustics();
  // ProgressiveFrames: the frame's place in the run (-1: the mean is complete).
  int BeginProgressiveFrame();
  bool CheckResourcesFor(vtkOpenGLRenderWindow* renWin, int lights);
  bool FitsTheDevice(); // CheckResources() for this frame's lights, reported once per cause
  void CheckSceneScale(); // warns once when GetLastSceneScaleRatio() passes GetSceneScaleLimit()
  void CheckRefractorsInLine(); // warns once (FollowsLightBetweenRefractors())
  void CheckMediumDensity(); // uploads the density grid; warns once where a stage takes its mean
  bool RenderDirectIrradiance();
  bool RenderAirlight(); // the medium's single scattering of direct light, into the volume layer
  bool DrawDirectIrradiance();
  void SetDirectLightUniforms(int light);
  void Composite(bool toFinalTexture);
  void DrawComposite(bool toFinalTexture);

  // ReadBuffer() as a table of buffers.
  struct BufferEntry;
  static const BufferEntry* FindBuffer(const std::string& name);
  bool ReadReceiverMask(const char* name, vtkImageData* output);

  int LightBufferResolution = 256;
  int ShadowMapResolution = 1024;
  double MaximumGPUMemory = 0.0;
  bool RefractionTracing = false; // techniques that carry caustic light turn it on
  int RefractionEvents = 8;
  int RefractorLayers = 8;
  int CameraViewMethod = BOTH;
  bool ComputeDirectIrradiance = false;
  bool KeepBuffers = false;
  bool SpecularShadows = false; // techniques that carry caustic light turn it on
  bool Denoise = false;         // techniques noisy per frame turn it on
  int ProgressiveFrames = 1;    // SetProgressiveFrames(): 1 is off
  bool StoresCaustic = false;   // this frame's camera view reads the caustic store

  FrameInputs Frame;
  FrameResult Result;
  vtkWeakPointer<vtkOpenGLRenderWindow> LastWindow;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
