#include "vtkCausticsSceneData.h"

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp> // For glm::make_mat4, glm::value_ptr

#include <algorithm>
#include <cmath>

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
  // Largest half angle a single frustum covers well (texel solid angles vary by
  // cos^3; beyond ~75 degrees the texels at the rim become useless).
  const double maxHalfAngle = 75.0 * 3.14159265358979323846 / 180.0;
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
    halfAngle = maxHalfAngle;
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
  view.clamped = halfAngle > maxHalfAngle || (inside && light.type != Light::Type::Spot);
  halfAngle = std::min(halfAngle, maxHalfAngle);
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
    projection[5] = 1.0 / e;
    projection[10] = -(f + n) / (f - n);
    projection[11] = -2.0 * f * n / (f - n);
    projection[14] = -1.0;
  }
  else
  {
    projection[0] = 1.0 / e;
    projection[5] = 1.0 / e;
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
    this->perspective ? this->FrustumSolidAngle() : 4.0 * this->halfExtent * this->halfExtent;
  return { { light.radiometric[0] * measure, light.radiometric[1] * measure,
    light.radiometric[2] * measure } };
}

double LightView::FrustumSolidAngle() const
{
  const double t2 = this->halfExtent * this->halfExtent;
  return 4.0 * std::atan(t2 / std::sqrt(1.0 + 2.0 * t2));
}

LightView ComputeLightView(const SceneData& scene, int index, LightView::Focus focus)
{
  LightView view;
  view.light = index;
  if (index < 0 || index >= static_cast<int>(scene.Lights.size()) || scene.Meshes.empty())
  {
    return view;
  }
  const Light& light = scene.Lights[index];
  Vec3 sceneCenter, focusCenter;
  double sceneRadius, focusRadius;
  BoundingSphere(scene.Bounds, sceneCenter, sceneRadius);
  if (focus == LightView::Focus::Specular && scene.HasSpecular)
  {
    BoundingSphere(scene.SpecularBounds, focusCenter, focusRadius);
  }
  else
  {
    focusCenter = sceneCenter;
    focusRadius = sceneRadius;
  }
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

double SceneData::Scale() const
{
  const double dx = this->Bounds[1] - this->Bounds[0];
  const double dy = this->Bounds[3] - this->Bounds[2];
  const double dz = this->Bounds[5] - this->Bounds[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}
}
