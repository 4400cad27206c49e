// Kernel radii from the spacing of the landed photons' grid neighbours
// (vtkCausticsPhotonSpacing, the shared stage a splatting transport runs before the
// splatter). A transport gives each landed photon a radius of its own (screen-space: a
// few pixel footprints; the impostor trace: a few spacings of the unoccluded beam).
// That is right where the specular surfaces focus the light, but where they spread it
// (the ball lens's halo, a low sun through the ball) photons one texel apart in the
// light land many spacings apart, and the splats print the photon grid into the
// caustic as dots and rings. Here the radius grows to `spacings` times the spacing of
// the photon's neighbours, never below the transport's:
// - neighbours are the four grid neighbours that landed on the same surface side
//   (normals within 25 degrees), in the same emission branch, and, with `stretch` > 0,
//   within `stretch` unoccluded spacings (the photon's footprint without the specular
//   surfaces: the record's measure, path length and cosine);
// - `estimate` AREA: the spacing vectors along the two grid axes (central differences
//   where both neighbours count, one-sided otherwise) span the receiver area per
//   photon, a, and the spacing is sqrt(a): sharp along folds, where the area is
//   small. For records of one bounce (screen-space), whose neighbours took the same
//   number of events;
// - `estimate` MEAN_DISTANCE: the mean distance to the neighbours that count. For
//   records of whole paths (the impostor trace), where a neighbour may have taken
//   another branch at a later event and the area between two such is no density;
// - a photon the estimate finds no neighbours for (AREA: not on both axes; their
//   neighbours took another Fresnel branch, roulette ended them, or it lies on the
//   lit region's edge) takes the distance to the nearest photon that counts in a
//   9 x 9 window: their density is that much lower.
// Splats are energy-normalized (vtkCausticsPhotonSplatter), so a radius changes how a
// photon's flux is spread, never how much there is.
layout(local_size_x = 16, local_size_y = 16) in;

// The landed photons in the record layout of vtkCausticsPhotonGrid.h, and their radii.
layout(rgba32f, binding = 0) uniform readonly image2D landedPosition;  // xyz, w > 0: landed
layout(rgba32f, binding = 1) uniform readonly image2D landedNormal;    // xyz, w = abs(N.D)
layout(rgba32f, binding = 2) uniform readonly image2D landedFlux;      // a = the texel's measure
layout(r32f, binding = 3) uniform image2D landedRadius;

uniform ivec2 grid;
uniform int branchRows;  // rows of one emission branch: neighbours never cross it
uniform int directional; // 1: measures are m^2 across the beam; 0: sr from the light
uniform float spacings;
uniform float stretch; // 0: any distance
uniform int estimate;  // 0: AREA, 1: MEAN_DISTANCE (vtkCausticsPhotonSpacing::Estimates)

// The photon's unoccluded spacing on its receiver (m).
float UnoccludedSpacing(ivec2 texel, vec4 position, vec4 normal)
{
  float measure = max(imageLoad(landedFlux, texel).a, 0.0);
  float distance = directional != 0 ? 1.0 : position.w;
  return distance * sqrt(measure / max(normal.w, 1e-3));
}

// Whether the photon at grid texel q counts as a neighbour of the one at x (normal n),
// and where it landed.
bool Neighbour(ivec2 q, int branch, vec3 x, vec3 n, float reach, out vec3 p)
{
  p = vec3(0.0);
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, grid)) || q.y / branchRows != branch)
  {
    return false;
  }
  vec4 position = imageLoad(landedPosition, q);
  if (!(position.w > 0.0) || dot(imageLoad(landedNormal, q).xyz, n) < 0.9)
  {
    return false;
  }
  p = position.xyz;
  return distance(p, x) <= reach;
}

// The spacing vector along one grid axis (AREA); zero when no neighbour counts.
vec3 AxisSpacing(ivec2 texel, ivec2 axis, int branch, vec3 x, vec3 n, float reach)
{
  vec3 a, b;
  bool hasA = Neighbour(texel - axis, branch, x, n, reach, a);
  bool hasB = Neighbour(texel + axis, branch, x, n, reach, b);
  if (hasA && hasB)
  {
    return 0.5 * (b - a);
  }
  return hasB ? b - x : (hasA ? x - a : vec3(0.0));
}

// The estimate's spacing; 0 where it finds no neighbours.
float NeighbourSpacing(ivec2 texel, int branch, vec3 x, vec3 n, float reach)
{
  if (estimate == 0)
  {
    vec3 ex = AxisSpacing(texel, ivec2(1, 0), branch, x, n, reach);
    vec3 ey = AxisSpacing(texel, ivec2(0, 1), branch, x, n, reach);
    return dot(ex, ex) > 0.0 && dot(ey, ey) > 0.0 ? sqrt(length(cross(ex, ey))) : 0.0;
  }
  float sum = 0.0;
  int count = 0;
  const ivec2 steps[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  for (int k = 0; k < 4; ++k)
  {
    vec3 p;
    if (Neighbour(texel + steps[k], branch, x, n, reach, p))
    {
      sum += distance(p, x);
      ++count;
    }
  }
  return count > 0 ? sum / float(count) : 0.0;
}

// The distance to the nearest photon that counts in a 9 x 9 window; 0 where none does.
float NearestSpacing(ivec2 texel, int branch, vec3 x, vec3 n, float reach)
{
  float nearest = 3.0e38;
  for (int j = -4; j <= 4; ++j)
  {
    for (int i = -4; i <= 4; ++i)
    {
      vec3 p;
      if ((i != 0 || j != 0) && Neighbour(texel + ivec2(i, j), branch, x, n, reach, p))
      {
        nearest = min(nearest, distance(p, x));
      }
    }
  }
  return nearest < 3.0e38 ? nearest : 0.0;
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, grid)))
  {
    return;
  }
  vec4 position = imageLoad(landedPosition, texel);
  if (!(position.w > 0.0) || !(spacings > 0.0))
  {
    return;
  }
  vec3 x = position.xyz;
  vec4 normal = imageLoad(landedNormal, texel);
  int branch = texel.y / branchRows;
  float reach = stretch > 0.0 ? stretch * UnoccludedSpacing(texel, position, normal) : 3.0e38;
  float spacing = NeighbourSpacing(texel, branch, x, normal.xyz, reach);
  if (!(spacing > 0.0))
  {
    spacing = NearestSpacing(texel, branch, x, normal.xyz, reach);
  }
  float radius = max(imageLoad(landedRadius, texel).r, spacings * spacing);
  imageStore(landedRadius, texel, vec4(radius));
}
