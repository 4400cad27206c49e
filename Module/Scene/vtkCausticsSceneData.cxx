#include "vtkCausticsSceneData.h"

#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsPhotonFocus.h"

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp> // For glm::pi
#include <glm/gtc/type_ptr.hpp> // For glm::make_mat4, glm::value_ptr

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace caustics
{
const char* RoleName(Role role)
{
  switch (role)
  {
    case Role::None:
      return "none";
    case Role::Receiver:
      return "receiver";
    case Role::Reflector:
      return "reflector";
    case Role::Refractor:
      return "refractor";
  }
  return "unknown";
}

double Light::SpotFactor(double cosAngle) const
{
  if (this->type != Type::Spot)
  {
    return 1.0;
  }
  if (cosAngle <= this->cosOuter)
  {
    return 0.0;
  }
  const double range = this->cosInner - this->cosOuter;
  if (range <= 1e-12)
  {
    return 1.0;
  }
  // KHR_lights_punctual's recommended falloff: a squared linear ramp in cos.
  const double t = std::min(1.0, (cosAngle - this->cosOuter) / range);
  return t * t;
}

namespace
{
void Transform(const double m[16], const double in[4], double out[4])
{
  for (int r = 0; r < 4; ++r)
  {
    out[r] = m[4 * r] * in[0] + m[4 * r + 1] * in[1] + m[4 * r + 2] * in[2] + m[4 * r + 3] * in[3];
  }
}
}

void Camera::PixelRay(double px, double py, Vec3& origin, Vec3& direction) const
{
  const double ndcX = 2.0 * (px + 0.5) / this->width - 1.0;
  const double ndcY = 2.0 * (py + 0.5) / this->height - 1.0;
  const double nearClip[4] = { ndcX, ndcY, -1.0, 1.0 };
  const double farClip[4] = { ndcX, ndcY, 1.0, 1.0 };
  double nearW[4], farW[4];
  Transform(this->clipToWorld, nearClip, nearW);
  Transform(this->clipToWorld, farClip, farW);
  double length = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    origin[i] = nearW[i] / nearW[3];
    direction[i] = farW[i] / farW[3] - origin[i];
    length += direction[i] * direction[i];
  }
  length = std::sqrt(length);
  for (int i = 0; i < 3; ++i)
  {
    direction[i] /= length;
  }
}

bool Camera::WorldToPixel(const Vec3& world, double& px, double& py) const
{
  const double p[4] = { world[0], world[1], world[2], 1.0 };
  double clip[4];
  Transform(this->worldToClip, p, clip);
  if (clip[3] <= 0.0)
  {
    return false;
  }
  px = (clip[0] / clip[3] * 0.5 + 0.5) * this->width;
  py = (clip[1] / clip[3] * 0.5 + 0.5) * this->height;
  return true;
}

namespace
{
double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
}

Vec3 Normalize(const Vec3& v)
{
  const double length = std::sqrt(Dot(v, v));
  return length > 0.0 ? Vec3{ { v[0] / length, v[1] / length, v[2] / length } }
                      : Vec3{ { 0, 0, -1 } };
}

