// Distance impostors (004_4da4b323b51d1415.txt §2-4): lookups into the cube maps of
// vtkCausticsDistanceImpostors and the Hit() search along a ray. A map's layer
// 6 map + face holds, per texel, the world position of the surface seen from the
// map's reference point in that direction (w = material index, -1: none) and its
// normal as modelled (w = role). The distance of a point is |p - reference point|.
uniform sampler2DArray impostorPosition;
uniform sampler2DArray impostorNormal;
uniform sampler2DArray impostorRadiance; // receivers: albedo x unshadowed direct irradiance
uniform mat4 impostorFaceRotation[6]; // points relative to the reference point -> face clip
uniform vec3 impostorCentre[4];       // reference points, m
uniform float impostorReach[4];       // longest segment a search of the map needs, m
uniform int impostorValid[4];         // 1: the map exists
uniform vec3 impostorContentMin[4];   // the box of the meshes a map draws (min > max: none)
uniform vec3 impostorContentMax[4];
uniform int impostorResolution;
uniform int impostorLinearSteps;
uniform int impostorSecantSteps;
uniform int impostorReflectorBounces; // mirror-to-mirror reflections in a row, at most
// The caustic store (vtkCausticsDistanceImpostors::BeginCaustic): per environment-map
// texel and channel (layer 18 channel + 6 map + face), the caustic flux that landed on
// the receiver the texel shows, less the direct light the specular objects block
// there, in counts of impostorCausticUnit W (0: no store this frame); layer
// 54 + 6 map + face: the number of deposits (photons and shadow samples).
layout(r32i, binding = CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE) uniform iimage2DArray impostorCaustic;
uniform float impostorCausticUnit;
uniform int impostorCausticRadius;  // the store's read window: (2 r + 1)^2 texels at most
uniform int impostorCausticSamples; // deposits the read window grows to hold
// The store's coarse level, for receivers too sparsely lit for the fine window: the
// same sums over cells of IMPOSTOR_COARSE^2 texels (impostorCausticCells per side of
// a face, 0: none), 64 cells' faces tiled per layer from layer 72
// (ImpostorCoarseTexel), and per cell the area of the receivers its texels show (m^2,
// impostorCausticArea, layer 6 map + face; vtkCausticsImpostorCausticAreaCS.glsl).
const int IMPOSTOR_COARSE = 8;
uniform int impostorCausticCells;
uniform int impostorCausticCoarseSamples;
uniform sampler2DArray impostorCausticArea;

const int IMPOSTOR_REFRACTOR_ENVIRONMENT = 0;
const int IMPOSTOR_REFRACTOR_SURFACE = 1;
const int IMPOSTOR_REFLECTOR_ENVIRONMENT = 2;
const int IMPOSTOR_REFLECTOR_SURFACE = 3;

// The texel of `map` in direction d from its reference point (the face of d's
// major axis, through the same matrix the face was rendered with).
ivec3 ImpostorTexel(int map, vec3 d)
{
  vec3 a = abs(d);
  int face = a.x >= a.y && a.x >= a.z ? (d.x >= 0.0 ? 0 : 1)
                                       : (a.y >= a.z ? (d.y >= 0.0 ? 2 : 3) : (d.z >= 0.0 ? 4 : 5));
  vec4 clip = impostorFaceRotation[face] * vec4(d, 1.0);
  vec2 uv = clip.xy / max(clip.w, 1e-30) * 0.5 + 0.5;
  ivec2 t = clamp(ivec2(floor(uv * float(impostorResolution))), ivec2(0),
    ivec2(impostorResolution - 1));
  return ivec3(t, 6 * map + face);
}

// How far p is beyond the map's surface in p's direction from the reference point
// (m; < 0 on the reference point's side). Measured from the texel's tangent plane,
// not as a difference of distances from the reference point: exact for planar
// surfaces between texels (the paper's assumption, §2.1) even where the map sees
// them at grazing angles and one texel spans much of the surface; the distance
// difference where the surface is seen edge-on. A direction without a surface is
// never passed.
float ImpostorGap(int map, vec3 p, out ivec3 texel)
{
  vec3 d = p - impostorCentre[map];
  texel = ImpostorTexel(map, d);
  vec4 s = texelFetch(impostorPosition, texel, 0);
  if (s.w < 0.0)
  {
    return -3.0e38;
  }
  vec3 n = texelFetch(impostorNormal, texel, 0).xyz;
  float side = dot(impostorCentre[map] - s.xyz, n);
  float radial = length(d) - distance(s.xyz, impostorCentre[map]);
  return abs(side) > 1e-3 * distance(s.xyz, impostorCentre[map]) * length(n)
    ? -dot(p - s.xyz, n) * sign(side) / max(length(n), 1e-20)
    : radial;
}

