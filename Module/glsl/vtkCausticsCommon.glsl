// Shared by every caustics shader (prepended after #version, the defines and the
// binding table vtkCausticsBindings.h).
// Layouts and constants here must match the host side (vtkCausticsSceneGeometry,
// vtkCausticsSceneData.h).

const float CAUSTICS_PI = 3.14159265358979323846;

// Two unit tangents e1, e2 of the plane with unit normal n, (e1, e2, n) right-handed:
// the one frame every stage lays a kernel disc on a receiver in (the splats, their
// share on the receiver, a disc's projected radius).
void CausticsTangents(vec3 n, out vec3 e1, out vec3 e2)
{
  vec3 helper = abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  e1 = normalize(cross(n, helper));
  e2 = cross(n, e1);
}

// Luminance of a linear RGB value (Rec. 709 weights): what the denoiser filters on.
float CausticsLuminance(vec3 c)
{
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Which half of the frame's photons the photon (or caustic triangle, or cluster) of
// row-major index `index` in its grid belongs to: +1 or -1 by the index's parity. The
// photons of a low-discrepancy sequence alternate (both halves are low-discrepancy
// sets themselves), those of a grid alternate by column. (A checkerboard split of the
// cascaded technique's R2 photons, tried once, overestimated the pool's variance 29.5x,
// against 4.7x for this one: scripts/photon-variance.py.)
float CausticsHalfSet(uint index)
{
  return (index & 1u) == 0u ? 1.0 : -1.0;
}

// What a reconstruction stage writes into caustic irradiance: the irradiance, and in
// alpha the deposit's luminance signed by its half set. Summed by additive blending
// (and by any linear filter after it), alpha is the difference A - B between the
// estimates of the two halves. For two independent halves of equal mean,
// E[(A - B)^2] = Var(A) + Var(B) = Var(A + B): its square (CausticsPhotonVariance) is
// the variance of the pixel's estimate from this frame's own photons, which the
// denoiser uses while its history is short. Unlike the sum of squared deposits (the
// variance of Poisson photons, used before) it sees part of what stratified or
// low-discrepancy photons gain: for the cascaded technique's photons that sum
// overestimated the variance 3.5x on the ball lens and 23x on the pool, the halves'
// difference 1.6x and 4.7x (medians over the caustic's pixels; scripts/photon-variance.py
// measures the second, a one-off variant of it the first). The halves of a
// low-discrepancy set are not independent, hence the rest.
vec4 CausticsDeposit(vec3 irradiance, float halfSet)
{
  return vec4(irradiance, halfSet * CausticsLuminance(irradiance));
}

// The variance of a pixel's luminance estimate from the alpha its deposits summed
// to (CausticsDeposit).
float CausticsPhotonVariance(float halfSetDifference)
{
  return halfSetDifference * halfSetDifference;
}

// Material roles (caustics::Role).
const int ROLE_NONE = 0;
const int ROLE_RECEIVER = 1;
const int ROLE_REFLECTOR = 2;
const int ROLE_REFRACTOR = 3;

// Spot falloff of glTF KHR_lights_punctual, as caustics::Light::SpotFactor: 1
// inside the inner cone, 0 outside the outer cone, a squared linear ramp in
// cos(angle) between.
float CausticsSpotFactor(float cosAngle, float cosOuter, float cosInner)
{
  if (cosAngle <= cosOuter)
  {
    return 0.0;
  }
  float range = cosInner - cosOuter;
  if (range <= 1e-12)
  {
    return 1.0;
  }
  float t = min(1.0, (cosAngle - cosOuter) / range);
  return t * t;
}

// The photon record (caustics::PhotonRecords, vtkCausticsPhotonGrid.h): three
// RGBA32F planes, one texel per photon of the emitter's grid.
//              emitted (after the first specular event)   landed on a receiver
//   position   xyz m; w: 0 none, 1 into air, 2 inside      xyz m; w: path length from the light (m), > 0
//   direction  xyz unit direction; w: texel measure        xyz receiver normal as modelled; w: |N.D|
//   flux       rgb W; a: specular events so far (1)        rgb W; a: texel measure
// The measure is m^2 across a directional light's beam, sr from a point or spot
// light; a directional light's path length starts at its view's eye plane. The
// kernel radius (m) a reconstruction gives a landed photon is an R32F texture
// beside them.

// Beer-Lambert: the fraction of the flux left after distance (m) through a
// medium of attenuation (or extinction) coefficients sigma (1/m).
vec3 CausticsTransmittance(vec3 sigma, float distance)
{
  return exp(-sigma * distance);
}

// A 32-bit integer hash (lowbias32) and a uniform number in [0, 1) drawn from a
// per-photon state, for the photon traces' Russian roulette.
uint CausticsHash(uint x)
{
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

float CausticsRandom(inout uint state)
{
  state = CausticsHash(state + 0x9e3779b9u);
  return float(state >> 8) * (1.0 / 16777216.0);
}

// A uniform number in [0, 1) for the photon at `texel` of a photon grid, stratified
// over the grid: the R2 sequence's dither (plastic-number increments, in 32-bit fixed
// point) rotated by `rotation` (a fixed-point number drawn once per frame). Each
// photon's number is uniform (Cranley-Patterson rotation), so Russian roulette on it
// stays unbiased; and any patch of neighbouring photons takes each branch in the
// share its probability says, where white noise leaves clumps of holes that show as
// speckle where their light converges (a lens's focus).
float CausticsGridStratified(ivec2 texel, uint rotation)
{
  uint fixedPoint = uint(texel.x) * 0xc13fa9a9u + uint(texel.y) * 0x91e10da6u + rotation;
  return float(fixedPoint >> 8u) * (1.0 / 16777216.0);
}

// Adds `watts` W to the 64-bit fixed-point counter (low word first) at words[slot] of
// a uint storage-buffer array, in units of `unit` W, rounded (no bias over many
// photons): integer atomics, which every GPU has (float atomics are NVIDIA's). A
// macro, since GLSL cannot hand a buffer's array to a function. The photon statistics
// (vtkCausticsPhotonStatistics.glsl) and the caustic maps' gather count with it.
#define CAUSTICS_ADD_FIXED_POINT(words, slot, watts, unit)                                  \
  {                                                                                         \
    float causticsUnits = floor((watts) / (unit) + 0.5);                                    \
    if (causticsUnits > 0.0 && !isinf(causticsUnits))                                       \
    {                                                                                       \
      uint causticsHigh = uint(causticsUnits / 4294967296.0);                               \
      uint causticsLow = uint(causticsUnits - float(causticsHigh) * 4294967296.0);          \
      uint causticsOld = atomicAdd(words[slot], causticsLow);                               \
      bool causticsCarry = causticsOld + causticsLow < causticsOld;                         \
      if (causticsHigh > 0u || causticsCarry)                                               \
      {                                                                                     \
        atomicAdd(words[(slot) + 1], causticsHigh + (causticsCarry ? 1u : 0u));             \
      }                                                                                     \
    }                                                                                       \
  }

// The sum of a flux's channels: what Russian roulette weighs paths by.
float CausticsChannelSum(vec3 c)
{
  return dot(c, vec3(1.0));
}

// Henyey-Greenstein phase function (1/sr), cosTheta between the propagation
// directions before and after scattering (as caustics::HenyeyGreenstein).
float CausticsHenyeyGreenstein(float cosTheta, float g)
{
  float denominator = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (4.0 * CAUSTICS_PI * denominator * sqrt(max(denominator, 1e-12)));
}

// Area of the convex polygon (its first `count` vertices, in order around it, at most
// 4) inside the unit square [0, 1]^2 (Sutherland-Hodgman against the square's sides):
// the share of a pixel or texel a caustic triangle or a pixel's footprint covers.
float CausticsAreaInUnitSquare(vec2 polygon[9], int count)
{
  for (int side = 0; side < 4 && count > 0; ++side)
  {
    int axis = side / 2;
    float sense = side % 2 == 0 ? 1.0 : -1.0; // keep x >= 0, then x <= 1, ...
    float bound = side % 2 == 0 ? 0.0 : 1.0;
    vec2 clipped[9]; // four sides cut a quadrilateral to at most 8 vertices
    int kept = 0;
    for (int i = 0; i < count; ++i)
    {
      vec2 p = polygon[i];
      vec2 q = polygon[(i + 1) % count];
      float dp = sense * (p[axis] - bound), dq = sense * (q[axis] - bound);
      if (dp >= 0.0)
      {
        clipped[kept++] = p;
      }
      if ((dp >= 0.0) != (dq >= 0.0))
      {
        clipped[kept++] = mix(p, q, dp / (dp - dq));
      }
    }
    for (int i = 0; i < kept; ++i)
    {
      polygon[i] = clipped[i];
    }
    count = kept;
  }
  float twice = 0.0;
  for (int i = 0; i < count; ++i)
  {
    vec2 p = polygon[i], q = polygon[(i + 1) % count];
    twice += p.x * q.y - p.y * q.x;
  }
  return 0.5 * abs(twice);
}

// Clips o + t d, t in [t0, t1], to an axis-aligned box; false if it misses.
bool CausticsClipToBox(vec3 o, vec3 d, vec3 boxMin, vec3 boxMax, inout float t0, inout float t1)
{
  for (int a = 0; a < 3; ++a)
  {
    if (abs(d[a]) < 1e-20)
    {
      if (o[a] < boxMin[a] || o[a] > boxMax[a])
      {
        return false;
      }
      continue;
    }
    float ta = (boxMin[a] - o[a]) / d[a];
    float tb = (boxMax[a] - o[a]) / d[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return t0 < t1;
}

// March of the optical depth: this step (voxels) inside leaves, at most this many steps
// per ray so that a frame cannot hang (longer rays take longer steps).
#define CAUSTICS_MEDIUM_STEP_VOXELS 0.5
#define CAUSTICS_MEDIUM_MAX_STEPS 256

// The participating medium (caustics::Medium): homogeneous, filling the scene's
// bounding box but not the refractors unless causticsMediumFillsRefractors (murky
// water), as in the reference renderer. Set from the host by
// caustics::gl::SetMediumUniforms.
uniform int causticsMediumOn;
uniform int causticsMediumFillsRefractors;
uniform vec3 causticsSigmaT;     // extinction, 1/m
uniform vec3 causticsMediumLow;  // the scene's bounds (m)
uniform vec3 causticsMediumHigh;

#ifdef CAUSTICS_MEDIUM_GRID
// A heterogeneous medium (vtkCausticsShaderProgram prepends PNanoVDB.h and its buffer
// to the programs with this define): causticsSigmaT is per unit density, the density
// is the NanoVDB grid's value x causticsDensityScale, and causticsMediumLow/High are the
// grid's world bounds within the scene's (0 outside).
uniform mat4 causticsWorldToIndex; // world -> index space, voxel centres at integers
uniform float causticsDensityScale;


pnanovdb_readaccessor_t CausticsGridAccessor()
{
  pnanovdb_buf_t buf;
  pnanovdb_grid_handle_t grid;
  grid.address.byte_offset = 0u;
  pnanovdb_readaccessor_t acc;
  pnanovdb_readaccessor_init(acc, pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, grid)));
  return acc;
}

float CausticsGridValue(inout pnanovdb_readaccessor_t acc, ivec3 ijk)
{
  pnanovdb_buf_t buf;
  return pnanovdb_read_float(
    buf, pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, acc, ijk));
}

// Trilinear, as openvdb::tools::BoxSampler (caustics::DensityGrid::Sample); unscaled.
float CausticsGridSample(inout pnanovdb_readaccessor_t acc, vec3 index)
{
  vec3 f = floor(index);
  ivec3 i = ivec3(f);
  vec3 w = index - f;
  float v00 = mix(CausticsGridValue(acc, i), CausticsGridValue(acc, i + ivec3(0, 0, 1)), w.z);
  float v01 =
    mix(CausticsGridValue(acc, i + ivec3(0, 1, 0)), CausticsGridValue(acc, i + ivec3(0, 1, 1)), w.z);
  float v10 =
    mix(CausticsGridValue(acc, i + ivec3(1, 0, 0)), CausticsGridValue(acc, i + ivec3(1, 0, 1)), w.z);
  float v11 =
    mix(CausticsGridValue(acc, i + ivec3(1, 1, 0)), CausticsGridValue(acc, i + ivec3(1, 1, 1)), w.z);
  return mix(mix(v00, v01, w.y), mix(v10, v11, w.y), w.x);
}

// The density (x scale) at a world point.
float CausticsMediumDensity(vec3 world)
{
  pnanovdb_readaccessor_t acc = CausticsGridAccessor();
  return causticsDensityScale * CausticsGridSample(acc, (causticsWorldToIndex * vec4(world, 1.0)).xyz);
}

// Integral of the density (x scale) along o + t d, t in [t0, t1], in density x m. Walks
// the tree's nodes (pnanovdb_readaccessor_get_dim, as PNanoVDB's HDDA does): a tile or
// empty node (dim > 1) is crossed in one step with its constant value, a leaf (dim 1) is
// marched at CAUSTICS_MEDIUM_STEP_VOXELS with trilinear samples at the steps' midpoints.
// Nodes are the boxes of their voxels' nearest-voxel cells, so the field is exact
// inside them and linear over the last half voxel at a tile's edge. At most maxSteps
// steps (a coarse march for many short rays, e.g. vtkCausticsAirlight's towards the light).
float CausticsMediumOpticalDepthSteps(vec3 o, vec3 d, float t0, float t1, int maxSteps)
{
  pnanovdb_readaccessor_t acc = CausticsGridAccessor();
  pnanovdb_buf_t buf;
  vec3 io = (causticsWorldToIndex * vec4(o, 1.0)).xyz;
  vec3 id = mat3(causticsWorldToIndex) * d;
  float voxelT = 1.0 / max(length(id), 1e-30); // t per voxel along the ray
  float h = max(CAUSTICS_MEDIUM_STEP_VOXELS * voxelT, (t1 - t0) / float(maxSteps));
  bvec3 crosses = greaterThan(abs(id), vec3(1e-30)); // axes along which the ray moves
  float sum = 0.0;
  float density = 0.0;
  float t = t0;
  for (int step = 0; step < maxSteps && t < t1; ++step)
  {
    vec3 index = io + t * id;
    ivec3 ijk = ivec3(floor(index + 0.5));
    int dim = int(pnanovdb_readaccessor_get_dim(PNANOVDB_GRID_TYPE_FLOAT, buf, acc, ijk));
    float next;
    if (dim > 1)
    {
      ivec3 lo = ijk & ~(dim - 1);
      vec3 exitFace = vec3(lo) - 0.5 + vec3(greaterThan(id, vec3(0.0))) * float(dim);
      vec3 exits = mix(vec3(3.0e38), (exitFace - io) / id, crosses);
      next = min(t1, max(min(exits.x, min(exits.y, exits.z)), t + 1e-3 * voxelT));
      density = CausticsGridValue(acc, ijk);
    }
    else
    {
      next = min(t1, t + h);
      density = CausticsGridSample(acc, io + 0.5 * (t + next) * id);
    }
    sum += density * (next - t);
    t = next;
  }
  // Out of steps: the rest at the last density (bounded work beats an exact tail).
  sum += density * max(t1 - t, 0.0);
  return causticsDensityScale * sum * length(d);
}

float CausticsMediumOpticalDepth(vec3 o, vec3 d, float t0, float t1)
{
  return CausticsMediumOpticalDepthSteps(o, d, t0, t1, CAUSTICS_MEDIUM_MAX_STEPS);
}

#ifdef CAUSTICS_CAMERA_OPTICAL_DEPTH
// vtkCausticsCameraOpticalDepth: the optical depth from the near plane along the viewing
// rays, a volume over the camera's frustum built once per frame.
uniform sampler3D causticsCameraDepthVolume;
uniform mat4 causticsCameraWorldToClip;
uniform mat4 causticsCameraClipToWorld;
uniform vec2 causticsCameraDepthRange; // m from the near plane: first and last slice
#endif
#endif


// The medium's transmittance along o + t d, t in [t0, t1] (d need not be unit: the
// distance is (t1 - t0) |d|); 1 without a medium or outside its box. A density grid is
// marched in at most maxSteps steps; a homogeneous medium is in closed form.
vec3 CausticsMediumTransmittanceSteps(vec3 o, vec3 d, float t0, float t1, int maxSteps)
{
  if (causticsMediumOn == 0 ||
    !CausticsClipToBox(o, d, causticsMediumLow, causticsMediumHigh, t0, t1))
  {
    return vec3(1.0);
  }
#ifdef CAUSTICS_MEDIUM_GRID
  return CausticsTransmittance(
    causticsSigmaT, CausticsMediumOpticalDepthSteps(o, d, t0, t1, maxSteps));
#else
  return CausticsTransmittance(causticsSigmaT, (t1 - t0) * length(d));
#endif
}

vec3 CausticsMediumTransmittance(vec3 o, vec3 d, float t0, float t1)
{
  return CausticsMediumTransmittanceSteps(o, d, t0, t1, CAUSTICS_MEDIUM_MAX_STEPS);
}

// Whether a photon's stretch lies in the medium: always in air, inside a refractor
// only when the medium fills the refractors (murky water under a surface).
bool CausticsStretchInMedium(bool insideRefractor)
{
  return causticsMediumOn != 0 && (!insideRefractor || causticsMediumFillsRefractors != 0);
}

// Distance of p from a light along its rays: from the light (point, spot: lightType 1,
// 2), or along the axis from its view's eye plane (directional, lightType 0).
float CausticsLightDistance(vec3 p, int lightType, vec3 origin, vec3 axis)
{
  return lightType == 0 ? dot(p - origin, axis) : length(p - origin);
}

// The depth bias of a surface point's shadow test, `distance` from the light
// (CausticsLightDistance), its normal at `cosine` to the light: two texels of the
// shadow map's lateral size (texelWorldSize: absolute for a sun, at unit distance
// otherwise), tilted by the surface, plus float noise.
float CausticsSurfaceShadowBias(
  float texelWorldSize, int lightType, float distance, float cosine)
{
  float texel = lightType == 0 ? texelWorldSize : texelWorldSize * distance;
  float tangent = sqrt(max(1.0 - cosine * cosine, 0.0)) / max(cosine, 0.05);
  return 2.0 * texel * (1.0 + tangent) + 1e-5 * abs(distance);
}

// Whether a shadow map's occluder sample (position, normal, the unit direction to the
// light there) shadows the receiver point p (normal n on the light's side) although it
// is within the bias: it stands off p's tangent plane more steeply than the slope a
// smooth receiver's own samples reach within a few texels (interpolated normals of
// coarse facets, curvature), and p lies behind the occluder's lit side. A wall rising
// from the floor stands at the light's elevation or steeper; the floor in front of a
// wall's lit face is not behind it, though a texel of its foot is nearer the light.
// n = 0: never.
#define CAUSTICS_CONTACT_SLOPE 0.25
bool CausticsContactOccluder(vec3 occluder, vec3 occluderNormal, vec3 toLight, vec3 p, vec3 n)
{
  vec3 offset = occluder - p;
  float height = dot(offset, n);
  float lateral = length(offset - height * n);
  float noise = 1e-5 * length(p);
  vec3 lit = dot(occluderNormal, toLight) < 0.0 ? -occluderNormal : occluderNormal;
  return height > CAUSTICS_CONTACT_SLOPE * lateral + noise && dot(offset, lit) > noise;
}

// A light's shadow map (vtkCausticsLightBuffers aimed at the scene: world positions seen
// from the light, w = material, -1: none; normals with w = role) at a point `clip` in the
// light's clip space, `distance` from it (CausticsLightDistance): the lit fraction by 2x2
// bilinear percentage-closer filtering, an occluder counting when it is nearer the light
// than distance - bias (m); `specular` gets the weight of the occluders that are
// reflectors or refractors. Outside the map's frustum (it holds the whole scene) nothing
// occludes. A refractor occluder counts from refractorBias on: a point of a medium that
// fills the refractors, just behind a water surface, is in the water, lit only through it.
//
// A surface point passes its position p and its normal n on the light's side; a point in
// a medium passes n = 0. The bias lets a surface that meets the receiver (a wall's foot
// on the floor) through: its texels are nearer the light than the receiver by less than
// the bias for a few centimetres from the contact. So an occluder within the bias still
// counts where it stands above the receiver's tangent plane more steeply than the
// receiver's own neighbouring texels can (CausticsContactOccluder).
float CausticsShadowVisibility(sampler2D shadowPosition, sampler2D shadowNormal, vec4 clip,
  float distance, float bias, float refractorBias, int lightType, vec3 origin, vec3 axis,
  vec3 p, vec3 n, out float specular)
{
  specular = 0.0;
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  if (!(clip.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))))
  {
    return 1.0;
  }
  float visibility = 0.0;
  vec2 size = vec2(textureSize(shadowPosition, 0));
  vec2 st = uv * size - 0.5;
  vec2 base = floor(st);
  vec2 f = st - base;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 texelIndex = clamp(ivec2(base) + ivec2(i, j), ivec2(0), ivec2(size) - 1);
      vec4 occluder = texelFetch(shadowPosition, texelIndex, 0);
      float weight = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      float nearer = occluder.w < 0.0
        ? -1.0
        : distance - CausticsLightDistance(occluder.xyz, lightType, origin, axis);
      // Within the bias, a surface point's candidate contact needs the occluder's normal.
      bool candidate = nearer > 1e-5 * abs(distance) && nearer <= max(bias, refractorBias) &&
        dot(n, n) > 0.0;
      vec4 occluderNormal = candidate || nearer > min(bias, refractorBias)
        ? texelFetch(shadowNormal, texelIndex, 0)
        : vec4(0.0, 0.0, 0.0, -1.0);
      vec3 toLight = lightType == 0 ? -axis : normalize(origin - occluder.xyz);
      bool contact =
        candidate && CausticsContactOccluder(occluder.xyz, occluderNormal.xyz, toLight, p, n);
      // The role only where an occluder may count (its texel read once, as before).
      int role = nearer <= min(bias, refractorBias) && !contact
        ? -1
        : int(occluderNormal.w + 0.5);
      if (nearer <= (role == ROLE_REFRACTOR ? refractorBias : bias) && !contact)
      {
        visibility += weight;
      }
      else
      {
        specular += role == ROLE_REFLECTOR || role == ROLE_REFRACTOR ? weight : 0.0;
      }
    }
  }
  return visibility;
}

