#include "vtkCausticsPhotonFocus.h"

#include "vtkCausticsSceneData.h"

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp> // For glm::pi

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace caustics
{
namespace
{
using Box = std::array<double, 6>;

constexpr double Infinity = std::numeric_limits<double>::infinity();

/** Cone-against-mesh tests PhotonFocusBounds may make across several meshes. */
constexpr double MaximumPairTests = 2e6;

Box EmptyBox()
{
  return { { Infinity, -Infinity, Infinity, -Infinity, Infinity, -Infinity } };
}

bool IsEmpty(const Box& b)
{
  return !(b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5]);
}

void Include(Box& b, const glm::dvec3& x)
{
  for (int k = 0; k < 3; ++k)
  {
    b[2 * k] = std::min(b[2 * k], x[k]);
    b[2 * k + 1] = std::max(b[2 * k + 1], x[k]);
  }
}

void Include(Box& b, const Box& other)
{
  for (int k = 0; k < 3; ++k)
  {
    b[2 * k] = std::min(b[2 * k], other[2 * k]);
    b[2 * k + 1] = std::max(b[2 * k + 1], other[2 * k + 1]);
  }
}

Box Grown(const Box& b, double margin)
{
  return { { b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin, b[4] - margin,
    b[5] + margin } };
}

bool Overlap(const Box& a, const Box& b)
{
  return a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3] && a[4] <= b[5] &&
    b[4] <= a[5];
}

/** The parameters t >= 0 at which the ray o + t d is inside `b`, or false. */
bool RayInterval(const glm::dvec3& o, const glm::dvec3& d, const Box& b, double& t0, double& t1)
{
  t0 = 0.0;
  t1 = Infinity;
  for (int k = 0; k < 3; ++k)
  {
    if (std::abs(d[k]) < 1e-300)
    {
      if (o[k] < b[2 * k] || o[k] > b[2 * k + 1])
      {
        return false;
      }
      continue;
    }
    double near = (b[2 * k] - o[k]) / d[k], far = (b[2 * k + 1] - o[k]) / d[k];
    if (near > far)
    {
      std::swap(near, far);
    }
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 <= t1;
}

/**
 * The directions leaving a triangle for one branch (reflected or refracted light),
 * bounded by a cone: light leaving any point of the triangle along a direction of
 * the branch stays within radius + t * spread of the ray origin + t direction.
 */
struct Cone
{
  bool valid = false;
  glm::dvec3 origin{ 0.0 }, direction{ 0.0 };
  double radius = 0.0;
  double spread = 0.0; // tangent of the half angle
};

/** Unit `d` reflected (refract false) or refracted at unit normal `n`; false at TIR. */
bool Scatter(const glm::dvec3& d, glm::dvec3 n, double ior, bool refract, glm::dvec3& out)
{
  if (!refract)
  {
    out = glm::reflect(d, n);
    return true;
  }
  double eta = 1.0 / ior;
  if (glm::dot(d, n) > 0.0)
  {
    n = -n; // leaving the refractor
    eta = ior;
  }
  out = glm::refract(d, n, eta);
  return glm::dot(out, out) > 0.5; // GLM returns the zero vector at TIR
}

/** A cone started from the triangle x: at its centroid, as wide as its farthest corner. */
Cone StartAt(const glm::dvec3 x[3])
{
  Cone cone;
  cone.origin = (x[0] + x[1] + x[2]) / 3.0;
  for (int k = 0; k < 3; ++k)
  {
    cone.radius = std::max(cone.radius, glm::length(x[k] - cone.origin));
  }
  return cone;
}

Cone MakeCone(const glm::dvec3 x[3], const glm::dvec3 leaving[3], const bool valid[3])
{
  Cone cone;
  int count = 0;
  glm::dvec3 sum(0.0);
  for (int k = 0; k < 3; ++k)
  {
    if (valid[k])
    {
      sum += leaving[k];
      ++count;
    }
  }
  if (count == 0 || !(glm::dot(sum, sum) > 1e-12))
  {
    return cone;
  }
  cone = StartAt(x);
  cone.valid = true;
  cone.direction = glm::normalize(sum);
  if (count < 3)
  {
    // Total internal reflection at some corners: the refracted directions between
    // them sweep towards the surface. Any direction of the half-space.
    cone.spread = 1e3;
    return cone;
  }
  double angle = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    angle = std::max(
      angle, std::acos(std::max(-1.0, std::min(1.0, glm::dot(cone.direction, leaving[k])))));
  }
  // Interpolated normals between the corners turn the light a little beyond the
  // corners' own directions (second order in the angle between them).
  const double widened = 1.1 * angle + 0.5 * glm::pi<double>() / 180.0;
  cone.spread = widened < 0.49 * glm::pi<double>() ? std::tan(widened) : 1e3;
  return cone;
}