// Whether the crossing h of a texel's tangent plane lies on the texel's surface:
// within one texel footprint (the texel's angle at its distance, stretched by the
// angle the reference point sees the surface at) of the surface point it holds.
// The plane reaches beyond the surface's edge; the surface does not.
bool ImpostorOnSurface(int map, vec3 h, ivec3 texel)
{
  vec3 s = texelFetch(impostorPosition, texel, 0).xyz;
  vec3 n = texelFetch(impostorNormal, texel, 0).xyz;
  vec3 toCentre = impostorCentre[map] - s;
  float distanceToCentre = length(toCentre);
  float cosine = abs(dot(toCentre, n)) / max(distanceToCentre * length(n), 1e-20);
  float footprint = 2.0 * distanceToCentre / float(impostorResolution) / max(cosine, 0.02);
  return texelFetch(impostorPosition, texel, 0).w >= 0.0 && distance(h, s) <= footprint;
}

// Hit(): the first crossing of the map's surface by o + t d, t in (tMin, tMax].
// A linear march of impostorLinearSteps samples finds the first sample beyond the
// surface; false position (Illinois) between it and the sample before refines it
// impostorSecantSteps times (the paper's iteration, §3, with its "undershooting /
// overshooting" pair kept as a bracket so that it converges). A ray that starts on
// or beyond the surface (a ray leaving a mirror wall the map holds: its own texel's
// distance is its start; a surface hidden behind the map's) is not in front of it
// yet: the march skips its samples until one is in front, so that the start itself
// is never reported, and a ray that never comes in front finds nothing. Returns
// false when no sample passes the surface; else t and the texel of the surface found.
bool ImpostorHit(int map, vec3 o, vec3 d, float tMin, float tMax, out float t, out ivec3 texel)
{
  t = tMax;
  texel = ivec3(0);
  if (impostorValid[map] == 0 || !(tMax > tMin))
  {
    return false;
  }
  ivec3 unused;
  float gStart = ImpostorGap(map, o + tMin * d, unused);
  bool behind = gStart >= 0.0;
  float t0 = tMin;
  float g0 = max(min(gStart, 0.0), -(tMax - tMin));
  float t1 = tMax;
  float g1 = -1.0;
  bool found = false;
  for (int i = 1; i <= impostorLinearSteps && !found; ++i)
  {
    float ti = tMin + (tMax - tMin) * float(i) / float(impostorLinearSteps);
    float gi = ImpostorGap(map, o + ti * d, texel);
    if (gi >= 0.0 && !behind)
    {
      t1 = ti;
      g1 = gi;
      found = true;
    }
    else if (gi < 0.0)
    {
      behind = false;
      t0 = ti;
      g0 = max(gi, -(tMax - tMin)); // a direction without surface counts as far before
    }
  }
  if (!found)
  {
    return false;
  }
  int side = 0; // Illinois: halve the weight of an end kept twice
  for (int k = 0; k < impostorSecantSteps; ++k)
  {
    float tm = (g1 - g0) > 0.0 ? t0 + (t1 - t0) * (-g0) / (g1 - g0) : 0.5 * (t0 + t1);
    ivec3 q;
    float gm = ImpostorGap(map, o + tm * d, q);
    if (gm >= 0.0)
    {
      t1 = tm;
      g1 = gm;
      texel = q;
      g0 = side == -1 ? 0.5 * g0 : g0;
      side = -1;
    }
    else
    {
      t0 = tm;
      g0 = max(gm, -(tMax - tMin));
      g1 = side == 1 ? 0.5 * g1 : g1;
      side = 1;
    }
  }
  t = (g1 - g0) > 0.0 ? t0 + (t1 - t0) * (-g0) / (g1 - g0) : t1;
  // The texel in the crossing's own direction: empty beyond a surface's edge.
  ivec3 own;
  if (ImpostorGap(map, o + t * d, own) > -3.0e38)
  {
    texel = own;
  }
  return ImpostorOnSurface(map, o + t * d, texel);
}