// The medium's transmittance between p and the camera: with CAUSTICS_CAMERA_OPTICAL_DEPTH
// one fetch of the volume (from the near plane), else, or outside the view, the march
// from p to `from` (the caller's eye or near-plane point).
vec3 CausticsMediumTransmittanceToCamera(vec3 p, vec3 from)
{
  if (causticsMediumOn == 0)
  {
    return vec3(1.0);
  }
#ifdef CAUSTICS_CAMERA_OPTICAL_DEPTH
  vec4 clip = causticsCameraWorldToClip * vec4(p, 1.0);
  vec2 ndc = clip.xy / clip.w;
  if (clip.w > 0.0 && all(lessThanEqual(abs(ndc), vec2(1.0))))
  {
    vec4 near = causticsCameraClipToWorld * vec4(ndc, -1.0, 1.0);
    vec3 size = vec3(textureSize(causticsCameraDepthVolume, 0));
    float s = (distance(p, near.xyz / near.w) - causticsCameraDepthRange.x) /
      max(causticsCameraDepthRange.y - causticsCameraDepthRange.x, 1e-30);
    // Slices sit at the texel centres; before the first the medium has not begun.
    vec3 coordinate = vec3(0.5 * ndc + 0.5, (clamp(s, 0.0, 1.0) * (size.z - 1.0) + 0.5) / size.z);
    float depth = s <= 0.0 ? 0.0 : texture(causticsCameraDepthVolume, coordinate).r;
    return CausticsTransmittance(causticsSigmaT, depth);
  }
#endif
  return CausticsMediumTransmittance(p, from - p, 0.0, 1.0);
}

// One entry per mesh (vtkCausticsSceneGeometry::UploadMaterials).
struct CausticsMaterial
{
  vec4 albedoRole;  // rgb: diffuse albedo, a: role
  vec4 params;      // x: IOR, y: roughness
  vec4 metalN;      // rgb: real part of the complex IOR (reflectors)
  vec4 metalK;      // rgb: imaginary part
  vec4 attenuation; // rgb: Beer-Lambert absorption inside refractors, 1/m
};

#ifndef CAUSTICS_NO_MATERIALS
layout(std430, binding = CAUSTICS_MATERIAL_BINDING) readonly buffer CausticsMaterials
{
  CausticsMaterial causticsMaterials[];
};
#endif
