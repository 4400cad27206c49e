// Caustics via distance impostors (vtkCausticsImpostorPhotonPass,
// 004_4da4b323b51d1415.txt §4-5). One thread per emitted photon (the shared
// vtkCausticsPhotonEmitter's grid: the first specular event, both Fresnel branches):
// 1. inside a refractor: Hit() against its refractor map (§4: the exit point and
//    normal seen from the map's reference point); where it has no surface ahead,
//    against the environment map (an open refractor, a water sheet, has no exit
//    below: the photon meets the pool's floor); Beer-Lambert over the chord;
// 2. in air: Hit() against the environment map of what the photon left (§3: the
//    refractors' map holds receivers and mirrors, the mirrors' map receivers and
//    refractors), and, leaving a mirror that sees itself, against the mirrors' own
//    map too, the nearer hit (ImpostorEnvironmentSearch); a participating medium
//    attenuates the stretch;
// 3. at a mirror or a refractor, the shared CausticsSurfaceInteraction: one branch
//    by Russian roulette on the exact Fresnel weights, the flux divided by its
//    probability (unbiased; total internal reflection stays inside); at most
//    maximumEvents events, of which at most impostorReflectorBounces mirror-to-mirror
//    reflections in a row;
// 4. at a receiver lit on the side the camera sees: the landed record (photon
//    record layout, vtkCausticsCommon.glsl) and its kernel radius, for
//    vtkCausticsPhotonSplatter (§5: the hits are splatted). The maps hold world
//    positions, so the receiver need not be in the camera's or the light's view;
// 5. where each photon's light went (vtkCausticsPhotonStatistics.glsl): landed
//    (STAT_HITS), out of the scene or on a receiver's side the camera does not see
//    (STAT_ESCAPED), or lost (STAT_LOST_INSIDE: a map texel with no surface, a
//    surface that is neither glass, mirror nor receiver, maximumEvents reached).
// The caustic store is filled from the landed records afterwards by the shared
// stage of every technique (glsl/vtkCausticsCausticStoreCS.glsl).
// Where glass and mirrors are traced as triangles (exactSpecular, as the camera view:
// some specular mesh is not a convex solid), every specular surface comes from the
// triangles (SpecularTrace) and the maps give only what lies around them: a photon
// inside a bunny meets its ears, and one that leaves glass may meet it again.
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D emitPosition;  // xyz, w = 0 none, 1 in air, 2 inside a refractor
uniform sampler2D emitDirection; // xyz unit, w = texel measure
uniform sampler2D emitFlux;      // rgb W
uniform sampler2D lightNormal;   // the light's G-buffer: w = role of the first surface
uniform sampler2D lightPosition; // its position: w = material of the first surface
uniform int emitResolution;      // N: rows of one branch
uniform ivec2 photonGrid;        // the emitter's grid (= the output grid)
uniform uint frameSeed;          // seed of the Russian roulette
uniform int lightType;           // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;        // point and spot lights
uniform vec3 lightEye;           // the light's view: a directional light's eye plane
uniform vec3 lightAxis;
uniform vec3 cameraPosition;
uniform vec3 cameraDirection; // towards the focal point
uniform int cameraParallel;
uniform vec3 boundsMin; // the scene's box (m): searches stay inside it
uniform vec3 boundsMax;
uniform float tolerance; // m: a search starts this far from its surface
uniform int maximumEvents;
uniform float spacings; // kernel radius in photon spacings
uniform int exactSpecular; // 1: glass and mirrors traced as triangles (SpecularTrace)

layout(rgba32f, binding = 0) uniform writeonly image2D outPosition;
layout(rgba32f, binding = 1) uniform writeonly image2D outNormal;
layout(rgba32f, binding = 2) uniform writeonly image2D outFlux;
layout(r32f, binding = 3) uniform writeonly image2D outRadius;

void NoPhoton(ivec2 g)
{
  imageStore(outPosition, g, vec4(0.0));
  imageStore(outNormal, g, vec4(0.0));
  imageStore(outFlux, g, vec4(0.0));
  imageStore(outRadius, g, vec4(0.0));
}

