// Splat radius from the photon's neighbours (a per-photon radius rule for
// vtkCausticsPhotonSplatter). Where photons are sparse, a kernel of a couple of
// pixels would print the regular photon grid into the caustic (rings and dots of
// the light buffer's texels); the density of the photons that reached a receiver
// in the same bounce sets the radius instead:
// 1. the spacing vectors to the grid neighbours (central differences where both
//    neighbours landed, one-sided otherwise) give the receiver area per photon a,
//    and the radius is spacings x sqrt(a);
// 2. a photon without neighbours on both axes (e.g. the few that Russian roulette
//    sent down a weak branch) takes spacings x the distance to the nearest photon
//    of its branch in a 9 x 9 window: their density is that much lower;
// 3. the radius never falls below the pixel-footprint rule the transfer wrote.
// Neighbours count when they landed this bounce on the same surface side (normals
// within 25 degrees) in the same half of the grid (direct or Fresnel-reflected
// branch of the emitter).
layout(local_size_x = 16, local_size_y = 16) in;

// The landed photons (the photon record layout of vtkCausticsCommon.glsl) and
// their kernel radii.
layout(rgba32f, binding = 0) uniform readonly image2D splatPosition;
layout(rgba32f, binding = 1) uniform readonly image2D splatNormal;
layout(r32f, binding = 3) uniform image2D splatRadius;

uniform ivec2 grid;
uniform int branchRows; // rows of one emitter branch (N), grid.y when not split
uniform float spacings;

bool Neighbour(ivec2 q, int branch, vec3 n, out vec3 p)
{
  p = vec3(0.0);
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, grid)) || q.y / branchRows != branch)
  {
    return false;
  }
  vec4 position = imageLoad(splatPosition, q);
  if (!(position.w > 0.0) || dot(imageLoad(splatNormal, q).xyz, n) < 0.9)
  {
    return false;
  }
  p = position.xyz;
  return true;
}

// Spacing vector along one axis, or zero when no neighbour landed.
vec3 Spacing(ivec2 texel, ivec2 axis, int branch, vec3 x, vec3 n)
{
  vec3 a, b;
  bool hasA = Neighbour(texel - axis, branch, n, a);
  bool hasB = Neighbour(texel + axis, branch, n, b);
  if (hasA && hasB)
  {
    return 0.5 * (b - a);
  }
  return hasB ? b - x : (hasA ? x - a : vec3(0.0));
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, grid)))
  {
    return;
  }
  vec4 position = imageLoad(splatPosition, texel);
  if (!(position.w > 0.0) || !(spacings > 0.0))
  {
    return;
  }
  vec3 x = position.xyz;
  vec3 n = imageLoad(splatNormal, texel).xyz;
  int branch = texel.y / branchRows;
  vec3 ex = Spacing(texel, ivec2(1, 0), branch, x, n);
  vec3 ey = Spacing(texel, ivec2(0, 1), branch, x, n);
  float spacing = 0.0;
  if (dot(ex, ex) > 0.0 && dot(ey, ey) > 0.0)
  {
    spacing = sqrt(length(cross(ex, ey)));
  }
  else
  {
    float nearest = 3.0e38;
    for (int j = -4; j <= 4; ++j)
    {
      for (int i = -4; i <= 4; ++i)
      {
        vec3 p;
        if ((i != 0 || j != 0) && Neighbour(texel + ivec2(i, j), branch, n, p))
        {
          nearest = min(nearest, distance(p, x));
        }
      }
    }
    spacing = nearest < 3.0e38 ? nearest : 0.0;
  }
  float radius = max(imageLoad(splatRadius, texel).r, spacings * spacing);
  imageStore(splatRadius, texel, vec4(radius));
}