// The first crossing of o + t d with the surface of impostor map `map` (Hit()), over
// the part of the ray inside the box [boxMin, boxMax] grown by `tolerance` (m) and
// within the map's reach, starting `tolerance` from o. Used by the camera view
// (vtkCausticsScreenSpaceRefractionFS.glsl) and the photon trace
// (vtkCausticsImpostorPhotonTraceCS.glsl).
bool ImpostorSearch(int map, vec3 o, vec3 d, vec3 boxMin, vec3 boxMax, float tolerance,
  out float t, out ivec3 texel)
{
  float t0 = 0.0;
  float t1 = impostorReach[map];
  t = t1;
  texel = ivec3(0);
  // A ray that misses the box of what the map draws meets nothing in it (the ball's
  // reflections of the sky): no search.
  float c0 = 0.0;
  float c1 = t1;
  bool content = all(lessThanEqual(impostorContentMin[map], impostorContentMax[map]));
  vec3 margin =
    vec3(tolerance) + 1e-4 * (content ? impostorContentMax[map] - impostorContentMin[map] : vec3(0.0));
  return content &&
    CausticsClipToBox(o, d, boxMin - vec3(tolerance), boxMax + vec3(tolerance), t0, t1) &&
    CausticsClipToBox(o, d, impostorContentMin[map] - margin, impostorContentMax[map] + margin,
      c0, c1) &&
    c1 >= max(t0, tolerance) && c0 <= t1 &&
    ImpostorHit(map, o, d, max(t0, tolerance), t1, t, texel);
}

// The first surface along o + t d outside the refractors (ImpostorSearch), for a ray
// that left a surface of role `leftRole` (a refractor's: pass ROLE_REFRACTOR from
// inside one too): the environment map of that group (a mirror's: receivers and
// refractors; any other: receivers and mirrors), and, leaving a mirror after
// `bounces` mirror-to-mirror reflections in a row (fewer than
// impostorReflectorBounces), also the mirrors' own map (REFLECTOR_SURFACE: a concave
// mirror sees itself), the nearer hit of the two. The one search of the photon
// trace (vtkCausticsImpostorPhotonTraceCS.glsl) and the camera view
// (vtkCausticsScreenSpaceRefractionFS.glsl).
bool ImpostorEnvironmentSearch(vec3 o, vec3 d, int leftRole, int bounces, vec3 boxMin,
  vec3 boxMax, float tolerance, out float t, out ivec3 texel)
{
  bool mirror = leftRole == ROLE_REFLECTOR;
  int map = mirror ? IMPOSTOR_REFLECTOR_ENVIRONMENT : IMPOSTOR_REFRACTOR_ENVIRONMENT;
  bool found = ImpostorSearch(map, o, d, boxMin, boxMax, tolerance, t, texel);
  float tSelf;
  ivec3 selfTexel;
  if (mirror && bounces < impostorReflectorBounces &&
    ImpostorSearch(IMPOSTOR_REFLECTOR_SURFACE, o, d, boxMin, boxMax, tolerance, tSelf, selfTexel) &&
    (!found || tSelf < t))
  {
    found = true;
    t = tSelf;
    texel = selfTexel;
  }
  return found;
}

