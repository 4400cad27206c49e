/**
 * @class   vtkCausticsDistanceImpostors
 * @brief   Distance impostors: cube maps of what surrounds the specular objects.
 *
 * 004_4da4b323b51d1415.txt §3 (environment maps with distance impostors) and §4
 * (refractor maps). One responsibility: the maps. Three cube maps, each from a
 * reference point, each face a vtkCausticsGBuffer of the shared scene geometry
 * rendered through a 90-degree frustum (world position + material index, normal
 * as modelled + role):
 * 1. REFRACTOR_ENVIRONMENT: from the centre of the refractors' bounding box, the
 *    receivers and reflectors (everything but the refractors);
 * 2. REFRACTOR_SURFACE: from the same point, the refractors themselves, nearest
 *    surface per direction: the refractor map of §4 (exit point and normal);
 * 3. REFLECTOR_ENVIRONMENT: from the centre of the reflectors' bounding box, the
 *    receivers and refractors (everything but the reflectors);
 * 4. REFLECTOR_SURFACE: from the same point, the reflectors themselves, nearest
 *    surface per direction, so that a concave mirror (a ring wall, a cup) sees
 *    itself: a ray that leaves a mirror searches this map and the environment map
 *    and takes the nearer hit; a hit here reflects again, at most
 *    ReflectorBounces times in a row. Made only where the reflector group can see
 *    itself from its reference point: the generalized winding number of the
 *    reflector meshes there is under 1/2 (the point is outside the mirror solid, or
 *    an open mirror does not wrap it: the centre of a ring or a cup, not of a
 *    mirror ball) and the group's box is not flat (its thinnest side over 1e-3 of
 *    its diagonal: a flat mirror cannot see itself).
 * Then each receiver texel's radiance for hits the camera does not see: albedo x
 *    the direct irradiance of the scene's first 8 lights (physical falloff;
 *    glsl/vtkCausticsImpostorShadeCS.glsl), with the shadows of the lights' shadow
 *    maps when Update() is given them (specular objects block the direct light too),
 *    plus, where a photon technique filled the caustic store this frame
 *    (StoreCaustic()), albedo x the caustic irradiance (and, without shadow maps,
 *    less the direct irradiance the specular objects block, which the store then
 *    takes off itself). Hits the camera sees take the camera's colour (caustics and
 *    shadows included) instead.
 * A map whose role group is empty is not made. The distance of a texel is
 * |position - reference point|, computed in the lookup (so the maps hold exact
 * world positions, not a depth); the shaders' Hit() search
 * (glsl/vtkCausticsImpostorCommon.glsl) is a linear march of LinearSteps samples
 * followed by SecantSteps steps of false position, as §2-3.
 *
 * Invalidation: the maps are rendered again only when a mesh's version, its
 * material index or role, a light, an albedo or Resolution change
 * (GetMapRenders() counts the renders); their radiance is shaded again, without
 * rendering them, when the shadow maps given to Update() were drawn again or
 * another (or none) is given. The other material parameters (IOR,
 * metal n and k, absorption) do not invalidate them: the shaders read the
 * material table live.
 *
 * Limits: maps are per role group, not per object, so a refractor does not see
 * another refractor through the environment map, and a mirror sees the mirrors
 * only through REFLECTOR_SURFACE, which holds the mirror surfaces nearest to the
 * reference point (the screen-space march sees the others, with the BOTH
 * camera-view method);
 * a reference point outside a non-convex object (a ring) still gives a map, but
 * surfaces hidden from that point are missing from it (the paper's "view
 * dependent occlusions").
 */
