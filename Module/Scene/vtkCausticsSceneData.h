/**
 * @file   vtkCausticsSceneData.h
 * @brief  Plain data shared by the GPU passes and the CPU reference renderer.
 *
 * vtkCausticsSceneExtractor turns a vtkRenderer (actors, their vtkProperty and
 * caustics keys, lights, active camera, medium) into this snapshot once per
 * frame. The GPU passes upload it, the reference renderer ray-traces it, so both
 * see exactly the same triangles, materials, lights and camera.
 *
 * Units: lengths are scene units, taken as metres. Light "Radiometric" values are
 * irradiance in W/m^2 (on a surface facing a directional light) or radiant
 * intensity in W/sr (point and spot lights), per RGB channel.
 */
#ifndef vtkCausticsSceneData_h
#define vtkCausticsSceneData_h

#include <algorithm> // For std::max
#include <array>   // For std::array
#include <cstdint> // For std::uint32_t
#include <memory>  // For std::shared_ptr
#include <string>  // For std::string
#include <tuple>   // For std::tuple
#include <vector>  // For std::vector

class vtkActor;

namespace caustics
{
using Vec3 = std::array<double, 3>;

/** What an actor does to light. Values are shared with the shaders (vtkCausticsCommon.glsl). */
enum class Role : int
{
  None = 0,      ///< drawn by VTK, ignored by caustics (no shadow, no caustic)
  Receiver = 1,  ///< diffuse (Lambertian) surface that shows caustics
  Reflector = 2, ///< specular mirror (conductor Fresnel with complex IOR n + ik)
  Refractor = 3  ///< specular dielectric (Fresnel-weighted reflection + refraction)
};

const char* RoleName(Role role);

struct Material
{
  Role role = Role::Receiver;
  Vec3 albedo{ { 0.8, 0.8, 0.8 } };       ///< diffuse reflectance of receivers (linear RGB)
  double ior = 1.5;                       ///< refractors: index of refraction, outside medium = 1
  double roughness = 0.0;                 ///< as in vtkProperty (PBR); > cut-off means diffuse
  Vec3 metalN{ { 0.155, 0.117, 0.138 } }; ///< reflectors: real part of complex IOR (silver)
  Vec3 metalK{ { 4.83, 3.12, 2.15 } };    ///< reflectors: imaginary part (extinction)
  Vec3 attenuation{ { 0, 0, 0 } };        ///< refractors: Beer-Lambert absorption, 1/m
};

struct Mesh
{
  std::string name;                   ///< actor's name or "actor <index>" for messages
  vtkActor* actor = nullptr;          ///< the source actor (not owned)
  /** Model to world, row-major: the actor's matrix composed with its assemblies'. */
  std::array<double, 16> modelToWorld{ { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 } };
  int material = 0;                   ///< index into SceneData::Materials
  std::vector<float> positions;       ///< world-space xyz per vertex
  std::vector<float> normals;         ///< world-space unit normal per vertex
  std::vector<std::uint32_t> indices; ///< three per triangle
  unsigned long version = 0;          ///< changes whenever positions/normals/indices change
  std::size_t TriangleCount() const { return indices.size() / 3; }
};

struct Light
{
  enum class Type : int
  {
    Directional = 0,
    Point = 1,
    Spot = 2
  };
  Type type = Type::Directional;
  Vec3 position{ { 0, 0, 0 } };    ///< point/spot: world position
  Vec3 direction{ { 0, 0, -1 } };  ///< unit vector the light travels along (directional/spot axis)
  Vec3 radiometric{ { 1, 1, 1 } }; ///< W/m^2 (directional) or W/sr (point/spot), per channel
  double cosOuter = -1.0;          ///< spot: cos of the outer cone half-angle
  double cosInner = 1.0;           ///< spot: cos of the inner cone half-angle (full intensity)
  /**
   * How VTK's own shading falls off for this light (vtkLight's attenuation values,
   * spot exponent and cone angle in degrees; a cone of 90 or more is no spot). The
   * composite removes that shading where reflectors and refractors block the light,
   * whatever falloff the user gave VTK; the caustics use the physical one above.
   */
  Vec3 shadingAttenuation{ { 1, 0, 0 } };
  double shadingExponent = 1.0;
  double shadingConeAngle = 180.0;