// The normal at h, a point on the surface that `texel` of `map` holds: bilinear
// between the normals of the 2 x 2 texels around h's direction that show the same
// material within 60 degrees of the texel's own normal (a smooth surface's normal is
// continuous; one texel's normal alone is piecewise constant, and a photon refracted
// by it is bent in steps, the caustic broken into bands). Unit; the texel's own where
// no neighbour qualifies.
vec3 ImpostorSmoothNormal(int map, vec3 h, ivec3 texel)
{
  int face = texel.z - 6 * map;
  vec4 clip = impostorFaceRotation[face] * vec4(h - impostorCentre[map], 1.0);
  vec2 c = (clip.xy / max(clip.w, 1e-30) * 0.5 + 0.5) * float(impostorResolution) - 0.5;
  ivec2 base = ivec2(floor(c));
  vec2 f = clamp(c - vec2(base), 0.0, 1.0);
  vec3 own = normalize(texelFetch(impostorNormal, texel, 0).xyz);
  float material = texelFetch(impostorPosition, texel, 0).w;
  vec3 sum = vec3(0.0);
  for (int k = 0; k < 4; ++k)
  {
    ivec3 corner = ivec3(clamp(base + ivec2(k & 1, k >> 1), ivec2(0),
                           ivec2(impostorResolution - 1)),
      texel.z);
    vec3 n = texelFetch(impostorNormal, corner, 0).xyz;
    float weight = ((k & 1) == 1 ? f.x : 1.0 - f.x) * ((k >> 1) == 1 ? f.y : 1.0 - f.y);
    bool same = texelFetch(impostorPosition, corner, 0).w == material && dot(n, n) > 0.0 &&
      dot(normalize(n), own) > 0.5;
    sum += same ? weight * normalize(n) : vec3(0.0);
  }
  return dot(sum, sum) > 1e-12 ? normalize(sum) : own;
}

// The area (m^2) of the surface that `texel` of `map` shows: the texel's solid angle
// from the reference point ((2 / resolution)^2 cos^3 of the angle to the face's axis)
// times distance^2 over the cosine at which the surface is seen (floored as in
// ImpostorOnSurface).
float ImpostorTexelArea(int map, ivec3 texel)
{
  vec3 s = texelFetch(impostorPosition, texel, 0).xyz;
  vec3 n = texelFetch(impostorNormal, texel, 0).xyz;
  vec3 toCentre = impostorCentre[map] - s;
  float r2 = max(dot(toCentre, toCentre), 1e-30);
  vec3 a = abs(toCentre);
  float axis = max(a.x, max(a.y, a.z)) * inversesqrt(r2);
  float side = 2.0 / float(impostorResolution);
  float cosine = abs(dot(toCentre, n)) * inversesqrt(max(r2 * dot(n, n), 1e-30));
  return side * side * axis * axis * axis * r2 / max(cosine, 0.02);
}

// The caustic irradiance (W/m^2, net of the direct light the specular objects block;
// may be negative in a shadow) at the receiver that `texel` of an environment map
// shows, from the caustic store; zero without one. An adaptive density estimate: the
// stored flux over the area of the smallest square of texels around it, radius 0 to
// impostorCausticRadius, of the face that holds impostorCausticSamples deposits or
// more (the last one otherwise), counting only texels that show the same surface
// (same material, normals within 60 degrees, within the window's footprint of its
// tangent plane). One texel alone holds about one photon where the light is spread
// (256^2 photons over the pool, 8 mm texels a metre away), and its count is that
// photon's noise; a fixed window wide enough for that blurs a focus seen in a mirror
// to a quarter of its peak. The window is also about `minimumWidth` (m) wide or more
// (the nearest width of 1, 3, 5, ... texels), as far as the radius allows: the
// footprint of the camera pixel that reads it. Otherwise a pixel that sees a focus in
// a convex mirror reads the focus's peak where the pixel averages a wide patch of
// floor (12 times the reference's there).
const int IMPOSTOR_STORE_FACES = 18; // 3 maps x 6 faces per channel

// The cell of the store's coarse level that holds `texel` (a layer 6 map + face).
ivec2 ImpostorCoarseCell(ivec2 texel)
{
  return min(texel / IMPOSTOR_COARSE, ivec2(impostorCausticCells - 1));
}

// Where the store keeps channel c (0-2: flux, 3: deposits) of `texel`: layer
// 18 c + 6 map + face.
ivec3 ImpostorStoreTexel(ivec3 texel, int c)
{
  return texel + ivec3(0, 0, IMPOSTOR_STORE_FACES * c);
}

// Where the coarse level keeps channel c of `cell` of layer 6 map + face: tile
// 18 c + layer of the 8 x 8 tiles of layers 72 and 73.
ivec3 ImpostorCoarseTexel(ivec2 cell, int layer, int c)
{
  int tile = IMPOSTOR_STORE_FACES * c + layer;
  return ivec3((tile % 8) * impostorCausticCells + cell.x,
    (tile / 8 % 8) * impostorCausticCells + cell.y, 4 * IMPOSTOR_STORE_FACES + tile / 64);
}

