/**
 * @class   vtkCausticsPhotonBuffer
 * @brief   A light's photon buffer: where each emitted photon lands on a diffuse receiver.
 *
 * The first pass of caustic mapping (001_7c07a484f7a872bb.txt §2, Fig. 2), after
 * the shared vtkCausticsPhotonEmitter has made every light-buffer texel that meets
 * a reflector or a refractor into a photon (one per texel, N x N or N x 2N with
 * the Fresnel-reflected branch):
 * 1. RenderLayers: the refractors' nearest and farthest surfaces as the light sees
 *    them (two vtkCausticsGBuffer of refractors only, in the emitter's view, the
 *    second with KeepFarthest): the front and back faces the paper uses for two
 *    refractive interfaces;
 * 2. Trace, three compute passes: a sort over every texel counts the photons and
 *    lists those inside a refractor and those in air; one indirect dispatch per
 *    list then follows them (lists keep every SIMD lane busy: Mesa's llvmpipe pays
 *    for untaken branches);
 * 3. a photon inside a refractor finds its exit on the back faces (front faces if
 *    it heads back towards the light), loses Beer-Lambert absorption on the way,
 *    and refracts out with exact Fresnel; the part reflected back inside is not
 *    followed to the surfaces (its flux is counted; with a medium filling the
 *    refractors its stretches inside are appended for the volume caustics), total
 *    internal reflection continues inside up to MaximumInternalEvents interfaces.
 *    Where neither layer holds the exit (a concave refractor), the refractor is the
 *    slab between the two layers and the photon leaves it where the march finds it
 *    outside;
 * 4. in air, the photon finds the receiver it lands on in `receivers`, a G-buffer
 *    of the receivers alone as the caustic map's view sees them (the finest level
 *    of vtkCausticsCausticMap), so that caustics can land where the specular
 *    object itself hides the floor from the light; the search is clipped to the
 *    receivers' bounding box;
 * 5. each layer crossing: plane steps (the ray meets the plane of the surface the
 *    layer shows where the estimate projects, until the estimate stops moving:
 *    exact in one step on planar receivers), else a march of MarchSteps samples
 *    that brackets the first change of side, bisection and a last plane step.
 * Output: GetLanded(), the landed photons in the photon record layout of
 * vtkCausticsPhotonGrid.h (position, w = path length from the light d_i, > 0 for a
 * landed photon; receiver normal, w = |N.D_i|; flux, a = the texel's measure
 * omega_i, as Eq. 2 of §3.3 needs).
 * GPU counters (photons and flux in, landed, lost inside, escaped, internally
 * reflected, absorbed) are kept every frame and read only on request
 * (GetStatistics, which stalls). MaximumInternalEvents and MarchSteps are members
 * of caustics::CausticMapSettings, which Render() and Trace() take. Limits:
 * photons are not occluded by specular objects after their last interface, a
 * refractor is one slab between its nearest and farthest surfaces seen from the
 * light (nested or overlapping refractors need
 * layered depth images), and only receivers the caustic map's view sees can be hit.
 */
#ifndef vtkCausticsPhotonBuffer_h
#define vtkCausticsPhotonBuffer_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include "vtkCausticsPhotonGrid.h" // For caustics::PhotonStatistics
#include "vtkNew.h"                // For vtkNew members

#include <cstddef> // For std::size_t
#include <memory>  // For std::unique_ptr