/** Distance from `x` to the box `b` (0 inside). */
double Distance(const glm::dvec3& x, const Box& b)
{
  double sum = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double outside = std::max({ b[2 * k] - x[k], 0.0, x[k] - b[2 * k + 1] });
    sum += outside * outside;
  }
  return std::sqrt(sum);
}

/**
 * Whether light along `cone` can reach `region`: some t >= 0 at which the ray's point
 * is within the cone's radius there, radius + t spread, of the box. That distance less
 * the radius is convex in t, so a golden-section search finds its least value.
 */
bool Reaches(const Cone& cone, const Box& region)
{
  if (cone.spread >= 1e3)
  {
    return true;
  }
  double farthest = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    const glm::dvec3 corner(
      region[(c & 1)], region[2 + ((c >> 1) & 1)], region[4 + ((c >> 2) & 1)]);
    farthest = std::max(farthest, glm::length(corner - cone.origin));
  }
  auto gap = [&](double t)
  { return Distance(cone.origin + t * cone.direction, region) - cone.radius - t * cone.spread; };
  // Beyond b the point is farther from every corner than the cone is wide.
  double a = 0.0, b = (farthest + cone.radius) / (1.0 - std::min(cone.spread, 0.9));
  if (gap(a) <= 0.0 || gap(b) <= 0.0)
  {
    return true;
  }
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - ratio * (b - a), d = a + ratio * (b - a);
  double gc = gap(c), gd = gap(d);
  for (int i = 0; i < 80 && gc > 0.0 && gd > 0.0; ++i)
  {
    if (gc < gd)
    {
      b = d;
      d = c;
      gd = gc;
      c = b - ratio * (b - a);
      gc = gap(c);
    }
    else
    {
      a = c;
      c = d;
      gc = gd;
      d = a + ratio * (b - a);
      gd = gap(d);
    }
  }
  return gc <= 0.0 || gd <= 0.0;
}

/** The part of `bounds` light along `cone` can cross (conservative). */
Box Swept(const Cone& cone, const Box& bounds)
{
  double t0, t1;
  const Box grown = Grown(bounds, cone.radius);
  if (!RayInterval(cone.origin, cone.direction, grown, t0, t1))
  {
    return EmptyBox();
  }
  if (cone.spread >= 1e3)
  {
    return bounds;
  }
  Box swept = EmptyBox();
  Include(swept, cone.origin + t0 * cone.direction);
  Include(swept, cone.origin + t1 * cone.direction);
  swept = Grown(swept, cone.radius + t1 * cone.spread);
  for (int k = 0; k < 3; ++k)
  {
    swept[2 * k] = std::max(swept[2 * k], bounds[2 * k]);
    swept[2 * k + 1] = std::min(swept[2 * k + 1], bounds[2 * k + 1]);
  }
  return swept;
}

/** The box around every receiver's vertices (empty without receivers). */
Box Intersection(const Box& a, const Box& b)
{
  Box both;
  for (int k = 0; k < 3; ++k)
  {
    both[2 * k] = std::max(a[2 * k], b[2 * k]);
    both[2 * k + 1] = std::min(a[2 * k + 1], b[2 * k + 1]);
  }
  return both;
}

/** The mesh's triangles with their corners and unit normals (per vertex, else per face). */
struct Triangles
{
  std::vector<glm::dvec3> Corners; // three per triangle
  std::vector<glm::dvec3> Normals; // three per triangle
};

