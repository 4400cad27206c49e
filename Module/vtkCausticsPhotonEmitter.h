/**
 * @class   vtkCausticsPhotonEmitter
 * @brief   Photons after their first specular interaction, one per light-buffer texel.
 *
 * The shared first stage of the photon techniques (000_54cf099eeccf42d9.txt §2,
 * 001_7c07a484f7a872bb.txt §2). For one light of a vtkCausticsLightBuffers:
 * 1. each texel whose first hit (from the light) is a reflector or a refractor
 *    becomes a photon carrying the texel's flux (W: the light's power through
 *    that texel, so photon fluxes sum to the power reaching specular surfaces);
 * 2. at that hit the photon is reflected (conductor Fresnel with complex IOR) or
 *    refracted (exact dielectric Fresnel, total internal reflection); with
 *    SplitFresnel on, a refractor's reflected part becomes a second photon, so
 *    no energy is dropped;
 * 3. the result is three RGBA32F textures of width N and height N (or 2N when
 *    split: rows N..2N-1 hold the reflected branch), N = the light-buffer
 *    resolution, so photons stay addressable by texel (hierarchical traversal,
 *    texture-row line tracing):
 *    - Position: xyz where the photon leaves the surface, w = state
 *      (0 none, 1 travelling in air, 2 inside a refractor);
 *    - Direction: xyz unit direction, w = the texel's measure (m^2 for
 *      directional lights, sr for point/spot lights);
 *    - Flux: rgb W after the Fresnel weight, a = specular events so far (1);
 * 4. GetGrid(): the caustics::PhotonGrid value the later stages take (size,
 *    branches, light, flux bound, these textures).
 */
#ifndef vtkCausticsPhotonEmitter_h
#define vtkCausticsPhotonEmitter_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsPhotonGrid.h" // For caustics::PhotonGrid
#include "vtkNew.h"                // For vtkNew members

class vtkCausticsLightBuffers;
class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct SceneData;
namespace gl
{
class FullScreenTriangle;
class PhotonPlanes;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsPhotonEmitter : public vtkObject
{
public:
  static vtkCausticsPhotonEmitter* New();
  vtkTypeMacro(vtkCausticsPhotonEmitter, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Emit a refractor's Fresnel-reflected part as a second photon. Default on. */
  vtkSetMacro(SplitFresnel, bool);
  vtkGetMacro(SplitFresnel, bool);
  vtkBooleanMacro(SplitFresnel, bool);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Emits the photons of light `light` of `lights` (rendered this frame for `scene`).
   * The scene geometry's material table must be current. Returns false on failure.
   */
  bool Emit(vtkOpenGLRenderWindow* renWin, vtkCausticsLightBuffers* lights, int light,
    vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene);
#endif

  ///@{
  /** Outputs of the last Emit(): the planes of GetGrid().Emitted (null before). */
  vtkTextureObject* GetPositionTexture()
  {
    return this->Grid.Emitted.Position;
  }
  vtkTextureObject* GetDirectionTexture()
  {
    return this->Grid.Emitted.Direction;
  }
  vtkTextureObject* GetFluxTexture()
  {
    return this->Grid.Emitted.Flux;
  }
  ///@}

#ifndef __VTK_WRAP__
  /** The photons of the last Emit(), for the later stages (empty before). */
  const caustics::PhotonGrid& GetGrid() const
  {
    return this->Grid;
  }
#endif

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsPhotonEmitter();
  ~vtkCausticsPhotonEmitter() override;

  bool SplitFresnel = true;
  caustics::PhotonGrid Grid;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  vtkNew<vtkCausticsShaderProgram> Program;

private:
  vtkCausticsPhotonEmitter(const vtkCausticsPhotonEmitter&) = delete;
  void operator=(const vtkCausticsPhotonEmitter&) = delete;

  /** Fills Grid for the photons of light `light` just emitted. */
  void DescribeGrid(
    const caustics::Light& source, const caustics::LightView& view, int light, int resolution);

  caustics::gl::FullScreenTriangle* Triangle;
  caustics::gl::PhotonPlanes* Planes; // what Grid.Emitted shows
};

#endif