class vtkCausticsDistanceImpostors;
class vtkCausticsGBuffer;
class vtkCausticsSpecularHierarchy;
class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace caustics
{
struct CausticMapSettings;
struct LightView;
struct PhotonGrid;
struct PhotonRecords;
struct SceneData;
namespace gl
{
class MediumBuffer;
class StorageBuffer;
class VolumeSegmentList;
}
}

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsPhotonBuffer : public vtkObject
{
public:
  static vtkCausticsPhotonBuffer* New();
  vtkTypeMacro(vtkCausticsPhotonBuffer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Renders the refractor layers in `photonView` (the view the grid's texels come
   * from) and traces the photons of `grid` (emitted for its light of `scene`) to the
   * receivers of `receivers`, a receiver-only G-buffer seen through `mapView`, with
   * the settings' MaximumInternalEvents and MarchSteps. The geometry's material
   * table must be current. Returns false if a program failed.
   */
  bool Render(vtkOpenGLRenderWindow* renWin, const caustics::CausticMapSettings& settings,
    vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene,
    const caustics::PhotonGrid& grid, const caustics::LightView& photonView,
    const caustics::LightView& mapView, vtkCausticsGBuffer* receivers,
    const caustics::gl::MediumBuffer* mediumGrid = nullptr);

  ///@{
  /**
   * Render() in its two steps: the refractor layers (N x N), then the trace. With
   * `volumeSegments` on (a scattering medium), the trace appends every photon's straight
   * pieces in air after its first specular event into it (reset here), for the
   * line-based volume caustics: texels x (MaximumReflections + 1) at most.
   */
  bool RenderLayers(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const caustics::LightView& photonView, const caustics::PhotonGrid& grid);
  bool Trace(vtkOpenGLRenderWindow* renWin, const caustics::CausticMapSettings& settings,
    vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene,
    const caustics::PhotonGrid& grid, const caustics::LightView& photonView,
    const caustics::LightView& mapView, vtkCausticsGBuffer* receivers,
    const caustics::gl::MediumBuffer* mediumGrid = nullptr,
    caustics::gl::VolumeSegmentList* volumeSegments = nullptr);
  ///@}

  /**
   * A second receiver layer of the same view and size as `receivers`: the receivers
   * hidden from the light by nearer ones (vtkCausticsCausticMap's hidden receivers).
   * A photon in air that finds no receiver in the first layer is searched in it; one
   * that lands there keeps the record layout with its measure (flux.a) negated, so
   * that the hidden receivers' map splats it. Null (the default): first layer only.
   * Not owned; it must stay alive through Trace().
   */
  void SetHiddenReceivers(vtkCausticsGBuffer* hidden) { this->HiddenReceivers = hidden; }

  /**
   * Glass traced as triangles inside the refractors (vtkCausticsSpecularHierarchy, as
   * the camera view traces it): a photon inside leaves through the triangle it meets,
   * with that face telling the side, instead of through the light's nearest and
   * farthest refractor layers (which a concave refractor does not fit). Null (the
   * default): the layers. Not owned; it must stay alive through Trace().
   */
  void SetTracedSpecularGeometry(vtkCausticsSpecularHierarchy* traced)
  {
    this->TracedSpecular = traced;
  }

  /**
   * The distance impostors whose caustic store takes the photons that no receiver
   * layer lands (a ceiling above the light, a wall beyond the caustic map's frame):
   * such a photon is searched in their environment map, and one that meets a receiver
   * there, lit from the side it arrives on, adds its flux to the store
   * (ImpostorDepositCaustic) instead of escaping, counted as Stored; the final
   * render then reads the store where the caustic map does not see
   * (vtkCausticsCausticMap::ApplyStore, drawn only when the store took more than
   * 10^-3 of the flux that landed). The store must be open for the frame
   * (vtkCausticsDistanceImpostors::OpenCaustic()) and hold the photons' light alone.
   * Null (the default): such photons escape. Not owned; it must stay alive through
   * Trace().
   */
  void SetCausticStore(vtkCausticsDistanceImpostors* store) { this->CausticStore = store; }

  /**
   * GPU counters of the last Render(); flux in W summed over RGB. Here LostInside
   * counts photons whose exit was not found within MaximumInternalEvents, Escaped
   * those that left the caustic map's view or hit a receiver's back.
   */
  using Statistics = caustics::PhotonStatistics;

  /** Reads the counters of the last Render() (stalls the GPU). False if none. */
  bool GetStatistics(Statistics& statistics);
#endif

#ifndef __VTK_WRAP__
  /**
   * The photons of the last Render() that landed on a receiver, in the photon record
   * layout of vtkCausticsPhotonGrid.h (one texel per photon of the grid; position.w
   * > 0 marks a landed photon; flux.a < 0 one landed on a hidden receiver, whose
   * measure is -flux.a).
   */
  caustics::PhotonRecords GetLanded() const;

  /**
   * The trace's counters on the GPU, and the byte offsets in it of the hidden
   * receivers' final-render draw arguments ({ 3, 1 if a photon landed on a hidden
   * receiver else 0, 0, 0 }, for vtkCausticsCausticMap::Apply) and of the caustic
   * store's ({ 3, 1 if the store took more than 10^-3 of the landed flux else 0,
   * 0, 0 }, for vtkCausticsCausticMap::ApplyStore).
   */
  const caustics::gl::StorageBuffer& GetStatisticsBuffer() const;
  static std::size_t GetHiddenDrawOffset();
  static std::size_t GetStoreDrawOffset();
#endif

  ///@{
  /** The refractor layers of the last Render(), front and back faces. */
  vtkCausticsGBuffer* GetFrontLayer()
  {
    return this->FrontLayer;
  }
  vtkCausticsGBuffer* GetBackLayer()
  {
    return this->BackLayer;
  }
  ///@}

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsPhotonBuffer();
  ~vtkCausticsPhotonBuffer() override;

  double FluxUnit = 1.0; // W per unit of the GPU flux counters, set by Trace()
  vtkNew<vtkCausticsGBuffer> FrontLayer;
  vtkNew<vtkCausticsGBuffer> BackLayer;
  vtkNew<vtkCausticsGBuffer> ReflectorLayer; // mirrors as the caustic map's view sees them
  vtkCausticsGBuffer* HiddenReceivers = nullptr; // not owned (SetHiddenReceivers)
  vtkCausticsSpecularHierarchy* TracedSpecular = nullptr; // not owned (SetTracedSpecularGeometry)
  vtkCausticsDistanceImpostors* CausticStore = nullptr;   // not owned (SetCausticStore)
  vtkNew<vtkCausticsShaderProgram> SortProgram;
  vtkNew<vtkCausticsShaderProgram> InsideProgram;
  vtkNew<vtkCausticsShaderProgram> AirProgram;
  vtkNew<vtkCausticsShaderProgram> ArgumentsProgram;
  vtkNew<vtkCausticsShaderProgram> StoreDrawProgram; // PHASE 3: the store's draw, or not

private:
  vtkCausticsPhotonBuffer(const vtkCausticsPhotonBuffer&) = delete;
  void operator=(const vtkCausticsPhotonBuffer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

public:
#ifndef __VTK_WRAP__
  struct TraceUniforms; // what every phase of one trace reads (the .cxx defines it)
#endif

private:
  // Trace() in steps.
  std::size_t AllocateOutputs(vtkOpenGLRenderWindow* renWin, int width, int height);
  void DescribeTrace(const caustics::CausticMapSettings& settings, const caustics::SceneData& scene,
    const caustics::PhotonGrid& grid, const caustics::LightView& photonView,
    const caustics::LightView& mapView, vtkCausticsGBuffer* receivers, TraceUniforms& trace);
  void BindTraceOutputs(vtkCausticsSceneGeometry* geometry);
};

#endif