// The flux counts (xyz) and deposits (w) one texel or cell of the store holds
// (`at`: its four channels' texels, ImpostorStoreTexel or ImpostorCoarseTexel).
vec4 ImpostorStoreLoad(ivec3 at[4])
{
  return vec4(float(imageLoad(impostorCaustic, at[0]).x), float(imageLoad(impostorCaustic, at[1]).x),
    float(imageLoad(impostorCaustic, at[2]).x), float(imageLoad(impostorCaustic, at[3]).x));
}

// Adds `counts` (flux in units of impostorCausticUnit) and one deposit there.
void ImpostorStoreAdd(ivec3 at[4], ivec3 counts)
{
  for (int c = 0; c < 3; ++c)
  {
    if (counts[c] != 0)
    {
      imageAtomicAdd(impostorCaustic, at[c], counts[c]);
    }
  }
  imageAtomicAdd(impostorCaustic, at[3], 1);
}

ivec3[4] ImpostorStoreTexels(ivec3 texel)
{
  return ivec3[4](ImpostorStoreTexel(texel, 0), ImpostorStoreTexel(texel, 1),
    ImpostorStoreTexel(texel, 2), ImpostorStoreTexel(texel, 3));
}

ivec3[4] ImpostorCoarseTexels(ivec2 cell, int layer)
{
  return ivec3[4](ImpostorCoarseTexel(cell, layer, 0), ImpostorCoarseTexel(cell, layer, 1),
    ImpostorCoarseTexel(cell, layer, 2), ImpostorCoarseTexel(cell, layer, 3));
}