  /** Spot falloff of glTF KHR_lights_punctual (1 inside the inner cone, 0 outside the outer). */
  double SpotFactor(double cosAngle) const;
};

struct Camera
{
  Vec3 position{ { 0, 0, 1 } };
  Vec3 focalPoint{ { 0, 0, 0 } };
  Vec3 viewUp{ { 0, 1, 0 } };
  double viewAngle = 30.0; ///< degrees, vertical
  bool parallel = false;
  double parallelScale = 1.0;
  double clippingRange[2] = { 0.1, 100.0 };
  int width = 256, height = 256;
  /** World to clip (OpenGL convention, row-major as vtkMatrix4x4), and its inverse. */
  double worldToClip[16];
  double clipToWorld[16];

  /** The primary ray through pixel centre (px+0.5, py+0.5); py counts up from the bottom row. */
  void PixelRay(double px, double py, Vec3& origin, Vec3& direction) const;
  /** Projects a world point to pixel coordinates (x right, y up); returns false behind the eye. */
  bool WorldToPixel(const Vec3& world, double& px, double& py) const;
};

class DensityGrid; // vtkCausticsDensityGrid.h

/**
 * Participating medium filling the scene (single scattering): the coefficients times
 * the density, which is 1 everywhere without a density grid (homogeneous).
 */
struct Medium
{
  bool enabled = false;
  Vec3 sigmaS{ { 0, 0, 0 } }; ///< scattering coefficient, 1/m per unit density
  Vec3 sigmaA{ { 0, 0, 0 } }; ///< absorption coefficient, 1/m per unit density
  double g = 0.0;             ///< Henyey-Greenstein anisotropy
  bool fillsRefractors = false; ///< also inside refractors (vtkCausticsMedium::SetFillsRefractors)
  /** Density, placed and scaled (vtkCausticsMedium::GetDensity()); null: homogeneous. */
  std::shared_ptr<const DensityGrid> density;

  /** The grid's mean density, 1 without a grid. */
  double MeanDensity() const;
  ///@{
  /**
   * The coefficients times MeanDensity(): the homogeneous medium a technique that
   * cannot follow the density uses instead (exactly sigmaS, sigmaS + sigmaA without a grid).
   */
  Vec3 MeanSigmaS() const;
  Vec3 MeanSigmaT() const;
  ///@}
};

struct SceneData;

/**
 * The frustum a light sees the scene through, for its light-space buffers:
 * orthographic along a directional light, perspective from a point or spot light.
 * It is aimed at a focus sphere (the specular objects, where photons must go, or
 * the whole scene, for shadows) and its depth range holds the whole scene, so
 * occluders between the light and the focus are rendered too.
 */
struct LightView
{
  enum class Focus : int
  {
    Specular = 0, ///< bounding sphere of reflectors and refractors
    Scene = 1,    ///< bounding sphere of every mesh
    /** Bounding sphere of the specular surfaces whose light can reach what the
     * camera sees (PhotonFocusBounds, vtkCausticsPhotonFocus.h): Specular, narrowed. */
    SeenSpecular = 2
  };
  int light = 0;            ///< index into SceneData::Lights
  bool perspective = false; ///< point/spot: true
  bool valid = false;       ///< false when there is nothing to look at
  bool clamped = false;     ///< point/spot inside the focus sphere: field of view capped
  Vec3 eye{ { 0, 0, 0 } }, axis{ { 0, 0, -1 } }, right{ { 1, 0, 0 } }, up{ { 0, 1, 0 } };
  double halfExtent = 1.0; ///< orthographic: half width (m); perspective: tan(half angle)
  /** Orthographic: the half height (along `up`) over halfExtent, in [1/MaximumAspect,
   * MaximumAspect]. A view fitted to a box's outline (Focus::SeenSpecular) takes the
   * outline's shape, so a sheet the light meets obliquely gets the texels a square
   * frustum would spend beside it. Perspective views stay square (1). */
  double aspect = 1.0;
  static constexpr double MaximumAspect = 2.0;
  /** Half height along `up` (m, or tan of the half angle): halfExtent x aspect. */
  double HalfExtentUp() const { return this->halfExtent * this->aspect; }
  /** The larger side of one texel of a `resolution`-texel buffer (m; perspective: at
   * unit depth). */
  double TexelWidth(int resolution) const
  {
    return 2.0 * this->halfExtent * std::max(1.0, this->aspect) / std::max(resolution, 1);
  }
  /** Area of one texel of a `resolution`-texel buffer (m^2; perspective: on the unit
   * image plane). */
  double TexelArea(int resolution) const
  {
    const double texel = 2.0 * this->halfExtent / std::max(resolution, 1);
    return texel * texel * this->aspect;
  }
  double nearPlane = 0.01, farPlane = 1.0;
  double worldToClip[16]; ///< row-major, OpenGL clip conventions
  double clipToWorld[16];
  /** The box the view is aimed at (xmin, xmax, ymin, ymax, zmin, zmax): for Focus::
   * SeenSpecular the specular surfaces whose light can reach what the camera sees,
   * which hold every reflection and refraction its photons can meet. */
  double focus[6] = { 0, 0, 0, 0, 0, 0 };