double Diagonal(const double b[6])
{
  const double dx = b[1] - b[0], dy = b[3] - b[2], dz = b[5] - b[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

void BoundingSphere(const double bounds[6], Vec3& center, double& radius)
{
  center = { { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) } };
  const double dx = bounds[1] - bounds[0], dy = bounds[3] - bounds[2], dz = bounds[5] - bounds[4];
  radius = 0.5 * std::sqrt(dx * dx + dy * dy + dz * dz);
}

/** Inverse of a row-major 4x4 matrix; false when it is singular. */
bool Invert(const double in[16], double out[16])
{
  // GLM is column-major, so it reads the row-major array as the transpose; the inverse
  // of the transpose is the transpose of the inverse, written back in the same layout.
  const glm::dmat4 matrix = glm::make_mat4(in);
  const double determinant = glm::determinant(matrix);
  if (determinant == 0.0 || !std::isfinite(determinant))
  {
    return false;
  }
  const glm::dmat4 inverse = glm::inverse(matrix);
  std::copy(glm::value_ptr(inverse), glm::value_ptr(inverse) + 16, out);
  return true;
}

/**
 * Directional light: an orthographic view along the light, centred on the focus, from
 * before the whole scene (`reach`: radius around the focus centre holding it).
 */
void AimOrthographic(
  LightView& view, const Light& light, const Vec3& focusCenter, double focusRadius, double reach)
{
  view.axis = Normalize(light.direction);
  const double back = 1.01 * reach;
  for (int i = 0; i < 3; ++i)
  {
    view.eye[i] = focusCenter[i] - back * view.axis[i];
  }
  view.halfExtent = focusRadius;
  view.nearPlane = 0.005 * reach;
  view.farPlane = back + reach;
}

/** Largest half angle a single frustum covers well (texel solid angles vary by
 * cos^3; beyond about 75 degrees the texels at the rim become useless). */
constexpr double MaximumPerspectiveHalfAngle = 75.0 * glm::pi<double>() / 180.0;

/**
 * Point and spot lights: a perspective view from the light subtending the focus
 * sphere, or the spot cone when narrower, at most 75 degrees off axis.
 */
void AimPerspective(LightView& view, const Light& light, const Vec3& focusCenter,
  double focusRadius, const Vec3& sceneCenter, double sceneRadius)
{
  view.eye = light.position;
  const Vec3 toFocus{ { focusCenter[0] - view.eye[0], focusCenter[1] - view.eye[1],
    focusCenter[2] - view.eye[2] } };
  const double distance = std::sqrt(Dot(toFocus, toFocus));
  double halfAngle;
  const bool inside = !(distance > focusRadius * 1.0001);
  if (!inside)
  {
    view.axis = Normalize(toFocus);
    halfAngle = std::asin(std::min(1.0, focusRadius / distance));
  }
  else
  {
    // Inside the focus (e.g. a lamp in a glass ball) light leaves towards every side
    // and one frustum cannot hold it all: aim at the centre of the whole scene, where
    // the receivers are, not at the specular actors' centre (with the light at that
    // centre, no direction at all).
    const Vec3 toScene{ { sceneCenter[0] - view.eye[0], sceneCenter[1] - view.eye[1],
      sceneCenter[2] - view.eye[2] } };
    const double sceneDistance = std::sqrt(Dot(toScene, toScene));
    if (light.type == Light::Type::Spot)
    {
      view.axis = Normalize(light.direction);
    }
    else if (sceneDistance > 1e-3 * sceneRadius)
    {
      view.axis = Normalize(toScene);
    }
    else if (distance > 1e-3 * focusRadius)
    {
      view.axis = Normalize(toFocus);
    }
    else
    {
      view.axis = Vec3{ { 0.0, -1.0, 0.0 } }; // the scene's down (its y axis points up)
    }
    halfAngle = MaximumPerspectiveHalfAngle;
  }
  if (light.type == Light::Type::Spot)
  {
    const double outer = std::acos(std::max(-1.0, std::min(1.0, light.cosOuter)));
    if (outer < halfAngle)
    {
      // The cone is narrower than the focus: look along the spot axis instead.
      view.axis = Normalize(light.direction);
      halfAngle = outer;
    }
  }
  view.clamped =
    halfAngle > MaximumPerspectiveHalfAngle || (inside && light.type != Light::Type::Spot);
  halfAngle = std::min(halfAngle, MaximumPerspectiveHalfAngle);
  view.halfExtent = std::tan(halfAngle) * 1.0001;
  const Vec3 eyeToScene{ { sceneCenter[0] - view.eye[0], sceneCenter[1] - view.eye[1],
    sceneCenter[2] - view.eye[2] } };
  view.farPlane = std::sqrt(Dot(eyeToScene, eyeToScene)) + sceneRadius;
  view.nearPlane = 1e-4 * view.farPlane;
}

/** The view's basis, worldToClip (eye transform, then projection) and its inverse. */
void SetViewTransforms(LightView& view)
{
  const Vec3 helper = std::abs(view.axis[1]) < 0.9 ? Vec3{ { 0, 1, 0 } } : Vec3{ { 1, 0, 0 } };
  view.right = Normalize(Cross(view.axis, helper));
  view.up = Cross(view.right, view.axis);

  // World to eye (right, up, -axis as x, y, z), then the projection.
  double worldToEye[16] = { view.right[0], view.right[1], view.right[2], -Dot(view.right, view.eye),
    view.up[0], view.up[1], view.up[2], -Dot(view.up, view.eye), -view.axis[0], -view.axis[1],
    -view.axis[2], Dot(view.axis, view.eye), 0, 0, 0, 1 };
  const double n = view.nearPlane, f = view.farPlane, e = view.halfExtent;
  double projection[16] = { 0 };
  if (view.perspective)
  {
    projection[0] = 1.0 / e;
    projection[5] = 1.0 / view.HalfExtentUp();
    projection[10] = -(f + n) / (f - n);
    projection[11] = -2.0 * f * n / (f - n);
    projection[14] = -1.0;
  }
  else
  {
    projection[0] = 1.0 / e;
    projection[5] = 1.0 / view.HalfExtentUp();
    projection[10] = -2.0 / (f - n);
    projection[11] = -(f + n) / (f - n);
    projection[15] = 1.0;
  }
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        sum += projection[4 * r + k] * worldToEye[4 * k + c];
      }
      view.worldToClip[4 * r + c] = sum;
    }
  }
  view.valid = Invert(view.worldToClip, view.clipToWorld);
}
}

Vec3 LightView::FrustumPower(const Light& light) const
{
  const double measure =
    this->perspective ? this->FrustumSolidAngle() : 4.0 * this->halfExtent * this->HalfExtentUp();
  return { { light.radiometric[0] * measure, light.radiometric[1] * measure,
    light.radiometric[2] * measure } };
}

double LightView::FrustumSolidAngle() const
{
  const double t2 = this->halfExtent * this->halfExtent;
  return 4.0 * std::atan(t2 / std::sqrt(1.0 + 2.0 * t2));
}