// The next surface along o + t d: in air, the environment map of what the photon
// left; inside a refractor, its own map (the exit, §4), or, where that map has no
// surface ahead (an open refractor such as a water sheet has no exit below), the
// environment's. A closed refractor resting on a floor meets the floor exactly where
// it leaves, and the environment map there is not consulted: a photon at its
// bottom face leaves it (or is reflected back in) as physics says. `bounces`: the
// mirror-to-mirror reflections in a row so far. With exactSpecular, glass and mirrors
// are the triangles' alone (a map's specular texel shows the same surface less
// exactly), and the nearer of the triangle and the map's receiver is the hit.
struct PhotonHit
{
  float t;
  ivec3 texel;          // the map's texel (not exact)
  bool exact;           // a traced triangle
  SpecularHit triangle; // exact: the triangle's material and normals
};

bool NextSurface(vec3 o, vec3 d, bool inside, int leftRole, int bounces, out PhotonHit hit)
{
  bool traced = exactSpecular != 0 && SpecularTrace(o, d, tolerance, 3.0e38, hit.triangle);
  float t = 3.0e38;
  ivec3 texel = ivec3(0);
  bool found = exactSpecular == 0 && inside &&
    ImpostorSearch(IMPOSTOR_REFRACTOR_SURFACE, o, d, boundsMin, boundsMax, tolerance, t, texel);
  // Traced, the mirrors meet themselves through their triangles: their own map is not
  // searched (its texel would hide the receiver the environment map holds beyond).
  int selfBounces = exactSpecular != 0 ? impostorReflectorBounces : bounces;
  found = found ||
    ImpostorEnvironmentSearch(o, d, inside ? ROLE_REFRACTOR : leftRole, selfBounces, boundsMin,
      boundsMax, tolerance, t, texel);
  if (found && exactSpecular != 0)
  {
    int role = int(texelFetch(impostorNormal, texel, 0).w + 0.5);
    found = role != ROLE_REFLECTOR && role != ROLE_REFRACTOR;
  }
  hit.exact = traced && (!found || hit.triangle.t <= t + tolerance);
  hit.t = hit.exact ? hit.triangle.t : t;
  hit.texel = texel;
  return hit.exact || found;
}

