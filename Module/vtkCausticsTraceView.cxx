#include "vtkCausticsTraceView.h"

#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace caustics
{
namespace
{
/** The 8 corners of an axis-aligned box (xmin, xmax, ymin, ymax, zmin, zmax). */
void Corners(const double bounds[6], glm::dvec3 corners[8])
{
  for (int c = 0; c < 8; ++c)
  {
    corners[c] = glm::dvec3(bounds[(c & 1) ? 1 : 0], bounds[(c & 2) ? 3 : 2], bounds[(c & 4) ? 5 : 4]);
  }
}

glm::dvec4 Transform(const double rowMajor[16], const glm::dvec4& p)
{
  glm::dvec4 q;
  for (int r = 0; r < 4; ++r)
  {
    q[r] = rowMajor[4 * r] * p.x + rowMajor[4 * r + 1] * p.y + rowMajor[4 * r + 2] * p.z +
      rowMajor[4 * r + 3] * p.w;
  }
  return q;
}

/** The box the fitted view must hold: specular actors and the scene the camera sees. */
void FittedBox(const SceneData& scene, double box[6])
{
  // The camera's frustum (its 8 clip-space corners in the world), cut to the scene.
  double seen[6] = { std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(), -std::numeric_limits<double>::max() };
  for (int c = 0; c < 8; ++c)
  {
    const glm::dvec4 ndc((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0, 1.0);
    const glm::dvec4 w = Transform(scene.View.clipToWorld, ndc);
    for (int k = 0; k < 3; ++k)
    {
      const double x = w.w != 0.0 ? w[k] / w.w : 0.0;
      seen[2 * k] = std::min(seen[2 * k], x);
      seen[2 * k + 1] = std::max(seen[2 * k + 1], x);
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    const double low = std::max(seen[2 * k], scene.Bounds[2 * k]);
    const double high = std::min(seen[2 * k + 1], scene.Bounds[2 * k + 1]);
    // An empty cut (the camera sees none of the scene) leaves the specular box alone.
    box[2 * k] = low <= high ? std::min(low, scene.SpecularBounds[2 * k]) : scene.SpecularBounds[2 * k];
    box[2 * k + 1] =
      low <= high ? std::max(high, scene.SpecularBounds[2 * k + 1]) : scene.SpecularBounds[2 * k + 1];
  }
}

/** A fitted view from its world-to-clip matrix. */
TraceView FromMatrices(const glm::dmat4& worldToClip)
{
  TraceView traced;
  const glm::dmat4 clipToWorld = glm::inverse(worldToClip);
  const double* a = glm::value_ptr(worldToClip); // column-major already
  const double* b = glm::value_ptr(clipToWorld);
  std::transform(a, a + 16, traced.WorldToClip, [](double v) { return static_cast<float>(v); });
  std::transform(b, b + 16, traced.ClipToWorld, [](double v) { return static_cast<float>(v); });
  traced.Fitted = true;
  return traced;
}

/** Orthographic, along the camera's direction, holding the box, square pixels. */
TraceView FitOrthographic(const SceneData& scene, const double box[6], int width, int height)
{
  const Camera& camera = scene.View;
  glm::dvec3 forward(camera.focalPoint[0] - camera.position[0],
    camera.focalPoint[1] - camera.position[1], camera.focalPoint[2] - camera.position[2]);
  forward = glm::length(forward) > 0.0 ? glm::normalize(forward) : glm::dvec3(0, 0, -1);
  glm::dvec3 up(camera.viewUp[0], camera.viewUp[1], camera.viewUp[2]);
  up -= glm::dot(up, forward) * forward;
  if (!(glm::length(up) > 1e-9))
  {
    up = std::abs(forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    up -= glm::dot(up, forward) * forward;
  }
  up = glm::normalize(up);
  const glm::dvec3 right = glm::cross(forward, up);

  glm::dvec3 low(std::numeric_limits<double>::max()), high(-std::numeric_limits<double>::max());
  glm::dvec3 corners[8];
  Corners(box, corners);
  for (const glm::dvec3& p : corners)
  {
    const glm::dvec3 q(glm::dot(p, right), glm::dot(p, up), glm::dot(p, forward));
    low = glm::min(low, q);
    high = glm::max(high, q);
  }
  // A margin of two pixels and 1 % of the depth, so surfaces on the box are inside.
  const double pixel = std::max((high.x - low.x) / width, (high.y - low.y) / height);
  const double halfWidth = 0.5 * pixel * width + 2.0 * pixel;
  const double halfHeight = 0.5 * pixel * height + 2.0 * pixel;
  const double depth = std::max(high.z - low.z, 1e-6 * std::max(halfWidth, halfHeight));
  const double margin = 0.01 * depth + 1e-9;
  const glm::dvec3 centre = 0.5 * (low.x + high.x) * right + 0.5 * (low.y + high.y) * up;
  const glm::dvec3 eye = centre + (low.z - margin) * forward;
  const glm::dmat4 view = glm::lookAt(eye, eye + forward, up);
  const glm::dmat4 projection =
    glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, 0.0, depth + 2.0 * margin);
  TraceView traced = FromMatrices(projection * view);
  traced.ViewOrigin[0] = forward.x;
  traced.ViewOrigin[1] = forward.y;
  traced.ViewOrigin[2] = forward.z;
  traced.ViewOrigin[3] = 0.0;
  return traced;
}

TraceView CameraView(const Camera& camera)
{
  TraceView traced;
  gl::ToColumnMajor(camera.worldToClip, traced.WorldToClip);
  gl::ToColumnMajor(camera.clipToWorld, traced.ClipToWorld);
  if (camera.parallel)
  {
    glm::dvec3 axis(camera.focalPoint[0] - camera.position[0],
      camera.focalPoint[1] - camera.position[1], camera.focalPoint[2] - camera.position[2]);
    axis = glm::length(axis) > 0.0 ? glm::normalize(axis) : glm::dvec3(0.0);
    traced.ViewOrigin[0] = axis.x;
    traced.ViewOrigin[1] = axis.y;
    traced.ViewOrigin[2] = axis.z;
    traced.ViewOrigin[3] = 0.0;
  }
  else
  {
    std::copy(camera.position.begin(), camera.position.end(), traced.ViewOrigin);
    traced.ViewOrigin[3] = 1.0;
  }
  return traced;
}
}

bool FrustumHoldsBox(const double worldToClip[16], const double bounds[6])
{
  glm::dvec3 corners[8];
  Corners(bounds, corners);
  for (const glm::dvec3& p : corners)
  {
    const glm::dvec4 c = Transform(worldToClip, glm::dvec4(p, 1.0));
    if (!(c.w > 0.0) || std::abs(c.x) > c.w || std::abs(c.y) > c.w || std::abs(c.z) > c.w)
    {
      return false;
    }
  }
  return true;
}

TraceView ChooseTraceView(const SceneData& scene, TraceViewMode mode, int width, int height)
{
  const bool fitted = mode == TraceViewMode::Fitted ||
    (mode == TraceViewMode::Automatic &&
      !FrustumHoldsBox(scene.View.worldToClip, scene.SpecularBounds));
  if (!fitted || width < 1 || height < 1)
  {
    return CameraView(scene.View);
  }
  double box[6];
  FittedBox(scene, box);
  return FitOrthographic(scene, box, width, height);
}
}