namespace
{
/** The view of `light` (index `index`) aimed at the box `focusBounds`. */
LightView AimLightView(
  const SceneData& scene, const Light& light, int index, const double focusBounds[6])
{
  LightView view;
  view.light = index;
  std::copy(focusBounds, focusBounds + 6, view.focus);
  Vec3 sceneCenter, focusCenter;
  double sceneRadius, focusRadius;
  BoundingSphere(scene.Bounds, sceneCenter, sceneRadius);
  BoundingSphere(focusBounds, focusCenter, focusRadius);
  // A flat or point-like focus still needs a non-empty frustum.
  sceneRadius = std::max(sceneRadius,
    1e-6 *
      std::max(
        1.0, std::abs(sceneCenter[0]) + std::abs(sceneCenter[1]) + std::abs(sceneCenter[2])));
  focusRadius = std::max(focusRadius, 1e-3 * sceneRadius);
  const Vec3 offset{ { focusCenter[0] - sceneCenter[0], focusCenter[1] - sceneCenter[1],
    focusCenter[2] - sceneCenter[2] } };
  // Radius around the focus centre that holds the whole scene.
  const double reach = std::sqrt(Dot(offset, offset)) + sceneRadius;

  view.perspective = light.type != Light::Type::Directional;
  if (view.perspective)
  {
    AimPerspective(view, light, focusCenter, focusRadius, sceneCenter, sceneRadius);
  }
  else
  {
    AimOrthographic(view, light, focusCenter, focusRadius, reach);
  }
  SetViewTransforms(view);
  return view;
}
}

namespace
{
/**
 * Narrows an orthographic view to the rectangle around the box's outline across it,
 * instead of the box's bounding sphere: a sheet seen obliquely fills its frustum.
 * The rectangle is at most `maximumAspect` times longer than it is wide (1: a
 * square); its longer side is the outline's, so it never holds less than the square.
 */
void FitOrthographic(LightView& view, const double box[6], double maximumAspect)
{
  const double infinity = std::numeric_limits<double>::infinity();
  double low[2] = { infinity, infinity };
  double high[2] = { -infinity, -infinity };
  for (int c = 0; c < 8; ++c)
  {
    const Vec3 offset{ { box[c & 1] - view.eye[0], box[2 + ((c >> 1) & 1)] - view.eye[1],
      box[4 + ((c >> 2) & 1)] - view.eye[2] } };
    const double across[2] = { Dot(offset, view.right), Dot(offset, view.up) };
    for (int k = 0; k < 2; ++k)
    {
      low[k] = std::min(low[k], across[k]);
      high[k] = std::max(high[k], across[k]);
    }
  }
  const double halfRight = 0.5 * (high[0] - low[0]) * 1.0001;
  const double halfUp = 0.5 * (high[1] - low[1]) * 1.0001;
  const double half = std::max(halfRight, halfUp);
  if (!(half > 0.0) || !(half < view.halfExtent))
  {
    return;
  }
  // Each side at least the outline's and at least 1/maximumAspect of the other.
  const double aspect = std::max(1.0, std::min(maximumAspect, LightView::MaximumAspect));
  const double right = std::max(halfRight, halfUp / aspect);
  const double up = std::max(halfUp, halfRight / aspect);
  for (int i = 0; i < 3; ++i)
  {
    view.eye[i] += 0.5 * (low[0] + high[0]) * view.right[i] + 0.5 * (low[1] + high[1]) * view.up[i];
  }
  view.halfExtent = right;
  view.aspect = up / right;
  SetViewTransforms(view);
}

/**
 * Narrows a perspective view to the square frustum around the box's corners as the
 * light sees them, when that is narrower than the view (a view subtends its focus's
 * bounding sphere, or, with the light inside that sphere, the widest frustum: a
 * lamp above the floor then spreads 512 texels over 75 degrees of it). Nothing
 * changes when some corner is not in front of the light, or the frustum would be
 * wider than the view or 75 degrees off axis.
 */
void FitPerspective(LightView& view, const double box[6])
{
  std::array<Vec3, 8> toCorners;
  Vec3 mean{ { 0, 0, 0 } };
  for (int c = 0; c < 8; ++c)
  {
    toCorners[c] = { { box[c & 1] - view.eye[0], box[2 + ((c >> 1) & 1)] - view.eye[1],
      box[4 + ((c >> 2) & 1)] - view.eye[2] } };
    const Vec3 unit = Normalize(toCorners[c]);
    for (int i = 0; i < 3; ++i)
    {
      mean[i] += unit[i];
    }
  }
  // The axis moves to the middle of the corners' angles on each side, a few times
  // (each move changes the extent); the narrowest frustum found is kept.
  LightView fitted = view;
  fitted.axis = Normalize(mean);
  Vec3 bestAxis = fitted.axis;
  double half = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 8; ++pass)
  {
    SetViewTransforms(fitted); // the basis of the current axis
    double low[2] = { std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity() };
    double high[2] = { -low[0], -low[1] };
    bool inFront = true;
    for (const Vec3& v : toCorners)
    {
      const double depth = Dot(v, fitted.axis);
      inFront = inFront && depth > 1e-9 * std::sqrt(Dot(v, v));
      const double across[2] = { Dot(v, fitted.right) / depth, Dot(v, fitted.up) / depth };
      for (int k = 0; k < 2; ++k)
      {
        low[k] = std::min(low[k], across[k]);
        high[k] = std::max(high[k], across[k]);
      }
    }
    if (!inFront)
    {
      break; // a corner beside or behind the light from this axis
    }
    const double extent = std::max({ high[0], -low[0], high[1], -low[1] });
    if (extent < half)
    {
      half = extent;
      bestAxis = fitted.axis;
    }
    const double middle[2] = { std::tan(0.5 * (std::atan(low[0]) + std::atan(high[0]))),
      std::tan(0.5 * (std::atan(low[1]) + std::atan(high[1]))) };
    for (int i = 0; i < 3; ++i)
    {
      fitted.axis[i] += middle[0] * fitted.right[i] + middle[1] * fitted.up[i];
    }
    fitted.axis = Normalize(fitted.axis);
  }
  fitted.axis = bestAxis;
  const double widest = std::tan(MaximumPerspectiveHalfAngle);
  half *= 1.0001;
  if (!(half > 0.0) || !(half < view.halfExtent) || !(half <= widest))
  {
    return;
  }
  fitted.halfExtent = half;
  fitted.aspect = 1.0;
  fitted.clamped = false; // it holds the whole box now
  SetViewTransforms(fitted);
  if (fitted.valid)
  {
    view = fitted;
  }
}
}

