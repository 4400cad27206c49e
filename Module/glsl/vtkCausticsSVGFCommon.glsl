// Shared by the SVGF steps (vtkCausticsSVGFDenoiser; Schied et al. 2017, cited by
// 002_97e66a5090de9b07.txt §3.3): which pixels carry caustic irradiance, their
// luminance, and the edge-stopping weights of the camera G-buffer
// (vtkCausticsGBuffer: position + material, normal + role).
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform readonly image2D gPosition; // xyz m, w = material (-1: none)
layout(rgba16f, binding = 1) uniform readonly image2D gNormal;   // xyz, w = role
uniform ivec2 size;        // pixels
uniform vec3 eye;          // the camera's position, m
uniform float pixelAngle;  // perspective: radians per pixel (0 for a parallel camera)
uniform float pixelSize;   // parallel: m per pixel (0 for a perspective camera)
uniform float sigmaDepth;  // plane distance over sigmaDepth x offset x footprint
uniform float sigmaNormal; // exponent of max(0, n.n')

// Caustic irradiance lives on receivers (caustics::Role::Receiver), nowhere else.
bool SVGFReceiver(ivec2 p)
{
  return imageLoad(gPosition, p).w >= 0.0 && abs(imageLoad(gNormal, p).w - 1.0) < 0.5;
}

bool SVGFInside(ivec2 p)
{
  return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, size));
}

// NaN compares false, infinities are beyond the bound: both are not finite.
bool SVGFFinite(vec4 v)
{
  return all(lessThanEqual(abs(v), vec4(3.0e38)));
}

float SVGFLuminance(vec3 c)
{
  return CausticsLuminance(c);
}

// World size of one pixel at x (m).
float SVGFFootprint(vec3 x)
{
  return pixelSize > 0.0 ? pixelSize : distance(x, eye) * pixelAngle;
}

// SVGF's depth and normal edge-stopping functions, with the plane distance of q
// from p's tangent plane in place of the clip depth difference along its gradient.
float SVGFGeometryWeight(vec3 xp, vec3 np, vec3 xq, vec3 nq, float offsetPixels)
{
  float wn = pow(max(0.0, dot(np, nq)), sigmaNormal);
  float dz = abs(dot(np, xq - xp));
  float wz = exp(-dz / (sigmaDepth * offsetPixels * SVGFFootprint(xp) + 1e-12));
  return wn * wz;
}
