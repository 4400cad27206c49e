// One point sprite per photon hit, sized to cover the photon's kernel disk on
// the receiver as the target view sees it.
// The landed photons (the photon record layout of vtkCausticsCommon.glsl).
uniform sampler2D hitPosition;  // xyz world, w > 0: a photon landed here
uniform sampler2D hitNormal;    // xyz receiver normal as modelled
uniform sampler2D hitFlux;      // rgb W
uniform sampler2D kernelRadius; // r: the kernel's radius (m)
uniform int hitWidth;
uniform mat4 worldToClip;
uniform vec2 viewport;
// The draw's viewport is wider than the target by a guard band on each side (the GL
// drops a point whose centre is outside the clip volume, vtkCausticsPhotonSplatter):
// clip x and y are scaled by target size / viewport size so that every point keeps its
// pixel.
uniform vec2 guardScale;
uniform float minimumRadiusPixels;
uniform float maximumRadiusPixels;
// Caustic triangles (vtkCausticsPhotonTriangleCommon.glsl): when on, a photon splats
// only the part of its flux its six triangles did not carry.
uniform bool triangles;
uniform usampler2D triangleMask; // bit t of a cell: its triangle t is valid
uniform ivec2 hitGridSize;

flat out vec3 splatCentre;
flat out vec3 splatNormal;
flat out vec3 splatFlux;
flat out float splatRadius;
flat out float splatHalfSet; // CausticsHalfSet of the photon

void Discard()
{
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume
  gl_PointSize = 1.0;
  splatRadius = 0.0;
}

// Valid triangles of `cell` among those named by `bits`; none outside the grid.
int ValidTriangles(ivec2 cell, uint bits)
{
  if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, hitGridSize)))
  {
    return 0;
  }
  return bitCount(texelFetch(triangleMask, cell, 0).r & bits);
}

// The share of a photon's flux that no caustic triangle carries: 1 - k/6, k of its
// six triangles valid (it is corner a of both triangles of its cell, b of triangle
// 0 of the cell to the left, c of triangle 1 of the cell below, d of both of the
// cell below-left).
float SplatShare(ivec2 texel)
{
  if (!triangles)
  {
    return 1.0;
  }
  int carried = ValidTriangles(texel, 3u) + ValidTriangles(texel - ivec2(1, 0), 1u) +
    ValidTriangles(texel - ivec2(0, 1), 2u) + ValidTriangles(texel - ivec2(1, 1), 3u);
  return 1.0 - float(carried) / 6.0;
}

vec2 ToPixels(vec3 p)
{
  vec4 clip = worldToClip * vec4(p, 1.0);
  return (clip.xy / clip.w * 0.5 + 0.5) * viewport;
}

void main()
{
  ivec2 texel = ivec2(gl_VertexID % hitWidth, gl_VertexID / hitWidth);
  vec4 position = texelFetch(hitPosition, texel, 0);
  vec3 normal = texelFetch(hitNormal, texel, 0).xyz;
  float radius = texelFetch(kernelRadius, texel, 0).r;
  vec3 flux = texelFetch(hitFlux, texel, 0).rgb * SplatShare(texel);
  vec4 clip = worldToClip * vec4(position.xyz, 1.0);
  if (position.w <= 0.0 || clip.w <= 0.0 || dot(flux, vec3(1.0)) <= 0.0 ||
    !(radius > 0.0))
  {
    Discard();
    return;
  }
  vec3 n = normalize(normal);
  vec3 e1, e2;
  CausticsTangents(n, e1, e2);
  float r = radius;
  vec2 centre = ToPixels(position.xyz);
  // The disk's image, an ellipse: the images of the two tangent radii, and its
  // semi-axes (the singular values of that 2 x 2 map).
  vec2 a = ToPixels(position.xyz + r * e1) - centre;
  vec2 b = ToPixels(position.xyz + r * e2) - centre;
  float squares = dot(a, a) + dot(b, b);
  float area = abs(a.x * b.y - a.y * b.x);
  float spread = sqrt(max(squares * squares - 4.0 * area * area, 0.0));
  float major = sqrt(0.5 * (squares + spread));
  float minor = sqrt(max(0.5 * (squares - spread), 0.0));
  if (!(major > 0.0) || isinf(major))
  {
    Discard();
    return;
  }
  // Keep every kernel at least a few pixels wide (else it falls between pixel
  // centres and its energy is lost) and bounded in cost; the kernel stays
  // normalized for the radius actually used. A disk the view sees obliquely (a floor
  // at a grazing angle) is narrower across than along: it is widened until its
  // narrow axis spans a pixel too, or its light fell between the rows (the bunny's
  // floor seen at 13 degrees at 128^2 pixels kept 0.72 of its caustic).
  float clamped = clamp(major, minimumRadiusPixels, maximumRadiusPixels);
  // (Up to the guard band around the view, 1.4143 maximumRadiusPixels: beyond that, at
  // glancing angles under 4 degrees, the narrow axis stays under a pixel.)
  clamped = max(clamped,
    min(major * min(1.0, minimumRadiusPixels) / max(minor, 1e-6 * major),
      1.4143 * maximumRadiusPixels));
  r *= clamped / major;
  splatCentre = position.xyz;
  splatNormal = n;
  splatFlux = flux;
  splatRadius = r;
  splatHalfSet = CausticsHalfSet(uint(gl_VertexID));
  gl_Position = vec4(clip.xy * guardScale, clip.zw);
  gl_PointSize = min(2.0 * clamped + 2.0, 1023.0); // the ellipse's square
}