Triangles Gather(const Mesh& mesh)
{
  Triangles t;
  const std::size_t vertices = mesh.positions.size() / 3;
  const bool normals = mesh.normals.size() == mesh.positions.size();
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
  {
    glm::dvec3 x[3], n[3];
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k)
    {
      const std::size_t v = mesh.indices[i + k];
      ok = v < vertices;
      if (ok)
      {
        x[k] =
          glm::dvec3(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
        n[k] = normals
          ? glm::dvec3(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2])
          : glm::dvec3(0.0);
        ok = std::isfinite(x[k].x) && std::isfinite(x[k].y) && std::isfinite(x[k].z);
      }
    }
    const glm::dvec3 face = glm::cross(x[1] - x[0], x[2] - x[0]);
    if (!ok || !(glm::dot(face, face) > 0.0))
    {
      continue; // a degenerate triangle draws nothing
    }
    for (int k = 0; k < 3; ++k)
    {
      const double length = glm::length(n[k]);
      n[k] = std::isfinite(length) && length > 1e-9 ? n[k] / length : glm::normalize(face);
      t.Corners.push_back(x[k]);
      t.Normals.push_back(n[k]);
    }
  }
  return t;
}

/** Whether every normal lies within 45 degrees of their mean: a sheet. */
bool IsSheetOf(const Triangles& t)
{
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& n : t.Normals)
  {
    mean += n;
  }
  if (t.Normals.empty() || !(glm::length(mean) > 0.5 * static_cast<double>(t.Normals.size())))
  {
    return false;
  }
  mean = glm::normalize(mean);
  const double cos45 = std::sqrt(0.5);
  return std::all_of(t.Normals.begin(), t.Normals.end(),
    [&](const glm::dvec3& n) { return glm::dot(n, mean) >= cos45; });
}

/** The cones of triangle `i` for light arriving along `incoming(x)`: reflected, refracted. */
template <typename Incoming>
void Cones(
  const Triangles& t, std::size_t i, double ior, bool refractor, Incoming incoming, Cone cones[2])
{
  const glm::dvec3* x = &t.Corners[3 * i];
  const glm::dvec3* n = &t.Normals[3 * i];
  for (int branch = 0; branch < 2; ++branch)
  {
    cones[branch] = Cone();
    if (branch == 1 && !refractor)
    {
      continue;
    }
    glm::dvec3 leaving[3];
    bool valid[3];
    for (int k = 0; k < 3; ++k)
    {
      valid[k] = Scatter(incoming(x[k]), n[k], ior, branch == 1, leaving[k]);
    }
    cones[branch] = MakeCone(x, leaving, valid);
  }
}

/** A specular mesh as the focus sees it. */
struct SpecularMesh
{
  const Material* material = nullptr;
  Triangles triangles;
  Box bounds = EmptyBox();
  bool sheet = false;
  std::size_t Count() const { return this->triangles.Corners.size() / 3; }
  bool Refracts() const { return this->material->role == Role::Refractor; }
};

/** The scene's reflectors and refractors that have a triangle. */
std::vector<SpecularMesh> GatherSpecular(const SceneData& scene)
{
  std::vector<SpecularMesh> meshes;
  for (const Mesh& mesh : scene.Meshes)
  {
    const Material& material = scene.Materials[mesh.material];
    if (material.role != Role::Reflector && material.role != Role::Refractor)
    {
      continue;
    }
    SpecularMesh m;
    m.material = &material;
    m.triangles = Gather(mesh);
    for (const glm::dvec3& x : m.triangles.Corners)
    {
      Include(m.bounds, x);
    }
    m.sheet = IsSheetOf(m.triangles);
    if (m.Count() > 0)
    {
      meshes.push_back(std::move(m));
    }
  }
  return meshes;
}

/**
 * The cone of light reflected at triangle `i` that arrives from anywhere in `source`
 * (another specular mesh's bounds): the directions from the source's bounding sphere
 * to the triangle's bounding sphere lie within alpha of the line between their
 * centres, the smoothed normals within beta of their mean, and a reflection turns by
 * at most alpha + 2 beta when its direction turns by alpha and its normal by beta.
 * Any direction (spread 1e3) where the spheres overlap.
 */
