/**
 * @class   vtkCausticsRenderPass
 * @brief   The caustics frame: VTK's own image plus physically based caustic light.
 *
 * Composes into a normal VTK scene like vtkSSAOPass: set a delegate (by default
 * a vtkRenderStepsPass is made) and install the pass on the renderer. One frame:
 * 1. PrepareScene: vtkCausticsSceneExtractor refreshes the scene snapshot (cached
 *    per actor); vtkCausticsSceneGeometry sends what changed to the GPU.
 * 2. If nothing needs caustics (no specular actor, no light with power, or the
 *    technique says so) and no extra output is requested, the delegate renders
 *    straight into the current framebuffer and the frame ends: plain VTK cost.
 * 3. RenderDelegate: VTK's image (colour, depth) into textures.
 * 4. RenderCameraGBuffers: camera G-buffers of the opaque roles (receivers,
 *    reflectors) and of the refractors (vtkCausticsGBuffer).
 * 5. RenderLightBuffers: per-light reflective shadow maps aimed at the specular
 *    actors (vtkCausticsLightBuffers, FOCUS_SPECULAR).
 * 6. RenderCausticIrradiance: the technique (a subclass) writes the caustic
 *    irradiance, W/m^2 at each pixel's visible opaque surface point before
 *    albedo, into CausticTexture. This base class has no technique: zero.
 * 7. RenderDirectIrradiance (on request): direct irradiance, W/m^2, with shadow
 *    maps aimed at the whole scene.
 * 8. RenderTechniqueColor (techniques that change what refractors look like): an
 *    optional display colour per pixel into TechniqueColorTexture; where its alpha
 *    is 1 it replaces VTK's colour (e.g. refraction traced through glass).
 * 9. Composite: VTK's colour (or the technique's) + albedo x caustic irradiance on
 *    receivers, in VTK's display convention (VTK shades a Lambertian surface as
 *    albedo x light intensity x cos, i.e. pi x radiance for irradiance in W/m^2),
 *    + pi x the volume radiance when the technique wrote VolumeTexture this frame
 *    (TechniqueWroteVolume), written with VTK's depth into the framebuffer the
 *    pass was called with.
 * Each stage is timed (GetTimings()). Intermediate buffers can be read back as
 * vtkImageData with ReadBuffer(), for tests and debugging only.
 *
 * Adding a technique: subclass, override RenderCausticIrradiance() (and
 * NeedsCaustics() if it can tell more cheaply that there is nothing to do),
 * use the protected scene, geometry, G-buffers and light buffers, and draw
 * additively into CausticFramebuffer. A technique with volume light writes
 * VolumeTexture (RGBA32F, W/(m^2 sr)) and sets TechniqueWroteVolume; one that
 * recolours refractors overrides RenderTechniqueColor(). See docs/architecture.md.
 */
#ifndef vtkCausticsRenderPass_h
#define vtkCausticsRenderPass_h

#include "vtkImageProcessingPass.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h"         // For vtkNew members
#include "vtkWeakPointer.h" // For the last window

class vtkCausticsGBuffer;
class vtkCausticsLightBuffers;
class vtkCausticsSceneExtractor;
class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkCausticsTimings;
class vtkImageData;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace caustics
{
namespace gl
{
class FullScreenTriangle;
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
   * Keep the G-buffers, light buffers and the HDR final colour readable after the
   * frame even when nothing needs caustics (for the CLI, tests and debugging).
   * Off by default: a frame without caustics then costs what plain VTK costs.
   */
  vtkSetMacro(KeepBuffers, bool);
  vtkGetMacro(KeepBuffers, bool);
  vtkBooleanMacro(KeepBuffers, bool);
  ///@}

  ///@{
  /** Metallic actors rougher than this are receivers. Default 0.3. */
  void SetRoughnessCutoff(double cutoff);
  double GetRoughnessCutoff();
  ///@}

  /** Per-stage GPU and CPU times of the last frames. */
  vtkCausticsTimings* GetTimings() { return this->Timings; }

  /** The scene snapshot of the last frame. */
  vtkCausticsSceneExtractor* GetSceneExtractor() { return this->Extractor; }

  ///@{
  /** Shared stages of the last frame, for techniques built beside this pass and tests. */
  vtkCausticsSceneGeometry* GetGeometry() { return this->Geometry; }
  vtkCausticsGBuffer* GetCameraGBuffer() { return this->CameraGBuffer; }
  vtkCausticsGBuffer* GetRefractiveGBuffer() { return this->RefractiveGBuffer; }
  vtkCausticsLightBuffers* GetLightBuffers() { return this->LightBuffers; }
  ///@}

