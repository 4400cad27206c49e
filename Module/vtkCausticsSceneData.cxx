#include "vtkCausticsSceneData.h"

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

double SceneData::Scale() const
{
  const double dx = this->Bounds[1] - this->Bounds[0];
  const double dy = this->Bounds[3] - this->Bounds[2];
  const double dz = this->Bounds[5] - this->Bounds[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}
}