LightView ComputeLightView(const SceneData& scene, int index, LightView::Focus focus)
{
  if (index < 0 || index >= static_cast<int>(scene.Lights.size()) || scene.Meshes.empty())
  {
    LightView view;
    view.light = index;
    return view;
  }
  if (focus == LightView::Focus::SeenSpecular)
  {
    double seen[6];
    const bool narrowed = PhotonFocusBounds(scene, index, seen);
    LightView view = AimLightView(scene, scene.Lights[index], index, seen);
    if (narrowed && !view.perspective && view.valid)
    {
      FitOrthographic(view, seen, LightView::MaximumAspect);
    }
    return view;
  }
  const bool specular = focus == LightView::Focus::Specular && scene.HasSpecular;
  return AimLightView(
    scene, scene.Lights[index], index, specular ? scene.SpecularBounds : scene.Bounds);
}

void OffsetLightView(LightView& view, double u, double v, int resolution)
{
  if (!view.valid || resolution < 1 || !(std::abs(u) <= 0.5) || !(std::abs(v) <= 0.5) ||
    (u == 0.0 && v == 0.0))
  {
    return;
  }
  // One texel: 2 halfExtent / resolution (times aspect along up), in metres
  // (orthographic) or in the tangent of the angle off the axis (perspective).
  const double step = 2.0 * view.halfExtent / resolution;
  const double stepUp = 2.0 * view.HalfExtentUp() / resolution;
  const Vec3 across{ { u * step * view.right[0] + v * stepUp * view.up[0],
    u * step * view.right[1] + v * stepUp * view.up[1],
    u * step * view.right[2] + v * stepUp * view.up[2] } };
  if (view.perspective)
  {
    view.axis = Normalize(
      Vec3{ { view.axis[0] + across[0], view.axis[1] + across[1], view.axis[2] + across[2] } });
  }
  else
  {
    for (int i = 0; i < 3; ++i)
    {
      view.eye[i] += across[i];
    }
  }
  SetViewTransforms(view);
}

Role MeshRole(const SceneData& scene, const Mesh& mesh)
{
  return mesh.material >= 0 && mesh.material < static_cast<int>(scene.Materials.size())
    ? scene.Materials[mesh.material].role
    : Role::None;
}

std::vector<std::tuple<unsigned long, int, int>> MeshKey(const SceneData& scene)
{
  std::vector<std::tuple<unsigned long, int, int>> key;
  key.reserve(scene.Meshes.size());
  for (const Mesh& mesh : scene.Meshes)
  {
    key.emplace_back(mesh.version, mesh.material, static_cast<int>(MeshRole(scene, mesh)));
  }
  return key;
}

bool LightReachesSpecular(const Light& light, const double specularBounds[6])
{
  if (!(light.radiometric[0] > 0.0 || light.radiometric[1] > 0.0 || light.radiometric[2] > 0.0))
  {
    return false;
  }
  if (light.type != Light::Type::Spot || light.cosOuter <= -1.0)
  {
    return true;
  }
  const double* sb = specularBounds;
  double v[3], radius2 = 0.0, distance2 = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    v[c] = 0.5 * (sb[2 * c] + sb[2 * c + 1]) - light.position[c];
    radius2 += 0.25 * (sb[2 * c + 1] - sb[2 * c]) * (sb[2 * c + 1] - sb[2 * c]);
    distance2 += v[c] * v[c];
  }
  if (distance2 <= radius2)
  {
    return true; // the light is inside the bounding sphere
  }
  const double distance = std::sqrt(distance2);
  const double cosAxis =
    (v[0] * light.direction[0] + v[1] * light.direction[1] + v[2] * light.direction[2]) / distance;
  const double axisAngle = std::acos(std::max(-1.0, std::min(1.0, cosAxis)));
  const double sphereAngle = std::asin(std::min(1.0, std::sqrt(radius2) / distance));
  return axisAngle - sphereAngle < std::acos(std::max(-1.0, std::min(1.0, light.cosOuter)));
}