vec3 ImpostorCausticIrradiance(ivec3 texel, float minimumWidth)
{
  if (!(impostorCausticUnit > 0.0))
  {
    return vec3(0.0);
  }
  if (texel.z >= IMPOSTOR_STORE_FACES)
  {
    return vec3(0.0); // REFLECTOR_SURFACE holds no receiver
  }
  int map = texel.z / 6;
  vec4 own = texelFetch(impostorPosition, texel, 0);
  vec3 n = normalize(texelFetch(impostorNormal, texel, 0).xyz);
  float footprint = 2.0 * distance(own.xyz, impostorCentre[map]) / float(impostorResolution);
  vec3 counts = vec3(0.0);
  float samples = 0.0;
  float area = 0.0;
  for (int ring = 0; ring <= impostorCausticRadius; ++ring)
  {
    float reach = float(2 * ring + 1) * footprint;
    for (int y = -ring; y <= ring; ++y)
    {
      for (int x = -ring; x <= ring; ++x)
      {
        ivec3 k = ivec3(texel.xy + ivec2(x, y), texel.z);
        if (max(abs(x), abs(y)) != ring || any(lessThan(k.xy, ivec2(0))) ||
          any(greaterThanEqual(k.xy, ivec2(impostorResolution))))
        {
          continue;
        }
        vec4 s = texelFetch(impostorPosition, k, 0);
        vec3 m = texelFetch(impostorNormal, k, 0).xyz;
        if (s.w != own.w || !(dot(m, m) > 0.0) || dot(normalize(m), n) < 0.5 ||
          abs(dot(s.xyz - own.xyz, n)) > reach)
        {
          continue;
        }
        vec4 stored = ImpostorStoreLoad(ImpostorStoreTexels(k));
        counts += stored.xyz;
        samples += stored.w;
        area += ImpostorTexelArea(map, k);
      }
    }
    if (samples >= float(impostorCausticSamples) && reach + footprint >= minimumWidth)
    {
      break;
    }
  }
  // The fine window's own evidence, kept to check the coarse level against.
  vec3 fineCounts = counts;
  float fineSamples = samples;
  float fineArea = area;
  if (samples < float(impostorCausticSamples) && impostorCausticCells > 0)
  {
    // Too few deposits within the fine window (light spread thin over a receiver the
    // map sees finely): a window of 3, then 5, cells of the coarse level per side
    // around it, whatever surfaces they show. Photons and shadow samples are lattices
    // that alias with the texels; a window holding too few of either leaves their
    // difference (a flat water sheet's T - 1 of the direct light) to that noise. The
    // window is centred on the texel, not on its cell, each cell counting by the share
    // of it the window covers: the estimate slides with the texel instead of stepping
    // from cell to cell (a cell-centred window drew the cells as blocks).
    vec2 position = vec2(texel.xy) + 0.5; // texels, from the face's corner
    for (int ring = 1; ring <= 2; ++ring)
    {
      counts = vec3(0.0);
      samples = 0.0;
      area = 0.0;
      vec2 low = position - float(IMPOSTOR_COARSE) * (float(ring) + 0.5);
      vec2 high = position + float(IMPOSTOR_COARSE) * (float(ring) + 0.5);
      ivec2 first = max(ivec2(floor(low / float(IMPOSTOR_COARSE))), ivec2(0));
      ivec2 last = min(ivec2(floor(high / float(IMPOSTOR_COARSE))), ivec2(impostorCausticCells - 1));
      for (int y = first.y; y <= last.y; ++y)
      {
        for (int x = first.x; x <= last.x; ++x)
        {
          ivec2 cell = ivec2(x, y);
          vec2 start = vec2(cell) * float(IMPOSTOR_COARSE);
          vec2 covered = clamp(min(start + float(IMPOSTOR_COARSE), high) - max(start, low),
            vec2(0.0), vec2(float(IMPOSTOR_COARSE))) / float(IMPOSTOR_COARSE);
          float share = covered.x * covered.y;
          if (!(share > 0.0))
          {
            continue;
          }
          vec4 stored = ImpostorStoreLoad(ImpostorCoarseTexels(cell, texel.z));
          counts += share * stored.xyz;
          samples += share * stored.w;
          area += share * texelFetch(impostorCausticArea, ivec3(cell, texel.z), 0).x;
        }
      }
      if (samples >= float(impostorCausticCoarseSamples))
      {
        break;
      }
    }
  }
  // The coarse cells average whatever lies around: at a shadow's edge (the floor under
  // a pool's wall, lit on one side) they carry the lit side's light into the shadow.
  // Their density would put `expected` deposits in the fine window; far fewer there
  // (beyond two standard deviations of a Poisson count) says the light ends there, and
  // the fine window's own estimate, dark or dim, stands.
  float expected = area > 0.0 ? samples * fineArea / area : 0.0;
  if (fineArea > 0.0 && fineSamples < float(impostorCausticSamples) &&
    fineSamples < expected - 2.0 * sqrt(expected))
  {
    return fineCounts * impostorCausticUnit / fineArea;
  }
  return area > 0.0 ? counts * impostorCausticUnit / area : vec3(0.0);
}

// Whether environment map `map` (made) has, in h's direction, a texel that shows a
// receiver at h: the texel the caustic store keeps h's light in.
bool ImpostorReceiverTexel(int map, vec3 h, out ivec3 texel)
{
  texel = ivec3(0);
  if (impostorValid[map] == 0)
  {
    return false;
  }
  texel = ImpostorTexel(map, h - impostorCentre[map]);
  return int(texelFetch(impostorNormal, texel, 0).w + 0.5) == ROLE_RECEIVER &&
    ImpostorOnSurface(map, h, texel);
}

// Adds `flux` (W per channel, negative for blocked light) landed at h on a receiver
// to the caustic store of each environment map whose texel in h's direction shows
// that receiver at h.
void ImpostorDepositCaustic(vec3 h, vec3 flux)
{
  if (!(impostorCausticUnit > 0.0) || !all(lessThan(abs(flux), vec3(1e30))))
  {
    return;
  }
  ivec3 counts = ivec3(round(flux / impostorCausticUnit));
  for (int map = IMPOSTOR_REFRACTOR_ENVIRONMENT; map <= IMPOSTOR_REFLECTOR_ENVIRONMENT; map += 2)
  {
    ivec3 texel;
    if (!ImpostorReceiverTexel(map, h, texel))
    {
      continue;
    }
    ImpostorStoreAdd(ImpostorStoreTexels(texel), counts);
    if (impostorCausticCells > 0)
    {
      ImpostorStoreAdd(ImpostorCoarseTexels(ImpostorCoarseCell(texel.xy), texel.z), counts);
    }
  }
}
