/**
 * @class   vtkCausticsCausticMap
 * @brief   A light's multi-resolution caustic map: splatted, then projected onto the scene.
 *
 * The caustic map of 001_7c07a484f7a872bb.txt (§2 and §3.3, Fig. 6): a light-space
 * image of caustic irradiance, projected onto the receivers like a shadow map.
 * 1. RenderReceivers: for each of NumberOfLevels levels (level j has
 *    CausticMapResolution / 2^j texels per side, both from the technique's
 *    caustics::CausticMapSettings), a vtkCausticsGBuffer of the receivers alone seen from
 *    the light (caustics::ComputeReceiverMapView: aimed at what the camera sees,
 *    turned towards receivers the light grazes):
 *    where splats land, and the depth test of the final render. Specular actors
 *    are left out so that caustics can land where they hide the floor.
 * 2. Splat: for each level, one glDrawArraysIndirect of point sprites over the
 *    level's splat list made by vtkCausticsPhotonBufferHierarchy (count written on
 *    the GPU); each splat fetches its photon from the photon buffer by index and is
 *    drawn with the shared receiver-oriented, energy-normalized kernel of
 *    vtkCausticsPhotonSplatter's fragment shader, so each level holds irradiance in
 *    W/m^2 and every splat deposits exactly its flux.
 * 3. Apply: a full-screen pass over the camera's G-buffer adds, at every receiver
 *    pixel the finest level sees, the sum over the levels of their bilinear
 *    irradiance (taps that show another surface are left out). Eq. 3's (1/4)^i
 *    weights renormalize energy counted per texel; per unit area, as stored here,
 *    they are already applied, and the sum of the levels is the irradiance.
 * A second map of the same view holds the receivers hidden from the light by nearer
 * receivers (RenderReceivers with `front`: each level peeled behind the front map's,
 * vtkCausticsGBuffer::SetPeelBehind), e.g. the floor along a pool's sunlit wall that
 * refraction bends light onto. Its Splat() draws only the photons that landed there
 * (`hiddenOnly`); its Apply() adds them where the camera sees those receivers. Every
 * surface point is in one map's receivers, so a kernel split across the two maps
 * deposits its flux once. The receivers neither map sees (a ceiling above the light, a
 * wall beyond the map's frame) take the photons that landed there from the distance
 * impostors' caustic store (ApplyStore).
 * Textures are allocated when the resolution changes, never per frame.
 */
#ifndef vtkCausticsCausticMap_h
#define vtkCausticsCausticMap_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkNew.h"          // For vtkNew members
#include "vtkSmartPointer.h" // For the per-level objects

#include <memory> // For std::unique_ptr