bool RefractorsInLine(const SceneData& scene, int index, int& first, int& second)
{
  first = second = -1;
  if (index < 0 || index >= static_cast<int>(scene.Lights.size()))
  {
    return false;
  }
  const Light& light = scene.Lights[index];
  if (!(light.radiometric[0] > 0.0 || light.radiometric[1] > 0.0 || light.radiometric[2] > 0.0))
  {
    return false;
  }
  std::vector<int> refractors;
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    if (MeshRole(scene, scene.Meshes[m]) == Role::Refractor)
    {
      refractors.push_back(static_cast<int>(m));
    }
  }
  if (refractors.size() < 2)
  {
    return false; // a frame's check: no vertex scan for a scene with one piece of glass
  }
  struct Sphere
  {
    int mesh;
    Vec3 centre;
    double radius;
  };
  std::vector<Sphere> spheres;
  for (const int m : refractors)
  {
    const double inf = std::numeric_limits<double>::infinity();
    double box[6] = { inf, -inf, inf, -inf, inf, -inf };
    GrowBounds(scene.Meshes[m], box);
    if (box[0] <= box[1] && box[2] <= box[3] && box[4] <= box[5])
    {
      Sphere sphere{ m, {}, 0.0 };
      BoundingSphere(box, sphere.centre, sphere.radius);
      spheres.push_back(sphere);
    }
  }
  const bool directional = light.type == Light::Type::Directional;
  const Vec3 along = Normalize(light.direction);
  // How far along the light's rays: the nearer sphere is met first.
  auto depth = [&](const Sphere& s)
  {
    const Vec3 v{ { s.centre[0] - light.position[0], s.centre[1] - light.position[1],
      s.centre[2] - light.position[2] } };
    return directional ? Dot(s.centre, along) : std::sqrt(Dot(v, v));
  };
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    for (std::size_t j = i + 1; j < spheres.size(); ++j)
    {
      const Sphere& a = spheres[i];
      const Sphere& b = spheres[j];
      bool inLine;
      if (directional)
      {
        Vec3 apart{ { b.centre[0] - a.centre[0], b.centre[1] - a.centre[1],
          b.centre[2] - a.centre[2] } };
        const double ahead = Dot(apart, along);
        for (int k = 0; k < 3; ++k)
        {
          apart[k] -= ahead * along[k];
        }
        inLine = std::sqrt(Dot(apart, apart)) < a.radius + b.radius;
      }
      else
      {
        const Vec3 toA{ { a.centre[0] - light.position[0], a.centre[1] - light.position[1],
          a.centre[2] - light.position[2] } };
        const Vec3 toB{ { b.centre[0] - light.position[0], b.centre[1] - light.position[1],
          b.centre[2] - light.position[2] } };
        const double da = std::sqrt(Dot(toA, toA)), db = std::sqrt(Dot(toB, toB));
        if (!(da > a.radius) || !(db > b.radius))
        {
          inLine = true; // the light is inside one of them
        }
        else
        {
          const double cosine = Dot(toA, toB) / (da * db);
          const double apart = std::acos(std::max(-1.0, std::min(1.0, cosine)));
          inLine = apart < std::asin(a.radius / da) + std::asin(b.radius / db);
        }
      }
      if (inLine)
      {
        const bool aFirst = depth(a) <= depth(b);
        first = aFirst ? a.mesh : b.mesh;
        second = aFirst ? b.mesh : a.mesh;
        return true;
      }
    }
  }
  return false;
}

namespace
{
/** The point of triangle (a, b, c) nearest to p (Ericson, Real-Time Collision Detection 5.1.5). */
Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  auto sub = [](const Vec3& u, const Vec3& v) { return Vec3{ { u[0] - v[0], u[1] - v[1], u[2] - v[2] } }; };
  auto along = [](const Vec3& o, const Vec3& d, double t) {
    return Vec3{ { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] } };
  };
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return a;
  }
  const Vec3 bp = sub(p, b);
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    return along(a, ab, d1 / (d1 - d3));
  }
  const Vec3 cp = sub(p, c);
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    return along(a, ac, d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
  {
    return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denominator = 1.0 / (va + vb + vc);
  return along(along(a, ab, vb * denominator), ac, vc * denominator);
}

/** A receiver triangle met by the incidence search: where, and its unit normal. */
struct Candidate
{
  double key = std::numeric_limits<double>::infinity(); // hit distance or squared distance
  Vec3 point{ { 0, 0, 0 } };
  Vec3 normal{ { 0, 1, 0 } };
};
}