  /** True if the last frame ran the caustic stages. */
  vtkGetMacro(LastFrameHadCaustics, bool);

  /**
   * Reads an intermediate buffer of the last frame into `output` (point-data array
   * named `name`). Names: FinalColor, CausticIrradiance, DirectIrradiance,
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

  /** Whether the technique has anything to do this frame (after PrepareScene). */
  virtual bool NeedsCaustics();

  /**
   * The technique: add caustic irradiance (W/m^2 per channel, before albedo) of the
   * visible opaque surface at each camera pixel into CausticFramebuffer (bound,
   * cleared to zero, additive blending off: subclasses choose). Returns false on
   * failure. The base class has no technique and leaves it at zero.
   */
  virtual bool RenderCausticIrradiance(vtkOpenGLRenderWindow* renWin);

  /** Frees the technique's own GL objects (called by ReleaseGraphicsResources). */
  virtual void ReleaseTechniqueResources(vtkWindow* w);

  /**
   * Optional, after the caustic and direct irradiance of a frame with caustics: the
   * technique writes display colours (VTK's units, linear) into
   * TechniqueColorTexture (RGBA32F, Width x Height); the composite shows them
   * instead of VTK's colour where alpha is 1. Returns true if it wrote the texture
   * this frame. The base class writes nothing.
   */
  virtual bool RenderTechniqueColor(vtkOpenGLRenderWindow* renWin);

  // Stages (see the class description).
  bool PrepareScene(vtkRenderer* renderer, vtkOpenGLRenderWindow* renWin);
  void RenderDelegate(const vtkRenderState* s);
  bool RenderCameraGBuffers(vtkOpenGLRenderWindow* renWin);
  bool RenderLightBuffers(vtkOpenGLRenderWindow* renWin);
  bool RenderCaustics(vtkOpenGLRenderWindow* renWin);
  bool RenderDirectIrradiance(vtkOpenGLRenderWindow* renWin);
  void Composite(vtkOpenGLRenderWindow* renWin, bool toFinalTexture);

  // Timed stage helpers.
  void StartStage(const char* name);
  void StopStage(const char* name);

  int LightBufferResolution = 256;
  int ShadowMapResolution = 1024;
  bool ComputeDirectIrradiance = false;
  bool KeepBuffers = false;
  bool LastFrameHadCaustics = false;
  bool LastFrameHadDirect = false;
  bool LastFrameHadBuffers = false;
  bool LastFrameHadTechniqueColor = false;
  bool TechniqueWroteVolume = false; // set by a technique that wrote VolumeTexture this frame

  // Frame state shared with techniques.
  int Width = 0;
  int Height = 0;
  float WorldToClip[16];
  vtkNew<vtkCausticsSceneExtractor> Extractor;
  vtkNew<vtkCausticsSceneGeometry> Geometry;
  vtkNew<vtkCausticsGBuffer> CameraGBuffer;      // receivers and reflectors
  vtkNew<vtkCausticsGBuffer> RefractiveGBuffer;  // refractors
  vtkNew<vtkCausticsLightBuffers> LightBuffers;  // photon buffers, aimed at specular actors
  vtkNew<vtkCausticsLightBuffers> ShadowBuffers; // shadow maps, aimed at the scene
  vtkNew<vtkTextureObject> CausticTexture;       // RGBA32F, W/m^2
  vtkNew<vtkOpenGLFramebufferObject> CausticFramebuffer;
  vtkNew<vtkTextureObject> DirectTexture; // RGBA32F, W/m^2
  vtkNew<vtkOpenGLFramebufferObject> DirectFramebuffer;
  vtkNew<vtkTextureObject> VolumeTexture;         // RGBA32F, W/(m^2 sr)
  vtkNew<vtkTextureObject> TechniqueColorTexture; // RGBA32F, display colour, a = 1: replace
  vtkNew<vtkTextureObject> DelegateColorTexture;
  vtkNew<vtkTextureObject> DelegateDepthTexture;
  vtkNew<vtkOpenGLFramebufferObject> DelegateFramebuffer;
  vtkNew<vtkTextureObject> FinalTexture; // HDR copy of the composite, on request
  vtkNew<vtkOpenGLFramebufferObject> FinalFramebuffer;
  vtkNew<vtkCausticsTimings> Timings;
  vtkWeakPointer<vtkOpenGLRenderWindow> LastWindow;

private:
  vtkCausticsRenderPass(const vtkCausticsRenderPass&) = delete;
  void operator=(const vtkCausticsRenderPass&) = delete;

  vtkNew<vtkCausticsShaderProgram> DirectProgram;
  vtkNew<vtkCausticsShaderProgram> CompositeProgram;
  caustics::gl::FullScreenTriangle* Triangle;
};

#endif