#ifndef vtkCausticsDistanceImpostors_h
#define vtkCausticsDistanceImpostors_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkCausticsLightBuffers;
class vtkCausticsSceneGeometry;
class vtkCausticsShaderProgram;
class vtkCausticsTimings;
class vtkOpenGLRenderWindow;
class vtkWindow;
#ifndef __VTK_WRAP__
namespace caustics
{
struct SceneData;
struct PhotonRecords;
namespace ssp
{
class TextureUnits;
}
}
#endif

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsDistanceImpostors : public vtkObject
{
public:
  static vtkCausticsDistanceImpostors* New();
  vtkTypeMacro(vtkCausticsDistanceImpostors, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The maps, in the order of their layers (6 faces each). */
  enum Map
  {
    REFRACTOR_ENVIRONMENT = 0,
    REFRACTOR_SURFACE = 1,
    REFLECTOR_ENVIRONMENT = 2,
    REFLECTOR_SURFACE = 3,
    NUMBER_OF_MAPS = 4
  };

  /**
   * Timings to report Update()'s steps to ("<stagePrefix>faces", "<stagePrefix>shading"
   * and "<stagePrefix>caustic cells"), or nullptr. Not owned.
   */
  void SetTimings(vtkCausticsTimings* timings, const char* stagePrefix);

  ///@{
  /** Texels along a cube face's edge, in [16, 2048]. Default 256. */
  vtkSetClampMacro(Resolution, int, 16, 2048);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /**
   * The Hit() search: samples of the linear march along a ray, in [1, 256]
   * (default 32), then steps of false position between the last sample before the
   * surface and the first beyond it, in [0, 32] (default 8).
   */
  vtkSetClampMacro(LinearSteps, int, 1, 256);
  vtkGetMacro(LinearSteps, int);
  vtkSetClampMacro(SecantSteps, int, 0, 32);
  vtkGetMacro(SecantSteps, int);
  ///@}

  ///@{
  /**
   * How many times in a row a ray that leaves a mirror may meet the mirrors again
   * through the REFLECTOR_SURFACE map, in [0, 16] (default 8, the photon pass's
   * default MaximumEvents; the ring's caustic reaches relative L2 9.8 % with 8,
   * 10.0 % with 4, 12.3 % with 1, 21.3 % with 0). Past it the ray searches the
   * environment map alone (the mirrors are then transparent to it); 0: mirrors never
   * see themselves. The photon trace's and the camera view's MaximumEvents bound
   * the whole path besides.
   */
  vtkSetClampMacro(ReflectorBounces, int, 0, 16);
  vtkGetMacro(ReflectorBounces, int);
  ///@}

  ///@{
  /**
   * The caustic store's read: the caustic irradiance at a texel is the stored flux
   * over the area of the smallest square of texels around it (radius 0 to
   * CausticRadius, counting only those that show the same surface) that holds
   * CausticSamples deposits (photons or shadow samples) or more: an adaptive density
   * estimate, sharp at a focus, smooth where the light is spread (one texel alone
   * holds about one photon there). CausticRadius in [0, 8], default 3; CausticSamples
   * in [1, 1024], default 8.
   *
   * Where even the widest window holds fewer, the light is spread thin (a wide water
   * sheet: a few thousand photons on a floor the map shows with 65 536 texels), and
   * photons and shadow samples, two lattices aliasing with the texels, would leave
   * their difference to that noise. The read then takes the store's coarse level,
   * cells of 8 x 8 texels summed as they are deposited: the 3 x 3 cells around the
   * texel, or the 5 x 5 where those hold fewer than CausticCoarseSamples deposits (in
   * [1, 4096], default 64: about 12 % noise where the light is that thin).
   */
  vtkSetClampMacro(CausticRadius, int, 0, 8);
  vtkGetMacro(CausticRadius, int);
  vtkSetClampMacro(CausticSamples, int, 1, 1024);
  vtkGetMacro(CausticSamples, int);
  vtkSetClampMacro(CausticCoarseSamples, int, 1, 4096);
  vtkGetMacro(CausticCoarseSamples, int);
  ///@}

  /**
   * The generalized winding number of the triangles of `meshes` (xyz per vertex,
   * three indices per triangle) at `point`: the sum of their signed solid angles
   * over 4 pi. 1 inside a closed mesh with outward normals, 0 outside, between
   * for open meshes. Exposed for tests.
   */
#ifndef __VTK_WRAP__
  static double WindingNumber(const caustics::SceneData& scene, int role, const double point[3]);
#endif

  /** How many times the maps were rendered (once per change, see above). */
  vtkGetMacro(MapRenders, int);

#ifndef __VTK_WRAP__
  /**
   * Renders the maps if the scene changed since the last call (see above).
   * `shadowMaps`: the lights' shadow maps of this frame (vtkCausticsLightBuffers
   * aimed at the scene, already rendered), whose shadows the maps' radiance takes;
   * null: unshadowed radiance. Returns false if a map could not be made (GL failure).
   */
  bool Update(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const caustics::SceneData& scene, vtkCausticsLightBuffers* shadowMaps = nullptr);

  /**
   * Whether the maps' radiance holds the specular objects' shadows (the last Update()
   * had shadow maps): the caustic store must then hold the photons' light alone
   * (StoreCaustic() with `shadow` false).
   */
  bool GetRadianceShadowed() const;

  /**
   * Sets the uniforms of glsl/vtkCausticsImpostorCommon.glsl on a bound program.
   * Without maps (never updated, or released) every map reads as absent; the
   * samplers are then bound to `fallbackArray`, a 2D array texture unit the
   * program already uses (GL refuses two sampler types on one unit).
   */
  void SetUniforms(vtkCausticsShaderProgram* program, caustics::ssp::TextureUnits& units);
  static void SetAbsentUniforms(vtkCausticsShaderProgram* program, int fallbackArrayUnit);

  /**
   * The caustic store: per texel of the environment maps, the caustic flux that
   * landed on the receiver the texel shows, in fixed point (integer atomics: GPUs
   * without float atomics; W per count set by the frame's first StoreCaustic(), per
   * channel; R32I, layer 18 channel + 6 map + face, then the deposits per texel in
   * layer 54 + 6 map + face), so that a camera-view hit the
   * camera does not see (in a mirror, through glass, outside the frame) is shaded
   * with albedo x (its caustic irradiance) besides the map's direct light
   * (ImpostorCausticIrradiance() in glsl/vtkCausticsImpostorCommon.glsl, over
   * CausticRadius).
   *
   * The shared stage of every photon technique (vtkCausticsRenderPass::StoreCaustic()
   * calls it): ResetCaustic() at the start of a frame (no GL; the store then reads as
   * zero), then StoreCaustic() once per light after the technique's transport, with
   * its landed photon records (vtkCausticsPhotonGrid.h layout, `width` x `height`,
   * position w > 0 for a landed photon) and the light's buffers: each landed photon's
   * flux goes to the texel showing where it landed, and, with `shadow` (once per
   * light), each texel of the light's view whose first surface is specular takes its
   * flux off the texel where it would have landed without the specular object. The
   * frame's first call clears the store; its fixed point is 1/4096 of
   * `maximumPhotonFlux` / 3. Call after Update(). Returns false on a GL failure.
   */
  void ResetCaustic();
  /**
   * Opens the frame's store if no StoreCaustic() has (clears it, sets its fixed point
   * from `maximumPhotonFlux` as StoreCaustic() would), for a trace that deposits into
   * it itself (vtkCausticsPhotonBuffer::SetCausticStore). True when it is open.
   */
  bool OpenCaustic(double maximumPhotonFlux);
  bool StoreCaustic(vtkOpenGLRenderWindow* renWin, const caustics::PhotonRecords& landed,
    int width, int height, double maximumPhotonFlux, vtkCausticsLightBuffers* lightBuffers,
    int light, const caustics::SceneData& scene, bool shadow = true);
  void BindCausticImage() const;
#endif

  /** Whether the last Update() made the given map (its role group is not empty). */
  bool HasMap(int map) const;
  /**
   * Layers of the position, normal and radiance arrays after the last Update(): 6
   * per map up to the last map made (6 when none is), e.g. 12 for refractors alone.
   * The maps not made below it keep their layers, unused.
   */
  int GetNumberOfLayers() const;
  /** The generalized winding number of the reflectors at their reference point (last Update()). */
  double GetReflectorWinding() const;
  /** The reference point of a map (world, m). */
  void GetReferencePoint(int map, double point[3]) const;

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkCausticsDistanceImpostors();
  ~vtkCausticsDistanceImpostors() override;

  int Resolution = 256;
  int LinearSteps = 32;
  int SecantSteps = 8;
  int ReflectorBounces = 8;
  int CausticRadius = 3;
  int CausticSamples = 8;
  int CausticCoarseSamples = 64;
  int MapRenders = 0;
  double CausticUnit = 0.0; // W per count of the caustic store; 0: none this frame
  void BeginCaustic(double unit); // clears the store, sets its fixed point

private:
  vtkCausticsDistanceImpostors(const vtkCausticsDistanceImpostors&) = delete;
  void operator=(const vtkCausticsDistanceImpostors&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

  // Steps of Update().
  bool SceneChanged(const caustics::SceneData& scene);
  void ChooseReferencePoints(const caustics::SceneData& scene);
  bool RenderMap(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry, int map);
  bool ShadeMaps(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const caustics::SceneData& scene, vtkCausticsLightBuffers* shadowMaps);
  // The receiver area of each coarse cell of the caustic store (its sparse read).
  bool MeasureCausticCells(vtkOpenGLRenderWindow* renWin);
};

#endif