ReceiverIncidence FindReceiverIncidence(const SceneData& scene, int index, const double* focus)
{
  ReceiverIncidence result;
  if (!scene.HasSpecular || index < 0 || index >= static_cast<int>(scene.Lights.size()))
  {
    return result;
  }
  const Light& light = scene.Lights[index];
  const double* sb = focus ? focus : scene.SpecularBounds;
  const Vec3 origin{ { 0.5 * (sb[0] + sb[1]), 0.5 * (sb[2] + sb[3]), 0.5 * (sb[4] + sb[5]) } };
  Vec3 direction = Normalize(light.direction);
  if (light.type != Light::Type::Directional)
  {
    const Vec3 away{ { origin[0] - light.position[0], origin[1] - light.position[1],
      origin[2] - light.position[2] } };
    const double length = std::sqrt(Dot(away, away));
    if (!(length > 1e-9 * std::max(1.0, scene.Scale())))
    {
      return result; // at the centre: light leaves towards every side
    }
    direction = Vec3{ { away[0] / length, away[1] / length, away[2] / length } };
  }
  result.direction = direction;
  // The receiver the light's central ray meets first past the specular centre, or
  // failing that (the ray runs past every receiver: a grazing sun beyond the floor's
  // edge) the receiver nearest to that centre.
  Candidate hit, nearest;
  for (const Mesh& mesh : scene.Meshes)
  {
    if (scene.Materials[mesh.material].role != Role::Receiver)
    {
      continue;
    }
    const std::vector<float>& p = mesh.positions;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    {
      const std::size_t i0 = 3 * std::size_t{ mesh.indices[t] };
      const std::size_t i1 = 3 * std::size_t{ mesh.indices[t + 1] };
      const std::size_t i2 = 3 * std::size_t{ mesh.indices[t + 2] };
      if (std::max(i0, std::max(i1, i2)) + 2 >= p.size())
      {
        continue;
      }
      const Vec3 a{ { p[i0], p[i0 + 1], p[i0 + 2] } };
      const Vec3 b{ { p[i1], p[i1 + 1], p[i1 + 2] } };
      const Vec3 c{ { p[i2], p[i2 + 1], p[i2 + 2] } };
      const Vec3 e1{ { b[0] - a[0], b[1] - a[1], b[2] - a[2] } };
      const Vec3 e2{ { c[0] - a[0], c[1] - a[1], c[2] - a[2] } };
      const Vec3 normal = Cross(e1, e2);
      const double area2 = std::sqrt(Dot(normal, normal));
      if (!(area2 > 0.0) || !std::isfinite(area2))
      {
        continue; // degenerate or NaN: no surface to meet
      }
      const Vec3 unit{ { normal[0] / area2, normal[1] / area2, normal[2] / area2 } };
      const Vec3 closest = ClosestPointOnTriangle(origin, a, b, c);
      const Vec3 gap{ { closest[0] - origin[0], closest[1] - origin[1], closest[2] - origin[2] } };
      const double distance2 = Dot(gap, gap);
      if (distance2 < nearest.key)
      {
        nearest = Candidate{ distance2, closest, unit };
      }
      // Moller-Trumbore; a ray in the triangle's plane misses it.
      const Vec3 q = Cross(direction, e2);
      const double det = Dot(e1, q);
      if (!(std::abs(det) > 1e-12 * area2))
      {
        continue;
      }
      const Vec3 toOrigin{ { origin[0] - a[0], origin[1] - a[1], origin[2] - a[2] } };
      const double u = Dot(toOrigin, q) / det;
      const Vec3 r = Cross(toOrigin, e1);
      const double v = Dot(direction, r) / det;
      const double distance = Dot(e2, r) / det;
      if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && distance > 0.0 && distance < hit.key)
      {
        hit = Candidate{ distance,
          Vec3{ { origin[0] + distance * direction[0], origin[1] + distance * direction[1],
            origin[2] + distance * direction[2] } },
          unit };
      }
    }
  }
  const Candidate& met = std::isfinite(hit.key) ? hit : nearest;
  if (!std::isfinite(met.key))
  {
    result.angle = -1.0; // no receiver
    return result;
  }
  result.found = true;
  result.point = met.point;
  const double along = Dot(met.normal, direction);
  // Facing the light: the light travels against the normal.
  result.normal = along > 0.0 ? Vec3{ { -met.normal[0], -met.normal[1], -met.normal[2] } } : met.normal;
  result.angle = std::asin(std::min(1.0, std::abs(along))) * 180.0 / 3.14159265358979323846;
  return result;
}

double ReceiverIncidenceAngle(const SceneData& scene, int index)
{
  return FindReceiverIncidence(scene, index).angle;
}

namespace
{
/** Rotates v about the unit axis k by `angle` radians (Rodrigues). */
Vec3 Rotate(const Vec3& v, const Vec3& k, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle), kv = Dot(k, v);
  const Vec3 kxv = Cross(k, v);
  Vec3 out;
  for (int i = 0; i < 3; ++i)
  {
    out[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1.0 - c);
  }
  return out;
}

/** Clips the convex polygon `polygon` to the half-space plane . (x, 1) >= 0 (Sutherland-Hodgman). */
std::vector<Vec3> ClipPolygon(const std::vector<Vec3>& polygon, const double plane[4])
{
  std::vector<Vec3> out;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % n];
    const double da = plane[0] * a[0] + plane[1] * a[1] + plane[2] * a[2] + plane[3];
    const double db = plane[0] * b[0] + plane[1] * b[1] + plane[2] * b[2] + plane[3];
    if (da >= 0.0)
    {
      out.push_back(a);
    }
    if ((da >= 0.0) != (db >= 0.0))
    {
      const double t = da / (da - db);
      out.push_back(Vec3{ { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]) } });
    }
  }
  return out;
}
}