Cone ReflectedFrom(const Triangles& t, std::size_t i, const Box& source)
{
  const glm::dvec3* x = &t.Corners[3 * i];
  const glm::dvec3* n = &t.Normals[3 * i];
  Cone cone = StartAt(x);
  cone.valid = true;
  const glm::dvec3 centre(
    0.5 * (source[0] + source[1]), 0.5 * (source[2] + source[3]), 0.5 * (source[4] + source[5]));
  const double sourceRadius =
    0.5 * glm::length(glm::dvec3(source[1] - source[0], source[3] - source[2], source[5] - source[4]));
  const glm::dvec3 mean = n[0] + n[1] + n[2];
  const double distance = glm::length(cone.origin - centre);
  cone.spread = 1e3;
  if (!(distance > sourceRadius + cone.radius) || !(glm::length(mean) > 1e-9))
  {
    return cone;
  }
  const glm::dvec3 normal = glm::normalize(mean);
  double beta = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    beta = std::max(beta, std::acos(std::max(-1.0, std::min(1.0, glm::dot(n[k], normal)))));
  }
  const double alpha = std::asin((sourceRadius + cone.radius) / distance);
  const double angle = alpha + 2.0 * beta + 0.5 * glm::pi<double>() / 180.0;
  cone.direction = glm::reflect((cone.origin - centre) / distance, normal);
  cone.spread = angle < 0.49 * glm::pi<double>() ? std::tan(angle) : 1e3;
  return cone;
}

/** Whether light along `cone` can reach a specular mesh other than `self`. */
bool ReachesAnother(const Cone& cone, const std::vector<SpecularMesh>& meshes, std::size_t self)
{
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    if (m != self && Reaches(cone, meshes[m].bounds))
    {
      return true;
    }
  }
  return false;
}
}

bool IsSheet(const Mesh& mesh)
{
  return IsSheetOf(Gather(mesh));
}

