/**
 * @class   vtkCausticsLightBuffers
 * @brief   Per-light reflective shadow maps: what each light sees, and the flux per texel.
 *
 * For every light of the scene snapshot:
 * 1. caustics::ComputeLightView() gives the frustum: orthographic along a
 *    directional light, perspective from a point or spot light, aimed at the
 *    focus (the specular objects, where photons are useful, narrowed to those whose
 *    light can reach what the camera sees; or the whole scene, for shadow maps) with
 *    a depth range that holds the whole scene; a directional light's frustum
 *    narrowed to what the camera sees is the rectangle around that focus's outline
 *    (at most LightView::MaximumAspect times longer than wide), so its texels can be
 *    longer one way: each texel's measure below is its own area;
 * 2. a vtkCausticsGBuffer renders every role from the light (position, normal,
 *    material, depth: the first surface each light ray meets);
 * 3. a full-screen pass writes the flux each texel carries, from the light's
 *    irradiance times the texel's area (directional) or its intensity times the
 *    texel's solid angle and the spot falloff (point/spot), so that the sum over
 *    texels equals the light's power inside the frustum. Flux is written for every
 *    texel, hit or not (rgb: W; a: the texel's area in m^2 or solid angle in sr).
 * GL objects are created when a light first appears or the resolution changes.
 *
 * A Render() whose inputs are those of the buffers held keeps them and draws
 * nothing (ReuseUnchanged, on by default): a still light over a still scene pays
 * for its buffers once, whatever the camera does. The buffers are drawn again when
 * any of these changed since the buffers held were drawn:
 * - the window or the vtkCausticsSceneGeometry passed in;
 * - Resolution, Focus or ShadowMapsOnly;
 * - the meshes: their number and order, and per mesh its version (renewed by
 *   vtkCausticsSceneExtractor when its triangles or its actor's matrix change),
 *   material slot, role and material properties (the G-buffer stores albedo and IOR);
 * - the lights: their number, and per light its type, position, direction,
 *   emission and spot cone, and the view computed from them and the scene's bounds
 *   (moved by GridOffset);
 * - ReleaseGraphicsResources() was called.
 * Nothing else is read. The camera is read only through the views: with FOCUS_SEEN
 * a camera that moves what it sees of a specular sheet moves the photons' frustum
 * (caustics::PhotonFocusBounds); otherwise it is not read. A failed Render() keeps
 * nothing, so the next one draws.
 */
#ifndef vtkCausticsLightBuffers_h
#define vtkCausticsLightBuffers_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsSceneData.h" // For caustics::LightView

#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

class vtkCausticsGBuffer;
class vtkCausticsSceneGeometry;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsLightBuffers : public vtkObject
{
public:
  static vtkCausticsLightBuffers* New();
  vtkTypeMacro(vtkCausticsLightBuffers, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum FocusType
  {
    FOCUS_SPECULAR = 0, ///< every reflector and refractor
    FOCUS_SCENE = 1,    ///< every mesh (shadow maps)
    /** The specular surfaces whose light can reach what the camera sees
     * (caustics::PhotonFocusBounds): a camera zoomed in on a part of a large water
     * surface gets its photons there. FOCUS_SPECULAR where that cannot be told. */
    FOCUS_SEEN = 2
  };

  ///@{
  /** Texels per side of each light's buffers, in [1, 8192]. Default 512. */
  vtkSetClampMacro(Resolution, int, 1, 8192);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /** What the frusta are aimed at. Default FOCUS_SEEN. */
  vtkSetClampMacro(Focus, int, FOCUS_SPECULAR, FOCUS_SEEN);
  vtkGetMacro(Focus, int);
  ///@}

  ///@{
  /**
   * Shadow maps only: each light's G-buffer holds position, normal and depth, with
   * no albedo target (vtkCausticsGBuffer::Albedo off) and no flux (step 3 skipped;
   * GetFluxTexture() returns nullptr). The direct irradiance and the airlight read
   * nothing else, so the render pass's shadow maps skip, at the default 1024 texels,
   * 25 MB of textures that llvmpipe zeroes on allocation, and the flux pass.
   * Default off.
   */
  vtkSetMacro(ShadowMapsOnly, bool);
  vtkGetMacro(ShadowMapsOnly, bool);
  vtkBooleanMacro(ShadowMapsOnly, bool);
  ///@}
  ///@{
  /**
   * Keep the buffers of the last Render() when its inputs are unchanged (the list
   * in the class description). Off, every Render() draws every buffer, the lights'
   * G-buffers included (their own ReuseUnchanged follows this one). Default on.
   */
  vtkSetMacro(ReuseUnchanged, bool);
  vtkGetMacro(ReuseUnchanged, bool);
  vtkBooleanMacro(ReuseUnchanged, bool);
  ///@}

  ///@{
  /**
   * Moves every light's texel grid by (u, v) texels, each clamped to [-0.5, 0.5]
   * (caustics::OffsetLightView): the photons are then another regular set of each
   * light's flux. vtkCausticsRenderPass's ProgressiveFrames moves it every frame of a
   * still scene and averages the frames. A new offset draws the buffers again (the
   * views are part of what they depend on). Default (0, 0).
   */
  void SetGridOffset(double u, double v);
  const double* GetGridOffset() const { return this->GridOffset; }
  ///@}

  /** Whether the last Render() kept the buffers it already held (nothing changed). */
  bool GetLastRenderReused() const;

#ifndef __VTK_WRAP__
  /**
   * Renders the buffers of every light, or keeps those held (ReuseUnchanged).
   * Returns false on a GL/program failure.
   */
  bool Render(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const caustics::SceneData& scene);

  /** The frustum of light i, as used by the last Render(). */
  const caustics::LightView& GetView(int i) const;
#endif

  /** Lights rendered by the last Render(). */
  int GetNumberOfLights() const;
  /** Position, normal, albedo and depth seen from light i. */
  vtkCausticsGBuffer* GetGBuffer(int i);
  /** Flux per texel of light i (rgb: W, a: m^2 or sr); nullptr with ShadowMapsOnly on. */
  vtkTextureObject* GetFluxTexture(int i);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsLightBuffers();
  ~vtkCausticsLightBuffers() override;

  int Resolution = 512;
  int Focus = FOCUS_SEEN;
  bool ShadowMapsOnly = false;
  bool ReuseUnchanged = true;
  double GridOffset[2] = { 0.0, 0.0 };

private:
  vtkCausticsLightBuffers(const vtkCausticsLightBuffers&) = delete;
  void operator=(const vtkCausticsLightBuffers&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

#ifndef __VTK_WRAP__
  /** The frustum of every light for Focus (warns of a clamped one for photons). */
  std::vector<caustics::LightView> ComputeViews(const caustics::SceneData& scene);
#endif
};

#endif
