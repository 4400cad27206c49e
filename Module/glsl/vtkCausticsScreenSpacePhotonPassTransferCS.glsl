// What each photon does at its first hit (000_54cf099eeccf42d9.txt §2.3, §3.1):
// 1. its flux loses what the segment absorbed: Beer-Lambert inside a refractor,
//    the medium's extinction (within the scene's bounds) in air, and inside
//    refractors too when the medium fills them;
// 2. on a receiver it ends (caustic shadowing falls out of first-hit termination,
//    §1.2): a landed photon record (vtkCausticsCommon.glsl) and its kernel radius
//    for vtkCausticsPhotonSplatter at its texel of the emitter grid, if the camera
//    sees the side the photon lit (the radius pass widens the radius later);
// 3. on a reflector or refractor, below the bounce limit, it is reflected or
//    refracted with the exact Fresnel weight: conductors scale the flux; at a
//    dielectric one branch is chosen with probability R (reflection) or 1 - R, so
//    the flux is kept and energy is conserved on average (total internal
//    reflection: always reflected). The result goes to the next transfer map.
// Where glass and mirrors are traced as triangles (exactSpecular, as the camera view:
// some specular mesh is not a convex solid), the segment's specular surface is the
// triangle it meets (SpecularTrace), not the screen's estimate: a concave refractor's
// exit, which the layers only guess and lose off the screen. Inside such glass the photon
// then goes from interface to interface here, within this bounce (FollowInsideGlass), up
// to maxPathEvents specular events on its whole path, and the screen traces it on once
// it leaves.
// Every photon's end is counted (vtkCausticsPhotonStatistics.glsl): landed
// (STAT_HITS), left the view it is traced in or lit a receiver's side the camera does
// not see (STAT_ESCAPED), or lost (STAT_LOST_INSIDE: MaximumBounces reached on glass or
// a mirror, its path's events inside traced glass used up, the transfer map full).
layout(local_size_x = 64) in;

SSP_COUNTER(readonly);
SSP_RAYS(readonly);
SSP_PAYLOADS(readonly);
SSP_HITS(readonly);
SSP_NEXT_RAYS(writeonly);
SSP_NEXT_PAYLOADS(writeonly);
SSP_NEXT_COUNTER();
layout(rgba32f, binding = 0) uniform writeonly image2D splatPosition;
layout(rgba32f, binding = 1) uniform writeonly image2D splatNormal;
layout(rgba32f, binding = 2) uniform writeonly image2D splatFlux;
layout(r32f, binding = 3) uniform writeonly image2D splatKernelRadius;

uniform int capacity;
uniform int gridWidth;
uniform int maxEvents;
uniform mat4 worldToClip;
uniform mat4 clipToWorld;
uniform vec2 viewport;
uniform vec4 viewOrigin;   // camera position (w = 1) or view direction (w = 0)
uniform float splatRadius; // m; 0: splatRadiusPixels pixel footprints
uniform float splatRadiusPixels;
uniform uint seed;
uniform int exactSpecular; // 1: glass and mirrors traced as triangles
uniform float tolerance;   // m: a trace starts this far from its surface
uniform int maxPathEvents; // specular events a path may have with traced glass

