// Caustic triangles (Umenhoffer, Patow and Szirmay-Kalos, "Caustic triangles on
// the GPU", the follow-up of 004_*.txt): neighbouring photons of the emitter's grid
// span the light's wavefront; where three of them landed together on one receiver,
// the triangle they land as carries the flux of the half cell of the grid between
// them over exactly the area it lands on. That is an adaptive filter with no radius
// to tune: it is as wide as the photons' spacing, so focusing and folds stay sharp.
//
// Cell (x, y) of the grid has corners a = (x, y), b = (x+1, y), c = (x, y+1),
// d = (x+1, y+1) and two triangles, 0: (a, b, d) and 1: (a, d, c). Each photon is a
// corner of six triangles, so a triangle takes 1/6 of each corner's flux; a photon
// whose triangles are not all valid splats the rest (vtkCausticsPhotonSplatVS), so
// every photon still deposits exactly its flux.
// Needs the photon record samplers hitPosition, hitNormal, hitFlux declared before.

uniform ivec2 hitGrid;           // the grid's width and height
uniform int hitBranchRows;       // rows of one emitter branch: cells never cross one
uniform int hitLightType;        // caustics::Light::Type: 0 directional (measure m^2), else sr
uniform float triangleStretch;   // longest edge, in unoccluded photon spacings
uniform mat4 triangleWorldToClip; // the target view
uniform vec2 triangleViewport;    // its size in pixels

const ivec2 CAUSTICS_TRIANGLE_CORNERS[6] =
  ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

struct CausticTriangle
{
  vec3 p[3];      // landed positions (m)
  vec2 pixel[3];  // the same in target pixels
  vec3 normal;    // the mean receiver normal
  vec3 flux;      // W: 1/6 of each corner's
  float footprint; // m^2: the largest corner's unoccluded footprint
};

// Grid texel of corner k (0..2) of triangle t of cell.
ivec2 CausticTriangleCorner(ivec2 cell, int t, int k)
{
  return cell + CAUSTICS_TRIANGLE_CORNERS[3 * t + k];
}

// True when the cell's four corners lie in the grid and in one emitter branch.
bool CausticCellInGrid(ivec2 cell)
{
  return all(greaterThanEqual(cell, ivec2(0))) && all(lessThan(cell + 1, hitGrid)) &&
    cell.y / hitBranchRows == (cell.y + 1) / hitBranchRows;
}

vec2 CausticTrianglePixel(vec3 p, out float w)
{
  vec4 clip = triangleWorldToClip * vec4(p, 1.0);
  w = clip.w;
  return (clip.xy / clip.w * 0.5 + 0.5) * triangleViewport;
}

// Loads triangle t of cell and tells whether it is a caustic triangle: its corners
// landed on one smooth receiver (normals within 25 degrees, each edge within 14
// degrees of the corners' tangent planes), it is not stretched across a
// silhouette or a change of path (no edge longer than triangleStretch unoccluded
// spacings: neighbours that took different paths land far apart), it lies in front
// of the target view and covers some of it.
bool LoadCausticTriangle(ivec2 cell, int t, out CausticTriangle tri)
{
  tri.normal = vec3(0.0);
  tri.flux = vec3(0.0);
  tri.footprint = 0.0;
  if (!CausticCellInGrid(cell))
  {
    return false;
  }
  vec3 n[3];
  for (int k = 0; k < 3; ++k)
  {
    ivec2 texel = CausticTriangleCorner(cell, t, k);
    vec4 position = texelFetch(hitPosition, texel, 0);
    vec4 normal = texelFetch(hitNormal, texel, 0);
    vec4 flux = texelFetch(hitFlux, texel, 0);
    // The measure is negative for a photon on a receiver the caustic maps' light view
    // hides (vtkCausticsPhotonBuffer): it lands there all the same.
    float measure = abs(flux.a);
    if (!(position.w > 0.0) || !(measure > 0.0))
    {
      return false;
    }
    float w;
    tri.p[k] = position.xyz;
    tri.pixel[k] = CausticTrianglePixel(position.xyz, w);
    if (!(w > 0.0))
    {
      return false;
    }
    n[k] = normalize(normal.xyz);
    tri.normal += n[k];
    tri.flux += flux.rgb;
    // Unoccluded footprint: the texel's measure over the beam's cross-section.
    if (hitLightType != 0)
    {
      measure *= position.w * position.w;
    }
    tri.footprint = max(tri.footprint, measure / max(normal.w, 0.05));
  }
  tri.flux /= 6.0;
  tri.normal = normalize(tri.normal);
  float longest = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    int l = (k + 1) % 3;
    vec3 edge = tri.p[l] - tri.p[k];
    float length2 = dot(edge, edge);
    longest = max(longest, length2);
    if (dot(n[k], n[l]) < 0.9 || abs(dot(edge, n[k])) > 0.25 * sqrt(length2) ||
      abs(dot(edge, n[l])) > 0.25 * sqrt(length2))
    {
      return false;
    }
  }
  vec2 e1 = tri.pixel[1] - tri.pixel[0], e2 = tri.pixel[2] - tri.pixel[0];
  float screenArea = 0.5 * abs(e1.x * e2.y - e1.y * e2.x);
  return longest <= triangleStretch * triangleStretch * tri.footprint && screenArea > 1e-4 &&
    dot(tri.flux, vec3(1.0)) > 0.0;
}