bool PhotonFocusBounds(const SceneData& scene, int index, double box[6])
{
  const double* whole = scene.HasSpecular ? scene.SpecularBounds : scene.Bounds;
  std::copy(whole, whole + 6, box);
  if (!scene.HasSpecular || scene.Participating.enabled || index < 0 ||
    index >= static_cast<int>(scene.Lights.size()))
  {
    return false;
  }
  double seen[6];
  if (!VisibleBounds(scene, seen))
  {
    return false;
  }
  const std::vector<SpecularMesh> meshes = GatherSpecular(scene);
  if (meshes.empty())
  {
    return false;
  }
  // Each sheet triangle's cones are tested against every other mesh: past a budget
  // of such tests (about a second's work) the whole box is kept rather than stall.
  double pairTests = 0.0;
  for (const SpecularMesh& mesh : meshes)
  {
    // Its cones against every other mesh, and (a mirror lit by the others) theirs.
    pairTests += mesh.sheet ? static_cast<double>(mesh.Count()) * (meshes.size() - 1) *
        (mesh.Refracts() ? 1.0 : static_cast<double>(meshes.size()))
                            : 0.0;
  }
  if (pairTests > MaximumPairTests)
  {
    return false;
  }
  // Caustics are seen on receivers: the receivers inside the camera's clip volume...
  Box receivers;
  caustics::ReceiverBounds(scene, receivers.data());
  Box visible;
  std::copy(seen, seen + 6, visible.begin());
  Box region = Intersection(visible, receivers);
  if (IsEmpty(region))
  {
    region = EmptyBox();
  }
  // ...and those it sees through a sheet or in it: its rays, reflected and refracted at
  // the triangles inside the clip volume, swept across the receivers. A ray that can
  // meet another specular mesh, or that enters a closed or curved one, may go on
  // anywhere: then every receiver counts.
  const Camera& camera = scene.View;
  const glm::dvec3 eye(camera.position[0], camera.position[1], camera.position[2]);
  const glm::dvec3 viewDirection = glm::normalize(
    glm::dvec3(camera.focalPoint[0], camera.focalPoint[1], camera.focalPoint[2]) - eye);
  auto fromCamera = [&](const glm::dvec3& x)
  { return camera.parallel ? viewDirection : glm::normalize(x - eye); };
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const SpecularMesh& mesh = meshes[m];
    if (!Overlap(mesh.bounds, visible))
    {
      continue;
    }
    if (!mesh.sheet)
    {
      Include(region, receivers);
      continue;
    }
    for (std::size_t i = 0; i < mesh.Count(); ++i)
    {
      Box triangle = EmptyBox();
      for (int k = 0; k < 3; ++k)
      {
        Include(triangle, mesh.triangles.Corners[3 * i + k]);
      }
      if (!Overlap(triangle, visible))
      {
        continue;
      }
      Cone cones[2];
      Cones(mesh.triangles, i, mesh.material->ior, mesh.Refracts(), fromCamera, cones);
      for (const Cone& cone : cones)
      {
        if (!cone.valid)
        {
          continue;
        }
        if (ReachesAnother(cone, meshes, m))
        {
          Include(region, receivers);
        }
        const Box swept = Swept(cone, receivers);
        if (!IsEmpty(swept))
        {
          Include(region, swept);
        }
      }
    }
  }
  if (IsEmpty(region))
  {
    return false; // no receiver in view: nothing to aim at
  }
  // The light leaving each sheet triangle, straight from the light.
  const Light& light = scene.Lights[index];
  const glm::dvec3 lightPosition(light.position[0], light.position[1], light.position[2]);
  const glm::dvec3 lightDirection =
    glm::normalize(glm::dvec3(light.direction[0], light.direction[1], light.direction[2]));
  auto fromLight = [&](const glm::dvec3& x)
  {
    return light.type == Light::Type::Directional ? lightDirection
                                                  : glm::normalize(x - lightPosition);
  };
  auto leaving = [&](const SpecularMesh& mesh, std::size_t i, Cone cones[2])
  { Cones(mesh.triangles, i, mesh.material->ior, mesh.Refracts(), fromLight, cones); };
  // The meshes whose specular light can reach each mesh: it gets light from directions
  // its own cones do not follow. A closed or curved mesh's light may go anywhere.
  std::vector<std::vector<std::size_t>> sources(meshes.size());
  for (std::size_t n = 0; n < meshes.size(); ++n)
  {
    for (std::size_t m = 0; m < meshes.size(); ++m)
    {
      bool reaches = m != n && !meshes[n].sheet;
      for (std::size_t i = 0; m != n && i < meshes[n].Count() && !reaches; ++i)
      {
        Cone cones[2];
        leaving(meshes[n], i, cones);
        reaches = (cones[0].valid && Reaches(cones[0], meshes[m].bounds)) ||
          (cones[1].valid && Reaches(cones[1], meshes[m].bounds));
      }
      if (reaches)
      {
        sources[m].push_back(n);
      }
    }
  }
  // The triangles whose light can reach that region, or another specular mesh (whose
  // light may then reach it). A mirror sheet lit by other meshes follows their light
  // too, from anywhere in their bounds (ReflectedFrom): a mirror far off that the glass
  // lights faintly and that sends that light to the sky stays out. A refracting sheet
  // lit by another mesh counts whole.
  Box focus = EmptyBox();
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const SpecularMesh& mesh = meshes[m];
    if (!mesh.sheet || (!sources[m].empty() && mesh.Refracts()))
    {
      Include(focus, mesh.bounds);
      continue;
    }
    for (std::size_t i = 0; i < mesh.Count(); ++i)
    {
      Cone cones[2];
      leaving(mesh, i, cones);
      bool kept = false;
      for (const Cone& cone : cones)
      {
        kept = kept || (cone.valid && (Reaches(cone, region) || ReachesAnother(cone, meshes, m)));
      }
      for (std::size_t n = 0; n < sources[m].size() && !kept; ++n)
      {
        const Cone reflected = ReflectedFrom(mesh.triangles, i, meshes[sources[m][n]].bounds);
        kept = Reaches(reflected, region) || ReachesAnother(reflected, meshes, m);
      }
      if (kept)
      {
        for (int k = 0; k < 3; ++k)
        {
          Include(focus, mesh.triangles.Corners[3 * i + k]);
        }
      }
    }
  }
  if (IsEmpty(focus))
  {
    return false; // no specular light reaches what is seen: keep the whole
  }
  bool narrower = false;
  for (int k = 0; k < 3; ++k)
  {
    const double low = std::max(whole[2 * k], focus[2 * k]);
    const double high = std::min(whole[2 * k + 1], focus[2 * k + 1]);
    narrower = narrower || low > whole[2 * k] || high < whole[2 * k + 1];
    box[2 * k] = low;
    box[2 * k + 1] = high;
  }
  return narrower;
}
}