uint Hash(uint x)
{
  // PCG output permutation (O'Neill 2014): deterministic per photon and event.
  uint state = x * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

vec3 Unproject(vec2 window, float ndcZ)
{
  vec4 p = clipToWorld * vec4(window / viewport * 2.0 - 1.0, ndcZ, 1.0);
  return p.xyz / p.w;
}

// Area (m^2) of the receiver's tangent plane at x seen by one pixel around x's
// projection, from the four corner rays (as the reference's PixelArea).
float PixelArea(vec3 x, vec3 n)
{
  vec4 clip = worldToClip * vec4(x, 1.0);
  vec2 centre = (clip.xy / clip.w * 0.5 + 0.5) * viewport;
  vec3 corners[4];
  const vec2 offsets[4] =
    vec2[4](vec2(-0.5, -0.5), vec2(0.5, -0.5), vec2(0.5, 0.5), vec2(-0.5, 0.5));
  bool valid = true;
  for (int c = 0; c < 4; ++c)
  {
    vec3 o = Unproject(centre + offsets[c], -1.0);
    vec3 d = normalize(Unproject(centre + offsets[c], 1.0) - o);
    float denominator = dot(d, n);
    float t = abs(denominator) > 1e-9 ? dot(x - o, n) / denominator : -1.0;
    valid = valid && t > 0.0;
    corners[c] = o + t * d;
  }
  float area = valid ? 0.5 * length(cross(corners[2] - corners[0], corners[3] - corners[1])) : 0.0;
  if (!(area > 0.0))
  {
    // Grazing view: the pixel's spread at this distance over the obliquity.
    vec3 o0 = Unproject(centre, -1.0);
    vec3 d0 = normalize(Unproject(centre, 1.0) - o0);
    vec3 o1 = Unproject(centre + vec2(1.0, 0.0), -1.0);
    vec3 d1 = normalize(Unproject(centre + vec2(1.0, 0.0), 1.0) - o1);
    float distance0 = dot(x - o0, d0);
    float spread = length((o1 - o0) + (d1 - d0) * distance0);
    area = spread * spread / max(abs(dot(d0, n)), 1e-3);
  }
  return area;
}

// The segment's hit with glass and mirrors traced as triangles: the triangle o + t d
// meets, where the screen found a glass or mirror surface (the same surface, less
// exactly) or nothing. A receiver the screen found stands (so does water's floor, with
// no triangle below), even where a triangle comes first: the photon would then need
// another bounce, and at MaximumBounces (3) it was lost (the mirror cup seen obliquely:
// 15.1 % against 16.4 %, but flux 0.977 against 0.981).
void TracedHit(vec3 o, vec3 d, inout float t, inout vec3 x, inout vec3 n, inout int materialIndex)
{
  SpecularHit triangle;
  if (exactSpecular == 0 || !SpecularTrace(o, d, tolerance, 3.0e38, triangle))
  {
    return;
  }
  int screenRole = t >= 0.0 ? int(causticsMaterials[materialIndex].albedoRole.a + 0.5) : ROLE_NONE;
  if (t >= 0.0 && screenRole != ROLE_REFLECTOR && screenRole != ROLE_REFRACTOR)
  {
    return;
  }
  t = triangle.t;
  x = o + t * d;
  materialIndex = triangle.material;
  CausticsMaterial material = causticsMaterials[materialIndex];
  n = CausticsTriangleNormal(
    d, triangle.shading, triangle.geometric, material, int(material.albedoRole.a + 0.5));
}

// One branch at a dielectric for photon `photon` at its event `event`: refracted with
// probability 1 - R (the flux kept as it is), else reflected (always under total
// internal reflection); `state` follows the side the photon ends on.
vec3 DielectricBranch(CausticsInteraction s, uint photon, int event, inout float state)
{
  float u = float(Hash(photon ^ Hash(uint(event) + seed)) >> 8) / 16777216.0;
  bool refracts = s.transmits && !(u < s.reflectedWeight.r);
  state = refracts ? (s.entering ? 2.0 : 1.0) : state;
  return refracts ? s.refracted : s.reflected;
}

// A photon inside glass traced as triangles, at x heading d (state 2) in `material`:
// followed from interface to interface as the screen's bounces would (absorption,
// exact Fresnel, one branch by the photon's own numbers), until it leaves into air
// (state 1), meets no triangle (an open sheet's water: the screen finds its floor) or
// runs out of events (false: lost, as the reference drops a path past its events;
// `events`: the path's events before this one).
// `path` grows by the distance. Not where a medium fills the refractors: the screen's
// bounces hand every stretch to the volume caustics.
bool FollowInsideGlass(inout vec3 x, inout vec3 d, inout float state, inout int material,
  inout vec3 flux, inout float path, uint photon, int events)
{
  if (exactSpecular == 0 || CausticsStretchInMedium(true))
  {
    return true;
  }
  for (int k = events + 1; k < maxPathEvents && state > 1.5; ++k)
  {
    SpecularHit triangle;
    if (!SpecularTrace(x, d, tolerance, 3.0e38, triangle))
    {
      return true;
    }
    CausticsMaterial surface = causticsMaterials[triangle.material];
    int role = int(surface.albedoRole.a + 0.5);
    if (role != ROLE_REFRACTOR)
    {
      return true; // a mirror in the glass: the screen's next bounce meets it
    }
    flux *= CausticsTransmittance(causticsMaterials[material].attenuation.rgb, triangle.t);
    path += triangle.t;
    x += triangle.t * d;
    vec3 n = CausticsTriangleNormal(d, triangle.shading, triangle.geometric, surface, role);
    CausticsInteraction s = CausticsSurfaceInteraction(d, n, surface, role, 1.0);
    d = normalize(DielectricBranch(s, photon, k, state));
    material = triangle.material;
  }
  return !(state > 1.5);
}

// A photon's end, counted with its light.
void Landed(vec3 flux)
{
  atomicAdd(statistics[STAT_HITS], 1u);
  AddFlux(STAT_FLUX_HITS, CausticsChannelSum(flux));
}
void LeftTheView(vec3 flux)
{
  atomicAdd(statistics[STAT_ESCAPED], 1u);
  AddFlux(STAT_FLUX_ESCAPED, CausticsChannelSum(flux));
}
void Lost(vec3 flux)
{
  atomicAdd(statistics[STAT_LOST_INSIDE], 1u);
  AddFlux(STAT_FLUX_LOST_INSIDE, CausticsChannelSum(flux));
}

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(rayCount, uint(capacity)))
  {
    return;
  }
  SspHit hit = hits[i];
  SspRay ray = rays[i];
  float t = hit.position.w;
  vec3 d = ray.direction.xyz;
  vec3 x = hit.position.xyz;
  vec3 n = hit.normal.xyz;
  int materialIndex = int(hit.normal.w + 0.5);
  TracedHit(ray.origin.xyz, d, t, x, n, materialIndex);
  SspPayload payload = payloads[i];
  if (!(t >= 0.0))
  {
    LeftTheView(payload.flux.rgb); // out of the scene, or off the view it is traced in
    return;
  }
  CausticsMaterial material = causticsMaterials[materialIndex];
  int role = int(material.albedoRole.a + 0.5);
  vec3 flux = payload.flux.rgb;
  int events = int(payload.flux.a + 0.5);
  bool inside = ray.origin.w > 1.5;

  // 1. Absorption along the segment.
  if (inside && ray.direction.w >= 0.0)
  {
    // Inside the refractor the photon last entered or reflected in: its surface.
    flux *= CausticsTransmittance(causticsMaterials[int(ray.direction.w + 0.5)].attenuation.rgb, t);
  }
  if (CausticsStretchInMedium(inside))
  {
    flux *= CausticsMediumTransmittance(ray.origin.xyz, d, 0.0, t);
  }
  if (!(dot(n, n) > 0.25) || !(dot(flux, vec3(1.0)) > 0.0))
  {
    if (dot(flux, vec3(1.0)) > 0.0)
    {
      Lost(flux); // no normal there
    }
    return;
  }
  n = normalize(n);

  // 2. Receivers end the photon.
  if (role == ROLE_RECEIVER)
  {
    vec3 toCamera = viewOrigin.w > 0.0 ? viewOrigin.xyz - x : -viewOrigin.xyz;
    if (dot(-d, n) * dot(toCamera, n) <= 0.0)
    {
      LeftTheView(flux); // lit the side the camera does not see
      return;
    }
    float radius = splatRadius > 0.0 ? splatRadius : splatRadiusPixels * sqrt(PixelArea(x, n));
    if (!(radius > 0.0) || isinf(radius))
    {
      Lost(flux);
      return;
    }
    // At the photon's texel of the emitter grid, where its neighbours are found.
    uint id = payload.info.x;
    ivec2 texel = ivec2(int(id % uint(gridWidth)), int(id / uint(gridWidth)));
    imageStore(splatPosition, texel, vec4(x, uintBitsToFloat(payload.info.y) + t));
    imageStore(splatNormal, texel, vec4(n, abs(dot(n, d))));
    imageStore(splatFlux, texel, vec4(flux, uintBitsToFloat(payload.info.z)));
    imageStore(splatKernelRadius, texel, vec4(radius));
    Landed(flux);
    return;
  }

  // 3. Specular surfaces send it on, up to the bounce limit.
  if ((role != ROLE_REFLECTOR && role != ROLE_REFRACTOR) || events >= maxEvents)
  {
    Lost(flux);
    return;
  }
  CausticsInteraction s = CausticsSurfaceInteraction(d, n, material, role, 1.0);
  vec3 direction = s.reflected;
  float state = ray.origin.w;
  if (role == ROLE_REFLECTOR)
  {
    flux *= s.reflectedWeight;
  }
  else
  {
    direction = DielectricBranch(s, payload.info.x, events, state);
  }
  float path = uintBitsToFloat(payload.info.y) + t;
  direction = normalize(direction);
  if (role == ROLE_REFRACTOR &&
    !FollowInsideGlass(x, direction, state, materialIndex, flux, path, payload.info.x, events))
  {
    Lost(flux);
    return;
  }
  if (!(dot(flux, vec3(1.0)) > 0.0))
  {
    return;
  }
  uint index = atomicAdd(nextCount, 1u);
  if (index >= uint(capacity))
  {
    Lost(flux);
    return;
  }
  nextRays[index].origin = vec4(x, state);
  nextRays[index].direction = vec4(direction, float(materialIndex));
  nextPayloads[index].flux = vec4(flux, float(events + 1));
  nextPayloads[index].info = uvec4(payload.info.x, floatBitsToUint(path), payload.info.zw);
}
