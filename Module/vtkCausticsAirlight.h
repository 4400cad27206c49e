/**
 * @class   vtkCausticsAirlight
 * @brief   Airlight and volume shadows: the medium's single scattering of the direct light.
 *
 * In a participating medium the light's own beam is visible: each point x along a
 * viewing ray scatters sigma_s(x) p(theta) of the radiance arriving straight from the
 * light towards the camera. This is the airlight with its volume shadows, term (A) of
 * 003_653219b45420e98f.txt §3 (Fig. 2), composed with the volume caustic (B) and the
 * surfaces (C) by addition (§5.3); the volume caustic is a technique's
 * (RenderVolumeRadiance), this stage is shared by every technique. One compute pass per
 * light and per pixel (vtkCausticsAirlightCS.glsl), full resolution:
 * 1. the camera ray from the near plane to the first visible surface (the camera
 *    G-buffers: a refractor ends it too, as the reference's camera rays, since what lies
 *    behind glass is seen refracted, in the technique's colour), clipped to the
 *    medium's box, is cut into Steps strata with one jittered sample each
 *    (deterministic per pixel: no banding, no flicker);
 * 2. at each sample: sigma_s (x the density of a grid), the Henyey-Greenstein phase,
 *    the light's irradiance (directional) or intensity / r^2 with the spot cone, its
 *    visibility in the light's shadow map (the direct irradiance's, aimed at the whole
 *    scene: every surface blocks, glass too, whose light is the volume caustic, exactly
 *    as the reference's shadow rays), and the transmittance towards the light: closed
 *    form in a homogeneous medium, through a density grid a march of at most LightSteps
 *    steps (tiles crossed in one step, CausticsMediumOpticalDepthSteps);
 * 3. the transmittance towards the camera: closed form; with a grid one fetch of the
 *    camera optical-depth volume (vtkCausticsCameraOpticalDepth), or, with that volume
 *    disabled, the exact march along the ray accumulated stratum by stratum; each
 *    stratum's own attenuation is integrated in closed form, so an opaque medium gives
 *    sigma_s / sigma_t of the in-scattered light, never a spike;
 * 4. the radiance, W/(m^2 sr), is stored (first light) or added into the volume layer
 *    (VolumeRadiance), which the composite adds to the image (pi x, VTK's scale).
 * Measured against the reference's AirlightRadiance in TestAirlight (docs/airlight.md).
 * GL objects: one program, compiled once per define set; nothing is allocated per frame.
 */
#ifndef vtkCausticsAirlight_h
#define vtkCausticsAirlight_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkCausticsCameraOpticalDepth;
class vtkCausticsLightBuffers;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;
namespace caustics
{
struct SceneData;
namespace gl
{
class MediumBuffer;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsAirlight : public vtkObject
{
public:
  static vtkCausticsAirlight* New();
  vtkTypeMacro(vtkCausticsAirlight, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Off: no airlight (the volume layer holds the technique's volume caustic only). Default on. */
  vtkSetMacro(Enabled, bool);
  vtkGetMacro(Enabled, bool);
  vtkBooleanMacro(Enabled, bool);
  ///@}

  ///@{
  /** Strata (samples) along each camera ray's part in the medium, in [1, 1024]. Default 64. */
  vtkSetClampMacro(Steps, int, 1, 1024);
  vtkGetMacro(Steps, int);
  ///@}

  ///@{
  /**
   * Most steps of the march towards the light through a density grid, per sample, in
   * [1, 256] (empty tiles take one step). A homogeneous medium needs none. Default 16.
   */
  vtkSetClampMacro(LightSteps, int, 1, 256);
  vtkGetMacro(LightSteps, int);
  ///@}

#ifndef __VTK_WRAP__
  /** What a frame hands the stage (all of the frame, none owned). */
  struct Inputs
  {
    vtkOpenGLRenderWindow* Window = nullptr;
    int Width = 0; ///< the viewport's pixels
    int Height = 0;
    const caustics::SceneData* Scene = nullptr;
    const caustics::gl::MediumBuffer* Grid = nullptr;            ///< the density grid on the GPU
    vtkCausticsCameraOpticalDepth* CameraOpticalDepth = nullptr; ///< used when valid
    vtkTextureObject* SurfacePositions = nullptr;   ///< camera G-buffer of opaque surfaces
    vtkTextureObject* RefractorPositions = nullptr; ///< camera G-buffer of refractors
    vtkCausticsLightBuffers* Shadows = nullptr;     ///< shadow maps aimed at the scene
    int ShadowMapResolution = 1;
  };

  /** Whether the scene's medium scatters anything this stage would draw (Enabled too). */
  bool IsNeeded(const caustics::SceneData& scene) const;

  /**
   * Writes the airlight (RGBA32F, W/(m^2 sr), Width x Height) into `target`, adding it
   * to what `target` holds when `accumulate`. Returns false (target untouched) when not
   * needed, no light has power and a view, or the program fails.
   */
  bool Render(const Inputs& in, vtkTextureObject* target, bool accumulate);
#endif

  /** Frees the program. */
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkCausticsAirlight();
  ~vtkCausticsAirlight() override;

  bool Enabled = true;
  int Steps = 64;
  int LightSteps = 16;

private:
  vtkCausticsAirlight(const vtkCausticsAirlight&) = delete;
  void operator=(const vtkCausticsAirlight&) = delete;

#ifndef __VTK_WRAP__
  void DrawLight(const Inputs& in, int light); // one light's dispatch, program bound
#endif

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