class vtkCausticsDistanceImpostors;
class vtkCausticsGBuffer;
class vtkCausticsPhotonBufferHierarchy;
class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLState;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct Camera;
struct CausticMapSettings;
struct LightView;
struct PhotonGrid;
struct PhotonRecords;
namespace gl
{
class FullScreenTriangle;
class StorageBuffer;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsCausticMap : public vtkObject
{
public:
  static vtkCausticsCausticMap* New();
  vtkTypeMacro(vtkCausticsCausticMap, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Texels per side of the finest level and levels of the pyramid (4 for the
   * multi-resolution map), as the last RenderReceivers() took them from its settings.
   */
  vtkGetMacro(Resolution, int);
  vtkGetMacro(NumberOfLevels, int);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Renders the receivers of every level (the settings' CausticMapResolution and
   * NumberOfLevels()) as `view` sees them; with `front` (a map whose receivers were
   * rendered with the same settings and view), the receivers behind `front`'s that
   * face the light: the hidden receivers' map.
   */
  bool RenderReceivers(vtkOpenGLRenderWindow* renWin, const caustics::CausticMapSettings& settings,
    vtkCausticsSceneGeometry* geometry, const caustics::LightView& view,
    vtkCausticsCausticMap* front = nullptr);

  /**
   * Clears the levels and draws the splat lists of `hierarchy` (gathered from the
   * photons of `grid` that landed (`landed`, in the photon record layout of
   * vtkCausticsPhotonGrid.h)) into them, each kernel's radius within
   * the settings' MinimumSplatRadius and MaximumSplatRadius. Clusters get the
   * settings' ClusterRadius(), and no less than MinimumCameraSplatRadius pixel
   * footprints of `camera` (may be null: no floor). `hiddenOnly`: only the photons
   * the trace marked as landed on a hidden receiver (a negative measure, see
   * vtkCausticsPhotonBuffer), for the hidden receivers' map. `otherLayer` (may be
   * null): the other receiver layer of the same view (the hidden receivers' map for
   * the map, the map for the hidden receivers'), whose receivers were rendered. Each
   * kernel deposits its whole flux on the receivers of its plane that either layer
   * shows, so a kernel cut by its plane's end, or by the map's frame, loses nothing.
   * False if a program failed.
   */
  bool Splat(vtkOpenGLRenderWindow* renWin, const caustics::CausticMapSettings& settings,
    const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
    vtkCausticsPhotonBufferHierarchy* hierarchy, const caustics::Camera* camera,
    vtkCausticsCausticMap* otherLayer = nullptr, bool hiddenOnly = false);

  /**
   * Adds the map's caustic irradiance at the receivers of `camera` (a G-buffer of
   * the opaque roles, drawn with `view`) into the bound framebuffer, additively.
   * The kernels are at least a pixel footprint wide (MinimumCameraSplatRadius) and
   * each pixel takes them at its centre. With
   * `front` (the hidden receivers' map, rendered behind `front`), only the pixels
   * `front`'s finest level does not see. With `drawArguments`, the draw's arguments
   * are read there on the GPU at `drawOffset` (vtkCausticsPhotonBuffer's hidden
   * draw: nothing is drawn when no photon landed on a hidden receiver). False on
   * failure.
   */
  bool Apply(vtkOpenGLRenderWindow* renWin, vtkCausticsGBuffer* camera,
    const caustics::Camera& view, vtkCausticsCausticMap* front = nullptr,
    const caustics::gl::StorageBuffer* drawArguments = nullptr, std::size_t drawOffset = 0);

  /**
   * Allocates the levels' irradiance and clears it, once per size, where nothing is
   * splatted into them (caustic triangles go to the camera's view) but ApplyStore()
   * still tests what the map sees through them (it reads the receivers alone).
   */
  void ClearIrradiance(vtkOpenGLRenderWindow* renWin);

  /**
   * Adds, at the receivers of `camera` that neither this map (as Apply() tests it)
   * nor `hidden` (its hidden receivers' map, or null) sees, the caustic irradiance of
   * `store`'s caustic store, where a texel of its environment maps shows the pixel's
   * point, read over at least the pixel's footprint (ImpostorCausticIrradiance): the
   * light of the photons the trace handed to the store because no receiver layer of
   * this view landed them (vtkCausticsPhotonBuffer::SetCausticStore: a ceiling above
   * the light, a wall beyond the map's frame). Drawn as Apply() with
   * `drawArguments` (vtkCausticsPhotonBuffer's store draw: nothing when the store took
   * no photon). False on failure.
   */
  bool ApplyStore(vtkOpenGLRenderWindow* renWin, vtkCausticsGBuffer* camera,
    const caustics::Camera& view, vtkCausticsCausticMap* hidden,
    vtkCausticsDistanceImpostors* store, const caustics::gl::StorageBuffer& drawArguments,
    std::size_t drawOffset);
#endif

  /** Irradiance (W/m^2, RGBA32F) of level j after Splat(). */
  vtkTextureObject* GetIrradianceTexture(int j);
  /** Receivers of level j as the map's view sees them. */
  vtkCausticsGBuffer* GetReceivers(int j);
  /** Texels per side of level j. */
  int GetLevelResolution(int j) const;

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsCausticMap();
  ~vtkCausticsCausticMap() override;

  int Resolution = 512;
  int NumberOfLevels = 4;
  // The splat kernel's receiver tests, as vtkCausticsPhotonSplatter's defaults:
  // within half a radius of the photon's tangent plane, normals within ~37 degrees.
  double PlaneTolerance = 0.5;
  double NormalTolerance = 0.8;

  vtkSmartPointer<vtkCausticsGBuffer> Receivers[4];
  vtkSmartPointer<vtkTextureObject> Irradiance[4];
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffers[4];
  vtkNew<vtkCausticsShaderProgram> SplatProgram;
  vtkNew<vtkCausticsShaderProgram> ApplyProgram;
  vtkNew<vtkCausticsShaderProgram> StoreProgram; // ApplyStore(): the same pass, CAUSTICS_STORE
  unsigned int VertexArray = 0;

private:
  vtkCausticsCausticMap(const vtkCausticsCausticMap&) = delete;
  void operator=(const vtkCausticsCausticMap&) = delete;

  // Splat() in steps.
  void ClearLevels(vtkOpenGLRenderWindow* renWin);
  void SetSplatUniforms(vtkCausticsShaderProgram* program,
    const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
    vtkCausticsPhotonBufferHierarchy* hierarchy, const caustics::Camera* camera);
  void DrawLevels(vtkOpenGLState* state, vtkCausticsShaderProgram* program,
    vtkCausticsPhotonBufferHierarchy* hierarchy, vtkCausticsCausticMap* otherLayer);
  // Apply() and ApplyStore(): `program` over the camera's receivers, additively.
  bool DrawFinal(vtkOpenGLRenderWindow* renWin, vtkCausticsShaderProgram* program,
    vtkCausticsGBuffer* camera, const caustics::Camera& view, vtkCausticsCausticMap* front,
    vtkCausticsDistanceImpostors* store, const caustics::gl::StorageBuffer* drawArguments,
    std::size_t drawOffset);

  struct Internals;
  std::unique_ptr<Internals> Internal; // the view of the last RenderReceivers()
  caustics::gl::FullScreenTriangle* Triangle;
};

#endif