  /**
   * Flux leaving the light through the frustum (W, per channel): irradiance x
   * cross-section for directional lights, intensity x solid angle for point lights.
   * Spot falloff is not included (integrate it per texel instead).
   */
  Vec3 FrustumPower(const Light& light) const;
  /** Solid angle (sr) of the perspective frustum: 4 atan(t^2 / sqrt(1 + 2 t^2)). */
  double FrustumSolidAngle() const;
};

/** Computes the view of light `index` aimed at `focus`. Invalid if the scene is empty. */
LightView ComputeLightView(const SceneData& scene, int index, LightView::Focus focus);

/**
 * Moves the view's texel grid by (u, v) texels of a `resolution`-texel buffer, each
 * in [-0.5, 0.5]: an orthographic view slides across the light, a perspective one turns
 * by that much about its eye (the light stays where it is). The photons of a buffer
 * drawn from the moved view are another regular set of the same light: frames drawn
 * with different offsets average towards the light's continuous flux.
 */
void OffsetLightView(LightView& view, double u, double v, int resolution);

struct SceneData
{
  std::vector<Mesh> Meshes;
  std::vector<Material> Materials; ///< one per mesh (same index)
  std::vector<Light> Lights;
  Camera View;
  Medium Participating;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };         ///< all participating meshes
  double SpecularBounds[6] = { 0, 0, 0, 0, 0, 0 }; ///< reflectors and refractors only
  bool HasSpecular = false;
  /** The longest straight path inside one refractor (m): the largest diagonal of a
   * refractor mesh's own bounds (0 without refractors). A mirror far away leaves it
   * alone, where the diagonal of SpecularBounds would grow with it. */
  double RefractorChord = 0.0;

  /** Length of the bounds' diagonal: the scene's size for relative tolerances. */
  double Scale() const;
};

/**
 * Whether `light` can send light to the specular objects bounded by
 * `specularBounds` (xmin, xmax, ymin, ymax, zmin, zmax): it has power in some
 * channel and, for a spot light, its outer cone meets the bounds' sphere
 * (directional and point lights reach everything). The bounds are taken as they
 * are: callers whose scene may hold no specular object at all test
 * SceneData::HasSpecular first.
 */
bool LightReachesSpecular(const Light& light, const double specularBounds[6]);

/**
 * Whether light `index` may pass through one refractor mesh and then through another:
 * two refractor meshes whose bounding spheres overlap as the light sees them (across
 * a sun's rays, or in angle from a point or spot light; a light inside one sees every
 * other in line). Conservative: spheres that overlap may hold no such path. `first`
 * and `second` are the two meshes (indices into scene.Meshes), the first nearer the
 * light. A light without power sees none.
 */
bool RefractorsInLine(const SceneData& scene, int index, int& first, int& second);

/**
 * The box (xmin, xmax, ymin, ymax, zmin, zmax) of every receiver's finite vertices;
 * empty (min > max) without receivers.
 */
void ReceiverBounds(const SceneData& scene, double box[6]);

/** A mesh's role: its material's, Role::None where the material index is out of range. */
Role MeshRole(const SceneData& scene, const Mesh& mesh);

/**
 * (version, material, role) of every mesh: two equal keys mean that no mesh's geometry,
 * material index or role changed, which is what caches of the geometry compare.
 */
std::vector<std::tuple<unsigned long, int, int>> MeshKey(const SceneData& scene);