bool VisibleBounds(const SceneData& scene, double box[6])
{
  std::copy(scene.Bounds, scene.Bounds + 6, box);
  const double* m = scene.View.worldToClip;
  // The clip volume's six planes, -w <= x, y, z <= w, as rows of worldToClip.
  double planes[6][4];
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int c = 0; c < 4; ++c)
    {
      planes[2 * axis][c] = m[12 + c] + m[4 * axis + c];
      planes[2 * axis + 1][c] = m[12 + c] - m[4 * axis + c];
    }
  }
  // The intersection's vertices lie on the box's faces (the faces clipped by the
  // planes) or are corners of the clip volume inside the box.
  const double* b = scene.Bounds;
  std::vector<Vec3> vertices;
  for (int axis = 0; axis < 3; ++axis)
  {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
    {
      std::vector<Vec3> face(4);
      const double corners[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
      for (int k = 0; k < 4; ++k)
      {
        face[k][axis] = b[2 * axis + side];
        face[k][u] = b[2 * u + static_cast<int>(corners[k][0])];
        face[k][v] = b[2 * v + static_cast<int>(corners[k][1])];
      }
      for (int plane = 0; plane < 6 && !face.empty(); ++plane)
      {
        face = ClipPolygon(face, planes[plane]);
      }
      vertices.insert(vertices.end(), face.begin(), face.end());
    }
  }
  for (int c = 0; c < 8; ++c)
  {
    const double ndc[4] = { (c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0, 1.0 };
    double world[4];
    Transform(scene.View.clipToWorld, ndc, world);
    if (!(world[3] > 0.0))
    {
      continue;
    }
    const Vec3 x{ { world[0] / world[3], world[1] / world[3], world[2] / world[3] } };
    if (x[0] >= b[0] && x[0] <= b[1] && x[1] >= b[2] && x[1] <= b[3] && x[2] >= b[4] && x[2] <= b[5])
    {
      vertices.push_back(x);
    }
  }
  double seen[6] = { std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  for (const Vec3& x : vertices)
  {
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      // Clipping rounds: stay inside the scene's box.
      seen[2 * k] = std::max(b[2 * k], std::min(seen[2 * k], x[k]));
      seen[2 * k + 1] = std::min(b[2 * k + 1], std::max(seen[2 * k + 1], x[k]));
    }
  }
  if (!(seen[0] <= seen[1] && seen[2] <= seen[3] && seen[4] <= seen[5]))
  {
    return false;
  }
  std::copy(seen, seen + 6, box);
  return true;
}

void GrowBounds(const Mesh& mesh, double box[6])
{
  for (std::size_t i = 0; i + 2 < mesh.positions.size(); i += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double x = mesh.positions[i + k];
      if (std::isfinite(x))
      {
        box[2 * k] = std::min(box[2 * k], x);
        box[2 * k + 1] = std::max(box[2 * k + 1], x);
      }
    }
  }
}

void ReceiverBounds(const SceneData& scene, double box[6])
{
  const double inf = std::numeric_limits<double>::infinity();
  std::fill(box, box + 6, inf);
  box[1] = box[3] = box[5] = -inf;
  for (const Mesh& mesh : scene.Meshes)
  {
    if (MeshRole(scene, mesh) == Role::Receiver)
    {
      GrowBounds(mesh, box);
    }
  }
}

double WindingNumber(const Mesh& mesh, const double point[3])
{
  const glm::dvec3 x(point[0], point[1], point[2]);
  const std::size_t vertices = mesh.positions.size() / 3;
  double sum = 0.0;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
  {
    glm::dvec3 v[3];
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k)
    {
      const std::size_t index = mesh.indices[i + k];
      ok = index < vertices;
      if (ok)
      {
        v[k] = glm::dvec3(mesh.positions[3 * index], mesh.positions[3 * index + 1],
                 mesh.positions[3 * index + 2]) -
          x;
        ok = std::isfinite(v[k].x) && std::isfinite(v[k].y) && std::isfinite(v[k].z);
      }
    }
    if (!ok)
    {
      continue;
    }
    const double l0 = glm::length(v[0]), l1 = glm::length(v[1]), l2 = glm::length(v[2]);
    const double triple = glm::dot(v[0], glm::cross(v[1], v[2]));
    const double denominator = l0 * l1 * l2 + glm::dot(v[0], v[1]) * l2 +
      glm::dot(v[0], v[2]) * l1 + glm::dot(v[1], v[2]) * l0;
    sum += 2.0 * std::atan2(triple, denominator);
  }
  return sum / (4.0 * glm::pi<double>());
}

double VisibleScale(const SceneData& scene, const double* specular)
{
  double seen[6];
  VisibleBounds(scene, seen);
  if (scene.HasSpecular)
  {
    const double* box = specular ? specular : scene.SpecularBounds;
    for (int k = 0; k < 3; ++k)
    {
      seen[2 * k] = std::min(seen[2 * k], box[2 * k]);
      seen[2 * k + 1] = std::max(seen[2 * k + 1], box[2 * k + 1]);
    }
  }
  return Diagonal(seen);
}