void main()
{
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, photonGrid)))
  {
    return;
  }
  vec4 p = texelFetch(emitPosition, g, 0);
  vec4 e = texelFetch(emitDirection, g, 0);
  vec3 flux = texelFetch(emitFlux, g, 0).rgb;
  if (!(p.w > 0.5) || !(CausticsChannelSum(flux) > 0.0) || !AllFinite(p.xyz) || !AllFinite(e.xyz))
  {
    NoPhoton(g);
    return;
  }
  ivec2 lightTexel = ivec2(g.x, g.y % emitResolution);
  vec3 o = p.xyz;
  vec3 d = e.xyz;
  float measure = e.w; // the beam one photon stands for (m^2 or sr)
  bool inside = p.w > 1.5;
  // What the photon left: the first surface the light sees there.
  int leftRole = int(texelFetch(lightNormal, lightTexel, 0).w + 0.5);
  // The refractor it is in: from the start, the one the emitter refracted it into (a
  // water sheet has no exit face, and its floor takes the water's absorption from it).
  int insideMaterial = inside ? int(texelFetch(lightPosition, lightTexel, 0).w + 0.5) : -1;
  float path = lightType == 0 ? dot(o - lightEye, lightAxis) : length(o - lightOrigin);
  // The participating medium between the light and the first specular surface.
  vec3 towardsLight = lightType == 0 ? -lightAxis : normalize(lightOrigin - o);
  float reach = lightType == 0 ? 3.0e38 : distance(o, lightOrigin);
  flux *= CausticsMediumTransmittance(o, towardsLight, 0.0, reach);
  uint rng = CausticsHash(uint(g.x + g.y * photonGrid.x) ^ CausticsHash(frameSeed));
  // The first roulette (a lens's exit) decides most of the photons' fate: stratified
  // over the grid, so that the light converging on a focus is not speckled.
  bool stratified = true;
  uint rotation = CausticsHash(frameSeed ^ 0x68e31da4u);
  int bounces = 0; // mirror-to-mirror reflections in a row
  atomicAdd(statistics[STAT_PHOTONS], 1u);
  AddFlux(STAT_FLUX_IN, CausticsChannelSum(flux));

  bool left = false; // out of the scene or out of sight; else lost unless landed
  for (int event = 0; event < maximumEvents && CausticsChannelSum(flux) > 0.0; ++event)
  {
    PhotonHit hit;
    if (!NextSurface(o, d, inside, leftRole, bounces, hit))
    {
      left = true;
      break;
    }
    float t = hit.t;
    vec3 h = o + t * d;
    int material;
    int role;
    vec3 n;
    if (hit.exact)
    {
      material = hit.triangle.material;
      role = int(causticsMaterials[material].albedoRole.a + 0.5);
      n = CausticsTriangleNormal(
        d, hit.triangle.shading, hit.triangle.geometric, causticsMaterials[material], role);
    }
    else
    {
      vec4 surface = texelFetch(impostorPosition, hit.texel, 0);
      vec4 normalRole = texelFetch(impostorNormal, hit.texel, 0);
      material = int(surface.w + 0.5);
      role = int(normalRole.w + 0.5);
      if (!(dot(normalRole.xyz, normalRole.xyz) > 0.0))
      {
        break;
      }
      n = ImpostorSmoothNormal(hit.texel.z / 6, h, hit.texel);
    }
    if (inside)
    {
      // Beer-Lambert over the chord, with the refractor's own absorption (the
      // material of the exit face, or, towards an open refractor's floor, of the
      // face the photon entered by).
      int absorbing = role == ROLE_REFRACTOR ? material : insideMaterial;
      flux *= absorbing >= 0 ? CausticsTransmittance(causticsMaterials[absorbing].attenuation.rgb, t)
                             : vec3(1.0);
    }
    if (CausticsStretchInMedium(inside))
    {
      flux *= CausticsMediumTransmittance(o, d, 0.0, t);
    }
    path += t;
    if (role == ROLE_REFLECTOR || role == ROLE_REFRACTOR)
    {
      bounces = role == ROLE_REFLECTOR && leftRole == ROLE_REFLECTOR ? bounces + 1 : 0;
      // A traced triangle's face tells the side (a closed mesh's inside), as in the
      // camera view; otherwise the photon's own count of crossings does.
      inside = hit.exact && role == ROLE_REFRACTOR ? dot(d, hit.triangle.geometric) > 0.0 : inside;
      bool wasInside = inside;
      float u = stratified ? CausticsGridStratified(g, rotation) : CausticsRandom(rng);
      stratified = false;
      CausticsScatterOneBranchBy(u, n, causticsMaterials[material], role, d, flux, inside);
      insideMaterial = inside && !wasInside ? material : insideMaterial;
      leftRole = role;
      o = h;
      continue;
    }
    // The normal check: light arrives on the side of the receiver the camera sees.
    vec3 towardsCamera = cameraParallel != 0 ? -normalize(cameraDirection)
                                             : normalize(cameraPosition - h);
    vec3 facing = dot(n, towardsCamera) >= 0.0 ? n : -n;
    float cosine = dot(-d, facing);
    if (role != ROLE_RECEIVER || !(cosine >= 0.0) || !AllFinite(flux) || !AllFinite(h))
    {
      left = role == ROLE_RECEIVER && !(cosine >= 0.0); // lit the side the camera does not see
      break;
    }
    // The landed record; the radius spans `spacings` photon spacings of the
    // unoccluded beam one photon stands for.
    float distance = lightType == 0 ? 1.0 : path;
    float radius = spacings * distance * sqrt(measure / max(cosine, 1e-3));
    imageStore(outPosition, g, vec4(h, max(path, 1e-6)));
    imageStore(outNormal, g, vec4(n, abs(dot(n, d))));
    imageStore(outFlux, g, vec4(flux, measure));
    imageStore(outRadius, g, vec4(radius));
    atomicAdd(statistics[STAT_HITS], 1u);
    AddFlux(STAT_FLUX_HITS, CausticsChannelSum(flux));
    return;
  }
  float power = AllFinite(flux) ? CausticsChannelSum(flux) : 0.0;
  if (left)
  {
    atomicAdd(statistics[STAT_ESCAPED], 1u);
    AddFlux(STAT_FLUX_ESCAPED, power);
  }
  else if (power > 0.0)
  {
    atomicAdd(statistics[STAT_LOST_INSIDE], 1u);
    AddFlux(STAT_FLUX_LOST_INSIDE, power);
  }
  NoPhoton(g);
}