/**
 * The angle in degrees at which light `index` meets the receivers beyond its
 * specular actors: the light's ray through the centre of SceneData::SpecularBounds
 * is followed past that centre to the first receiver triangle (or, when it meets
 * none, e.g. a sun parallel to the floor, the receiver triangle nearest to that
 * centre is taken), and the angle between the ray and that surface is returned
 * (90: head-on, 0: grazing). -1 when the scene has no receiver, 90 when it has no
 * specular actor or the light sits at their centre. A CPU scan of
 * the receivers' triangles; techniques that store caustics in the light's view
 * (caustic maps) lose what lands on surfaces the light sees edge-on.
 */
double ReceiverIncidenceAngle(const SceneData& scene, int index);

/** Where ReceiverIncidenceAngle() meets the receivers, and the surface there. */
struct ReceiverIncidence
{
  double angle = 90.0;                ///< as ReceiverIncidenceAngle()
  bool found = false;                 ///< a receiver triangle was met or taken
  Vec3 point{ { 0, 0, 0 } };          ///< the hit, or the nearest point of the nearest triangle
  Vec3 normal{ { 0, 1, 0 } };         ///< that triangle's unit normal, facing the light
  Vec3 direction{ { 0, 0, -1 } };     ///< the light's unit direction there
};
/** With `focus` (a box: what the light's photons are aimed at, LightView::focus) the
 * light's ray goes through its centre instead of SceneData::SpecularBounds'. */
ReceiverIncidence FindReceiverIncidence(
  const SceneData& scene, int index, const double* focus = nullptr);

/**
 * The part of the scene the camera sees: the bounding box of scene.Bounds cut by
 * the camera's clip volume (scene.View, near to far plane), exactly (the box is
 * clipped as a polyhedron, not box against box). Returns false, with `box` set to
 * scene.Bounds, when the camera sees none of it.
 */
bool VisibleBounds(const SceneData& scene, double box[6]);

/**
 * The diagonal of the box around VisibleBounds() and the specular actors: the size
 * of the region a frame's caustics are computed over, which relative tolerances
 * follow (a far-away actor the camera does not see changes nothing). With
 * `specular` (a box: the specular surfaces photons can meet, LightView::focus) that
 * box stands for the specular actors: an idle mirror far off changes nothing either.
 */
double VisibleScale(const SceneData& scene, const double* specular = nullptr);

/** VisibleScale() over the specular actors' bounds diagonal; 0 without specular actors. */
double VisibleOverSpecular(const SceneData& scene);

/**
 * Widens `box` (xmin, xmax, ymin, ymax, zmin, zmax) to hold `mesh`'s vertex
 * positions; non-finite coordinates are skipped.
 */
void GrowBounds(const Mesh& mesh, double box[6]);

/**
 * The generalized winding number of `mesh` at `point`: the signed solid angle of its
 * triangles over 4 pi (Van Oosterom and Strackee). About 1 inside a closed mesh whose
 * triangles face outward, 0 outside, fractions for open meshes; triangles with an
 * index out of range or a non-finite vertex are skipped.
 */
double WindingNumber(const Mesh& mesh, const double point[3]);

/**
 * The view a light-space receiver map (a caustic map) of light `index` is stored
 * in: the light's own view (ComputeLightView) aimed at the part of the scene the
 * camera sees (VisibleBounds), so that its texels go where the image can show
 * them whatever else the scene holds. When the light meets the receivers beyond
 * the specular actors at under `minimumIncidence` degrees (`incidence`, from
 * FindReceiverIncidence(scene, index), a scan of the receivers that callers keep
 * while the light and meshes stay),
 * the view is turned about that point, towards the receiver's normal, until it
 * sees them at `minimumIncidence`: a surface the light sees edge-on has no texels
 * in the light's view. A point or spot light's frustum is then narrowed to the
 * corners of the box of the receivers the camera sees and every mirror across the
 * light, when some frustum within 75 degrees holds them: a lamp inside the seen box's
 * bounding sphere otherwise gets the widest frustum. With `photonFocus` (the box the light's
 * photons are aimed at, LightView::focus, which holds every mirror they can meet)
 * only the mirrors that meet it count. The fit does not apply with a participating
 * medium (the photons' paths are seen beyond where they land). The depth range holds
 * the whole scene, as for every light view.
 */
LightView ComputeReceiverMapView(const SceneData& scene, int index,
  const ReceiverIncidence& incidence, double minimumIncidence, const double* photonFocus = nullptr);
}

#endif