double VisibleOverSpecular(const SceneData& scene)
{
  const double specular = scene.HasSpecular ? Diagonal(scene.SpecularBounds) : 0.0;
  return specular > 0.0 ? VisibleScale(scene) / specular : 0.0;
}

LightView ComputeReceiverMapView(const SceneData& scene, int index,
  const ReceiverIncidence& incidence, double minimumIncidence, const double* photonFocus)
{
  if (index < 0 || index >= static_cast<int>(scene.Lights.size()) || scene.Meshes.empty())
  {
    LightView view;
    view.light = index;
    return view;
  }
  double focus[6];
  VisibleBounds(scene, focus);
  Light light = scene.Lights[index];
  if (incidence.found && incidence.angle < minimumIncidence)
  {
    // Turn the light about the receiver point, in the plane of its direction and
    // the receiver's normal, until its direction meets the surface at the minimum.
    const Vec3& d = incidence.direction;
    Vec3 axis = Cross(d, Vec3{ { -incidence.normal[0], -incidence.normal[1], -incidence.normal[2] } });
    const double length = std::sqrt(Dot(axis, axis));
    if (length > 1e-12)
    {
      axis = Vec3{ { axis[0] / length, axis[1] / length, axis[2] / length } };
    }
    else
    {
      // The light along the normal meets the surface at 90 degrees, more than any
      // minimum; only rounding gets here, and any axis in the surface will do.
      axis = Normalize(Cross(incidence.normal, Vec3{ { 1, 0, 0 } }));
    }
    const double turn = (minimumIncidence - incidence.angle) * 3.14159265358979323846 / 180.0;
    light.direction = Normalize(Rotate(light.direction, axis, turn));
    if (light.type != Light::Type::Directional)
    {
      const Vec3 fromPoint{ { light.position[0] - incidence.point[0],
        light.position[1] - incidence.point[1], light.position[2] - incidence.point[2] } };
      const Vec3 turned = Rotate(fromPoint, axis, turn);
      for (int i = 0; i < 3; ++i)
      {
        light.position[i] = incidence.point[i] + turned[i];
      }
    }
  }
  LightView view = AimLightView(scene, light, index, focus);
  if (!view.valid || !view.perspective || scene.Participating.enabled)
  {
    // A directional light's map keeps the seen box's sphere; with a medium the
    // photons' paths are seen beyond where they land: the sphere or cone stays.
    return view;
  }
  // A lamp in the scene (inside the seen box's sphere) would otherwise spread the map
  // over 75 degrees, most of it beside what the camera sees. The map holds the
  // receivers photons land on and the mirrors they meet on the way (the caustic
  // maps' trace searches both in it): the receivers the camera sees (the corners of
  // the whole seen box, the glass over the floor, would widen the frustum towards
  // 75 degrees).
  const double inf = std::numeric_limits<double>::infinity();
  double fit[6];
  double receivers[6];
  ReceiverBounds(scene, receivers);
  for (int k = 0; k < 3; ++k)
  {
    fit[2 * k] = std::max(receivers[2 * k], focus[2 * k]);
    fit[2 * k + 1] = std::min(receivers[2 * k + 1], focus[2 * k + 1]);
  }
  if (!(fit[0] <= fit[1] && fit[2] <= fit[3] && fit[4] <= fit[5]))
  {
    std::copy(focus, focus + 6, fit); // no receiver in view: what the camera sees
  }
  for (const Mesh& mesh : scene.Meshes)
  {
    if (MeshRole(scene, mesh) != Role::Reflector)
    {
      continue;
    }
    double own[6] = { inf, -inf, inf, -inf, inf, -inf };
    GrowBounds(mesh, own);
    bool meets = true;
    for (int k = 0; photonFocus && k < 3; ++k)
    {
      meets = meets && own[2 * k] <= photonFocus[2 * k + 1] && own[2 * k + 1] >= photonFocus[2 * k];
    }
    for (int k = 0; meets && k < 3; ++k)
    {
      fit[2 * k] = std::min(fit[2 * k], own[2 * k]);
      fit[2 * k + 1] = std::max(fit[2 * k + 1], own[2 * k + 1]);
    }
  }
  FitPerspective(view, fit);
  return view;
}

double Medium::MeanDensity() const
{
  return this->density ? this->density->GetMeanDensity() : 1.0;
}

Vec3 Medium::MeanSigmaS() const
{
  const double mean = this->MeanDensity();
  return { { this->sigmaS[0] * mean, this->sigmaS[1] * mean, this->sigmaS[2] * mean } };
}

Vec3 Medium::MeanSigmaT() const
{
  const double mean = this->MeanDensity();
  return { { (this->sigmaS[0] + this->sigmaA[0]) * mean,
    (this->sigmaS[1] + this->sigmaA[1]) * mean, (this->sigmaS[2] + this->sigmaA[2]) * mean } };
}

double SceneData::Scale() const
{
  return Diagonal(this->Bounds);
}
}
