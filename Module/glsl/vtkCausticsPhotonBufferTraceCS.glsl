// The photon buffer (001_7c07a484f7a872bb.txt §2, Fig. 2): every emitted photon
// (vtkCausticsPhotonEmitter: after its first specular interaction) is followed to
// the diffuse receiver it lands on. Three phases, three programs (PHASE), and a
// fourth with the caustic store (PHASE 3, below: whether its final render draws):
// 0. sort, one thread per texel: photons are counted; those in air are handed
//    over to phase 2, those inside a refractor listed for phase 1;
// 1. inside, one thread per listed photon: the exit is found on the refractor's
//    back faces (or front faces, for a photon heading back towards the light) as
//    the light sees them, Beer-Lambert absorption applies on the way, and the
//    photon refracts out with exact Fresnel; total internal reflection continues
//    inside, up to maximumInternalEvents interfaces. At a partial exit the photon
//    goes on inside with probability R (Russian roulette) where the glass is traced
//    as triangles; between the layers the part reflected back inside is not
//    followed to the surfaces (counted), since their exit fits only directions that
//    come from the light (an 8 % overshoot under a sun parallel to the floor). A medium
//    that fills the refractors takes its share on each stretch and, when it
//    scatters, the stretch is appended for the volume caustics (as phase 2's), and so
//    are the stretches of that reflected part (its volume light only);
// 2. in air, one thread per listed photon: the hit is found on the receivers as
//    the caustic map's view sees them (a receiver-only depth layer), else on the
//    receivers hidden behind them (a second, peeled layer, when the technique has
//    one: its photons' measure is negated for the hidden receivers' map); a mirror met
//    before it (a mirror-only layer of the same view) reflects the photon with the
//    conductor's Fresnel reflectance, up to maximumReflections times, after which
//    a mirror in the way stops it (it no longer passes through). With
//    CAUSTICS_STORE_ESCAPED, a photon that neither layer lands (a ceiling above
//    the light, a wall beyond the map's frame) is searched in the distance
//    impostors' environment map, and one that lands on a receiver there adds its
//    flux to their caustic store (ImpostorDepositCaustic), which the final render
//    reads where the caustic map does not see (vtkCausticsCausticMap::ApplyStore).
// Lists keep every thread of a work group busy: Mesa's llvmpipe runs the
// instructions of branches no lane takes, so a texel-wide dispatch would pay
// for the tracing code at every empty texel.
// Each layer crossing: plane steps (the ray is intersected with the plane of the
// surface seen where the estimate projects, until the estimate stops moving;
// exact in one step on a plane), with a march + bisection fallback.
// With a scattering medium (CAUSTICS_VOLUME_SEGMENT_APPEND), phase 2 appends each
// straight piece in air, mirror to mirror to receiver (or to where it leaves the
// scene), and, when the medium fills the refractors, phase 1 each piece inside,
// interface to interface, for the line-based volume caustics (vtkCausticsVolumeLines):
// pieces after the first specular event only, the light's own beam being
// vtkCausticsAirlight's.
// Output per photon: hit position (w = path length from the light, > 0 marks a
// hit), receiver normal (as modelled; w = |N.D|), flux (rgb W; a = the texel's
// measure omega_i, m^2 or sr).
#if PHASE == 0
layout(local_size_x = 8, local_size_y = 8) in;
#else
layout(local_size_x = 64) in;
#endif

uniform sampler2D photonPosition;   // xyz, w = 0 none, 1 in air, 2 inside a refractor
uniform sampler2D photonDirection;  // xyz unit, w = texel measure
uniform sampler2D photonFlux;       // rgb W
uniform sampler2D frontPosition;    // refractors' nearest surfaces seen from the light
uniform sampler2D frontNormal;
uniform sampler2D backPosition;     // refractors' farthest surfaces seen from the light
uniform sampler2D backNormal;
uniform sampler2D receiverPosition; // receivers seen by the caustic map's view
uniform sampler2D receiverNormal;
uniform sampler2D reflectorPosition; // mirrors seen by the caustic map's view
uniform sampler2D reflectorNormal;
uniform int hasReflectors;           // 0: the scene has no mirror (the layer is not read)
uniform sampler2D hiddenPosition;    // receivers behind the first ones, facing the light
uniform sampler2D hiddenNormal;      // (the hidden receivers' map; same view and size)
uniform int hasHiddenReceivers;      // 0: no such layer (not read)
uniform int maximumReflections;      // mirrors a photon in air may meet
uniform CausticsView photonView;    // the view the emitter's texels come from
uniform CausticsView mapView;
uniform ivec2 gridSize;
uniform int lightType; // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;
uniform int maximumInternalEvents;
uniform int marchSteps;
uniform float chordLength; // longest straight path inside the refractors (m)
uniform float airLength;   // longest straight path through the scene (m)
uniform vec3 receiverLow;  // the receivers' bounds, slightly enlarged
uniform vec3 receiverHigh;
uniform int exactSpecular; // 1: inside, the glass's triangles (SpecularTrace), not the slab

// The photon buffer, also the hand-over between the two phases (PHASE 0 inside
// refractors, PHASE 1 in air; two programs, so that each stays small): after
// phase 0 a texel holds the photon leaving into air (position, path length;
// direction, 1 = in air, 2 + the sheet's material = in the water under an open sheet;
// flux, measure), after
// phase 1 its hit.
layout(rgba32f, binding = 0) uniform image2D outPosition;
layout(rgba32f, binding = 1) uniform image2D outNormal;
layout(rgba32f, binding = 2) uniform image2D outFlux;

// Work lists: control words as the hierarchy's (list lengths at
// CONTROL_LIST_COUNT + 0 (inside) and + 1 (in air), their dispatch arguments at
// CONTROL_DISPATCH + 0 and + 3), then the two lists of packed texels.
layout(std430, binding = CAUSTICS_HIERARCHY_CONTROL_BINDING) buffer PhotonLists
{
  uint lists[];
};
uniform uint listCapacity; // entries per list

void Append(int list, ivec2 texel)
{
  uint slot = atomicAdd(lists[CONTROL_LIST_COUNT + list], 1u);
  lists[uint(CONTROL_SIZE) + uint(list) * listCapacity + slot] =
    uint(texel.x) | (uint(texel.y) << 16);
}

// The texel of this thread's list entry (false past the list's end).
bool Listed(int list, out ivec2 texel)
{
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint item = group * 64u + gl_LocalInvocationIndex;
  texel = ivec2(0);
  if (item >= lists[CONTROL_LIST_COUNT + list])
  {
    return false;
  }
  uint code = lists[uint(CONTROL_SIZE) + uint(list) * listCapacity + item];
  texel = ivec2(int(code & 0xFFFFu), int(code >> 16));
  return true;
}


// The surface a layer shows at the texel of x; false where it shows none.
bool LayerAt(CausticsView v, sampler2D lp, sampler2D ln, vec3 x, out vec3 s, out vec3 n,
  out float material)
{
  vec2 pixel;
  s = vec3(0.0);
  n = vec3(0.0, 0.0, 1.0);
  material = -1.0;
  if (!ViewProject(v, x, pixel))
  {
    return false;
  }
  ivec2 texel = ViewTexel(v, pixel);
  vec4 p = texelFetch(lp, texel, 0);
  if (p.w < 0.0)
  {
    return false;
  }
  s = p.xyz;
  n = texelFetch(ln, texel, 0).xyz;
  material = p.w;
  return true;
}

// True if x lies on the surface the layer shows at x's texel (within the texel's
// footprint on that surface).
bool OnLayer(CausticsView v, sampler2D lp, sampler2D ln, vec3 x)
{
  vec3 s, n;
  float material;
  if (!LayerAt(v, lp, ln, x, s, n, material))
  {
    return false;
  }
  float facing = abs(dot(n, ViewAway(v, x)));
  return distance(x, s) <= 2.0 * ViewTexelSize(v, x) / max(facing, 0.05);
}

// Plane step: where the ray meets the plane of the surface the layer shows at x.
bool PlaneStep(CausticsView v, sampler2D lp, sampler2D ln, vec3 o, vec3 d, vec3 x, out float t)
{
  vec3 s, n;
  float material;
  t = -1.0;
  if (!LayerAt(v, lp, ln, x, s, n, material))
  {
    return false;
  }
  float dn = dot(d, n);
  if (abs(dn) < 1e-6)
  {
    return false;
  }
  t = dot(s - o, n) / dn;
  return true;
}

// Side of the layer x is on: -1 in front (towards the light), +1 behind, 0 where
// the layer shows nothing.
float LayerSide(CausticsView v, sampler2D lp, sampler2D ln, vec3 x)
{
  vec3 s, n;
  float material;
  if (!LayerAt(v, lp, ln, x, s, n, material))
  {
    return 0.0;
  }
  return ViewDepth(v, x) >= ViewDepth(v, s) ? 1.0 : -1.0;
}

// Plane steps: the ray is intersected with the plane of the surface the layer
// shows where the estimate projects, until the estimate stops moving (exact in
// one step on a plane, fast on smooth surfaces); true if it converges onto the layer.
bool PlaneSteps(CausticsView v, sampler2D lp, sampler2D ln, vec3 o, vec3 d, float tMin,
  float tMax, out float tHit)
{
  tHit = -1.0;
  float t = tMin;
  for (int k = 0; k < 8; ++k)
  {
    vec3 x = o + t * d;
    float next;
    if (!PlaneStep(v, lp, ln, o, d, x, next) || !(next > tMin) || next > tMax)
    {
      return false;
    }
    if (abs(next - t) <= 0.01 * ViewTexelSize(v, x) + 1e-6 * next)
    {
      tHit = next;
      return OnLayer(v, lp, ln, o + next * d);
    }
    t = next;
  }
  return false;
}

// First crossing of the ray o + t d, t in (tMin, tMax], with the layer's surface,
// coming from side `from` (-1: from in front, +1: from behind): plane steps, else
// a march that brackets the first change of side, bisection and a plane step.
bool LayerHit(CausticsView v, sampler2D lp, sampler2D ln, vec3 o, vec3 d, float tMin, float tMax,
  float from, out float tHit)
{
  if (PlaneSteps(v, lp, ln, o, d, tMin, tMax, tHit))
  {
    return true;
  }
  tHit = -1.0;
  float previousT = tMin;
  float previousSide = LayerSide(v, lp, ln, o + tMin * d);
  for (int i = 1; i <= marchSteps; ++i)
  {
    float ti = tMin + (tMax - tMin) * float(i) / float(marchSteps);
    float side = LayerSide(v, lp, ln, o + ti * d);
    if (previousSide == from && side == -from)
    {
      float a = previousT, b = ti;
      for (int j = 0; j < 12; ++j)
      {
        float c = 0.5 * (a + b);
        if (LayerSide(v, lp, ln, o + c * d) == from)
        {
          a = c;
        }
        else
        {
          b = c;
        }
      }
      float planeT;
      if (PlaneStep(v, lp, ln, o, d, o + b * d, planeT) && planeT > tMin &&
        abs(planeT - b) <= 2.0 * (ti - previousT) && OnLayer(v, lp, ln, o + planeT * d))
      {
        tHit = planeT;
        return true;
      }
    }
    previousSide = side;
    previousT = ti;
  }
  return false;
}

// Normal of the layer at x, bilinear between the texels showing the same surface
// (the layer holds one normal per texel centre; exits need a smooth normal).
vec3 LayerNormal(CausticsView v, sampler2D lp, sampler2D ln, vec3 x, vec3 nearest)
{
  vec2 pixel;
  ViewProject(v, x, pixel);
  vec2 f = pixel - 0.5;
  ivec2 base = ivec2(floor(f));
  vec2 w = f - floor(f);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), ivec2(v.size) - 1);
      if (texelFetch(lp, texel, 0).w < 0.0)
      {
        continue;
      }
      vec3 n = texelFetch(ln, texel, 0).xyz;
      if (dot(n, nearest) < 0.5)
      {
        continue;
      }
      sum += (i == 0 ? 1.0 - w.x : w.x) * (j == 0 ? 1.0 - w.y : w.y) * n;
    }
  }
  float length2 = dot(sum, sum);
  return length2 > 1e-12 ? sum * inversesqrt(length2) : nearest;
}

// Where x is relative to the refractor as the light sees it, a slab between its
// nearest and farthest surfaces: 0 inside, 1 beyond the back faces, 2 in front of
// the front faces, 3 outside its silhouette.
int SlabState(vec3 x)
{
  vec3 sf, nf, sb, nb;
  float mf, mb;
  if (!LayerAt(photonView, frontPosition, frontNormal, x, sf, nf, mf) ||
    !LayerAt(photonView, backPosition, backNormal, x, sb, nb, mb))
  {
    return 3;
  }
  float depth = ViewDepth(photonView, x);
  float slack = 0.5 * ViewTexelSize(photonView, x); // the layers are sampled per texel
  if (depth > ViewDepth(photonView, sb) + slack)
  {
    return 1;
  }
  if (depth < ViewDepth(photonView, sf) - slack)
  {
    return 2;
  }
  return 0;
}

// Exit of a photon inside a refractor at o heading along d. The exact answer for a
// convex refractor is on the layer it heads to (plane steps); otherwise the
// refractor is taken as the slab between its front and back faces (what two
// interfaces can describe), marched until the photon leaves it, and the exit is
// refined by bisection. Returns the distance, and the layer whose normal applies
// (1 back, 2 front; 3: through the silhouette, the normal of the last texel inside).
bool SlabExit(vec3 o, vec3 d, out float tExit, out int kind, out vec3 normal)
{
  bool away = dot(d, ViewAway(photonView, o)) >= 0.0;
  vec3 s, nearest;
  float material;
  kind = away ? 1 : 2;
  // Not the surface the photon stands on: a quarter texel on.
  float tMin = 0.25 * ViewTexelSize(photonView, o);
  bool found = away
    ? PlaneSteps(photonView, backPosition, backNormal, o, d, tMin, chordLength, tExit)
    : PlaneSteps(photonView, frontPosition, frontNormal, o, d, tMin, chordLength, tExit);
  if (!found)
  {
    float previousT = tMin;
    int state = 0;
    for (int i = 1; i <= marchSteps && state == 0; ++i)
    {
      float ti = tMin + (chordLength - tMin) * float(i) / float(marchSteps);
      state = SlabState(o + ti * d);
      if (state == 0)
      {
        previousT = ti;
        continue;
      }
      float a = previousT, b = ti;
      for (int j = 0; j < 12; ++j)
      {
        float c = 0.5 * (a + b);
        int middle = SlabState(o + c * d);
        if (middle == 0)
        {
          a = c;
        }
        else
        {
          b = c;
          state = middle;
        }
      }
      kind = state == 3 ? 3 : state;
      tExit = state == 3 ? a : b;
      if (state == 1 || state == 2)
      {
        // Finish on the crossed layer's plane when it is close.
        float planeT;
        bool onBack = state == 1;
        if ((onBack ? PlaneStep(photonView, backPosition, backNormal, o, d, o + b * d, planeT)
                    : PlaneStep(photonView, frontPosition, frontNormal, o, d, o + b * d, planeT)) &&
          abs(planeT - b) <= 2.0 * chordLength / float(marchSteps))
        {
          tExit = planeT;
        }
      }
    }
    if (state == 0)
    {
      return false; // still inside after the refractors' extent
    }
  }
  vec3 x = o + tExit * d;
  if (kind == 1)
  {
    LayerAt(photonView, backPosition, backNormal, x, s, nearest, material);
    normal = LayerNormal(photonView, backPosition, backNormal, x, nearest);
  }
  else if (kind == 2)
  {
    LayerAt(photonView, frontPosition, frontNormal, x, s, nearest, material);
    normal = LayerNormal(photonView, frontPosition, frontNormal, x, nearest);
  }
  else
  {
    // Through the silhouette: of the two layers' normals at the last texel inside,
    // the one facing along the photon.
    vec3 last = o + max(tExit - 0.5 * ViewTexelSize(photonView, o), 0.0) * d;
    vec3 nf = vec3(0.0), nb = vec3(0.0);
    LayerAt(photonView, frontPosition, frontNormal, last, s, nf, material);
    LayerAt(photonView, backPosition, backNormal, last, s, nb, material);
    normal = dot(nf, d) >= dot(nb, d) ? nf : nb;
  }
  float length2 = dot(normal, normal);
  normal = length2 > 1e-12 ? normal * inversesqrt(length2) : -d;
  return true;
}

// A flux's power summed over its channels, as the statistics count it.
float Power(vec3 flux)
{
  return CausticsChannelSum(flux);
}

// The emitted photon's flux after the medium between the light (or where its ray
// enters the medium) and the photon's first specular surface; the loss counts as
// absorbed. The medium fills the scene's bounds in air (CausticsMediumTransmittance).
vec3 ArrivedFromTheLight(vec3 p, vec3 flux)
{
  if (causticsMediumOn == 0)
  {
    return flux;
  }
  float reach = lightType == 0 ? 3.0e38 : distance(p, lightOrigin);
  vec3 kept = flux * CausticsMediumTransmittance(p, -ViewAway(photonView, p), 0.0, reach);
  AddFlux(STAT_FLUX_ABSORBED, Power(flux) - Power(kept));
  return kept;
}

#if PHASE == 0
// Phase 0: every photon the emitter made is counted; photons in air are handed
// over to phase 2 (position, path length; direction, 1; flux, measure), photons
// inside a refractor listed for phase 1.
void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, gridSize)))
  {
    return;
  }
  vec4 photon = texelFetch(photonPosition, texel, 0);
  vec4 direction = texelFetch(photonDirection, texel, 0);
  vec3 flux = texelFetch(photonFlux, texel, 0).rgb;
  int state = int(photon.w + 0.5);
  // No hit until a later phase writes one (no stale texel from the last frame).
  imageStore(outPosition, texel, vec4(0.0));
  imageStore(outNormal, texel, vec4(0.0));
  imageStore(outFlux, texel, vec4(0.0));
  if (state == 0 || !AllFinite(photon.xyz) || !AllFinite(direction.xyz) || !AllFinite(flux) ||
    !(dot(direction.xyz, direction.xyz) > 0.0))
  {
    return;
  }
  atomicAdd(statistics[STAT_PHOTONS], 1u);
  AddFlux(STAT_FLUX_IN, Power(flux));
  if (state == 2)
  {
    Append(0, texel);
    return;
  }
  vec3 p = photon.xyz;
  flux = ArrivedFromTheLight(p, flux);
  float path = lightType == 0 ? ViewDepth(photonView, p) : length(p - lightOrigin);
  imageStore(outPosition, texel, vec4(p, path));
  imageStore(outNormal, texel, vec4(normalize(direction.xyz), 1.0));
  imageStore(outFlux, texel, vec4(flux, direction.w));
  Append(1, texel);
}
#elif PHASE == 1
// One stretch of a photon inside a refractor: to the interface it meets as the light
// sees the refractor (SlabExit), losing the participating medium's share when the
// medium fills the refractors (the stretch is appended for the volume caustics) and
// the refractor's own absorption. On return p is that interface and flux what arrives
// there; `transmits` whether part of it leaves into air (along `refracted`, the part
// `reflectance` back along `mirrored`), else all of it reflects along `mirrored`
// (total internal reflection or a grazing exit). False when no exit is found.
bool InsideStretch(inout vec3 p, vec3 d, inout vec3 flux, out float t, out float reflectance,
  out vec3 mirrored, out vec3 refracted, out bool transmits)
{
  vec3 n;
  float material;
  if (exactSpecular != 0)
  {
    // The glass's triangles: the one the photon meets, its normal by the face's rules
    // (CausticsTriangleNormal). A start on the surface it stands on is skipped.
    SpecularHit hit;
    if (!SpecularTrace(p, d, 1e-4 * chordLength, 3.0e38, hit))
    {
      return false;
    }
    t = hit.t;
    material = float(hit.material);
    n = CausticsTriangleNormal(
      d, hit.shading, hit.geometric, causticsMaterials[hit.material], ROLE_REFRACTOR);
  }
  else
  {
    int kind;
    if (!SlabExit(p, d, t, kind, n))
    {
      return false;
    }
    vec3 x = p + t * d;
    vec3 s, nearest;
    bool onLayer = kind == 2
      ? LayerAt(photonView, frontPosition, frontNormal, x, s, nearest, material)
      : LayerAt(photonView, backPosition, backNormal, x, s, nearest, material);
    if (!onLayer)
    {
      // The silhouette: the material of the last texel inside.
      LayerAt(photonView, backPosition, backNormal,
        p + max(t - ViewTexelSize(photonView, p), 0.0) * d, s, nearest, material);
    }
  }
  vec3 x = p + t * d;
  int refractor = max(int(material + 0.5), 0);
  CausticsMaterial medium = causticsMaterials[refractor];
  // The participating medium when it fills the refractors (its volume caustic and
  // extinction), then the refractor's own absorption.
  flux = CausticsMediumStretch(p, d, t, flux, true, refractor) *
    CausticsTransmittance(medium.attenuation.rgb, t);
  p = x;
  // Leaving the medium: the normal facing the photon is the inward one. A normal
  // that faces the photon already belongs to a surface the slab model puts on the
  // wrong side (a concavity between the two layers): the photon leaves through it.
  n = dot(d, n) < 0.0 ? -n : n;
  float ior = max(medium.params.x, 1.0);
  // Always from inside into air, so CausticsDielectric with the two indices, and
  // the cosine dot(d, n) as it is (this trace never clamped it).
  transmits = CausticsDielectric(d, -n, dot(d, n), ior, 1.0, reflectance, mirrored, refracted) &&
    dot(d, n) > 1e-4;
  return true;
}

// Phase 1: photons inside a refractor go from interface to interface until they
// leave it; those that do are listed for phase 2.
void main()
{
  ivec2 texel;
  if (!Listed(0, texel))
  {
    return;
  }
  vec4 photon = texelFetch(photonPosition, texel, 0);
  vec4 direction = texelFetch(photonDirection, texel, 0);
  vec3 flux = ArrivedFromTheLight(photon.xyz, texelFetch(photonFlux, texel, 0).rgb);
  int state = 2;
  vec3 p = photon.xyz;
  vec3 d = normalize(direction.xyz);
  float path = lightType == 0 ? ViewDepth(photonView, p) : length(p - lightOrigin);
  float absorbed = 0.0, reflected = 0.0;
  bool underSheet = false;
  // An open refractor (a water surface: one sheet) has no back face behind the
  // entry: the farthest refractor surface the light sees there is the entry itself,
  // facing the light. The photon stays in that medium and goes on to the receivers,
  // the water's absorption taken on the way there (phase 1, SheetTransmittance).
  vec3 backSample, backNormalHere;
  float backMaterial;
  if (LayerAt(photonView, backPosition, backNormal, p, backSample, backNormalHere, backMaterial) &&
    distance(backSample, p) <= 2.0 * ViewTexelSize(photonView, p) &&
    dot(backNormalHere, ViewAway(photonView, p)) < -0.1)
  {
    state = 1;
    underSheet = true;
  }
  // Between the light's layers, the part reflected back inside at the exit (the echo),
  // followed below for the volume caustic by Russian roulette: with probability R (stratified over the
  // photons, a fixed rotation, so the frame stays deterministic) and the flux the
  // photon brought to the exit, which keeps its mean (flux x R) without a piece per photon.
  bool echo = false;
  vec3 echoFlux = vec3(0.0), echoPosition = p, echoDirection = d;
  int event = 0;
  uint rng = CausticsHash(uint(texel.x) * 0x9e3779b9u ^ uint(texel.y));
  for (; event < maximumInternalEvents && state == 2; ++event)
  {
    float t, reflectance;
    vec3 mirrored, refracted;
    bool transmits;
    vec3 arriving = flux;
    if (!InsideStretch(p, d, flux, t, reflectance, mirrored, refracted, transmits))
    {
      break;
    }
    absorbed += Power(arriving - flux);
    path += t;
    if (transmits && exactSpecular != 0)
    {
      // Traced as triangles, the part reflected back inside is followed: Russian
      // roulette between the branches with the Fresnel weights (stratified over the
      // photons at the first exit), as the reference and the impostors' photons do.
      float u = event == 0 ? CausticsGridStratified(texel, 0x68e31da4u) : CausticsRandom(rng);
      if (u < reflectance)
      {
        d = mirrored;
        continue;
      }
      d = refracted;
      state = 1;
    }
    else if (transmits)
    {
      // Between the light's two layers, whose exit a direction that does not come from
      // the light may miss, it is not (counted; its volume echo is followed below).
      reflected += Power(flux) * reflectance;
      echo = CausticsGridStratified(texel, 0x68e31da4u) < reflectance;
      echoFlux = flux;
      echoPosition = p;
      echoDirection = mirrored;
      flux *= 1.0 - reflectance;
      d = refracted;
      state = 1;
    }
    else
    {
      d = mirrored; // total internal reflection (or a grazing exit)
    }
  }
#ifdef CAUSTICS_VOLUME_SEGMENT_APPEND
  // When the medium fills the refractors the echo's light scatters inside too (the
  // reference follows it: 5 % of the volume caustic seen from inside the filled ball).
  // It is followed for its volume pieces only (what leaves at an interface is not
  // followed, as the echo itself is not for the surfaces), on by Russian roulette again
  // at each partial exit (total internal reflection keeps it), within the same
  // maximumInternalEvents pieces per photon (the list's capacity).
  if (echo && state == 1 && CausticsStretchInMedium(true))
  {
    for (; event < maximumInternalEvents; ++event)
    {
      float t, reflectance;
      vec3 mirrored, refracted;
      bool transmits;
      if (!InsideStretch(
            echoPosition, echoDirection, echoFlux, t, reflectance, mirrored, refracted, transmits) ||
        (transmits && !(CausticsRandom(rng) < reflectance)))
      {
        break;
      }
      echoDirection = mirrored;
    }
  }
#endif
  AddFlux(STAT_FLUX_ABSORBED, absorbed);
  AddFlux(STAT_FLUX_INTERNAL_REFLECTION, reflected);
  if (state == 2 || !AllFinite(p) || !AllFinite(d))
  {
    atomicAdd(statistics[STAT_LOST_INSIDE], 1u);
    AddFlux(STAT_FLUX_LOST_INSIDE, Power(flux));
    return;
  }
  imageStore(outPosition, texel, vec4(p, path));
  imageStore(outNormal, texel, vec4(d, underSheet ? 2.0 + max(round(backMaterial), 0.0) : 1.0));
  imageStore(outFlux, texel, vec4(flux, direction.w));
  Append(1, texel);
}
#elif PHASE == 3
// Phase 3, one thread, after phase 2 with the caustic store: its final render
// (vtkCausticsCausticMap::ApplyStore, a full-screen pass) is drawn only when the store
// took more than `storeDrawShare` of the flux that landed; below it, leaving that light
// out changes the caustic's flux by less than that share (the ball lens's few
// grazing photons beyond its map: 2e-4 of it).
uniform float storeDrawShare;

void main()
{
  if (gl_LocalInvocationIndex == 0u)
  {
    statistics[STAT_STORE_DRAW + 1] =
      CounterFlux(STAT_FLUX_STORED) > storeDrawShare * CounterFlux(STAT_FLUX_HITS) ? 1u : 0u;
  }
}
#else
// Phase 2: photons in air find the receiver they land on, as the caustic map sees
// receivers, searched only where the ray is inside the receivers' bounds (slab
// test; 1 / d is +-Inf on axis-parallel rays, which the test handles). A mirror
// between the photon and that receiver reflects it (second reflections, e.g. inside
// a mirror cup) and the search starts again from the mirror.

// The first receiver along p + t d, t in the receivers' bounds: true with t and
// the receiver's normal. One the first layer does not show (the ray passes behind
// it) is searched in the hidden receivers' layer, up to where the ray meets the
// first layer's back if it does: `hidden` then.
bool FindReceiver(vec3 p, vec3 d, out float t, out vec3 n, out bool hidden)
{
  vec3 inverse = 1.0 / d;
  vec3 near = (receiverLow - p) * inverse, far = (receiverHigh - p) * inverse;
  vec3 entries = min(near, far), exits = max(near, far);
  float enter = max(max(entries.x, entries.y), entries.z);
  float leave = min(min(exits.x, exits.y), exits.z);
  float start = max(1e-4 * airLength, enter);
  float end = min(airLength, leave);
  vec3 s;
  float material;
  t = -1.0;
  n = vec3(0.0, 0.0, 1.0);
  hidden = false;
  if (!(end > start))
  {
    return false;
  }
  float first;
  if (LayerHit(mapView, receiverPosition, receiverNormal, p, d, start, end, -1.0, first))
  {
    t = first;
    if (LayerAt(mapView, receiverPosition, receiverNormal, p + t * d, s, n, material) &&
      dot(d, n) < 0.0)
    {
      return true;
    }
    end = first; // a receiver reached from behind shows nothing, nor lets light through
  }
  float behind;
  if (hasHiddenReceivers != 0 && end > start &&
    LayerHit(mapView, hiddenPosition, hiddenNormal, p, d, start, end, -1.0, behind) &&
    LayerAt(mapView, hiddenPosition, hiddenNormal, p + behind * d, s, n, material) &&
    dot(d, n) < 0.0)
  {
    t = behind;
    hidden = true;
    return true;
  }
  return false;
}

// The first mirror along p + t d before `limit`, away from the mirror the photon
// may be leaving: true with t, its smoothed normal and material.
bool FindReflector(vec3 p, vec3 d, float limit, out float t, out vec3 n, out int material)
{
  t = -1.0;
  n = vec3(0.0, 0.0, 1.0);
  material = -1;
  if (hasReflectors == 0)
  {
    return false;
  }
  // Two texels off the mirror it leaves, so that the search does not meet it again.
  float start = max(1e-4 * airLength, 2.0 * ViewTexelSize(mapView, p));
  if (!(limit > start))
  {
    return false;
  }
  float from = LayerSide(mapView, reflectorPosition, reflectorNormal, p + start * d);
  vec3 s, nearest;
  float index;
  if (!LayerHit(mapView, reflectorPosition, reflectorNormal, p, d, start, limit,
        from == 0.0 ? -1.0 : from, t) ||
    !LayerAt(mapView, reflectorPosition, reflectorNormal, p + t * d, s, nearest, index))
  {
    return false;
  }
  n = LayerNormal(mapView, reflectorPosition, reflectorNormal, p + t * d, nearest);
  material = int(index + 0.5);
  return true;
}

#ifdef CAUSTICS_STORE_ESCAPED
// Where a photon no receiver layer lands meets a receiver in the distance impostors'
// environment map of what it left (`leftMirror`: a mirror's; else the refractors' when
// made), lit from the side it arrives on: its t, or -1 where there is none.
float EscapedReceiver(vec3 p, vec3 d, bool leftMirror)
{
  bool mirror = leftMirror || impostorValid[IMPOSTOR_REFRACTOR_ENVIRONMENT] == 0;
  float t;
  ivec3 texel;
  if (!ImpostorEnvironmentSearch(p, d, mirror ? ROLE_REFLECTOR : ROLE_REFRACTOR, 0, receiverLow,
        receiverHigh, 1e-4 * airLength, t, texel))
  {
    return -1.0;
  }
  vec4 normalRole = texelFetch(impostorNormal, texel, 0);
  return int(normalRole.w + 0.5) == ROLE_RECEIVER && dot(d, normalRole.xyz) < 0.0 ? t : -1.0;
}
#endif

// The Beer-Lambert absorption over t m of the water a photon under an open sheet is
// in (sheetMaterial; -1: in air, none).
vec3 SheetTransmittance(int sheetMaterial, float t)
{
  return sheetMaterial >= 0
    ? CausticsTransmittance(causticsMaterials[sheetMaterial].attenuation.rgb, t)
    : vec3(1.0);
}

void main()
{
  ivec2 texel;
  if (!Listed(1, texel))
  {
    return;
  }
  vec4 leaving = imageLoad(outNormal, texel);
  vec4 start4 = imageLoad(outPosition, texel);
  vec4 flux4 = imageLoad(outFlux, texel);
  vec3 p = start4.xyz;
  vec3 d = leaving.xyz;
  float path = start4.w;
  // In the water under an open sheet the reference holds no medium (a photon inside a
  // refractor) unless the medium fills the refractors: neither extinction nor volume
  // caustic there; the water's own absorption, as inside a closed refractor.
  bool underSheet = leaving.w > 1.5;
  int sheetMaterial = underSheet ? int(leaving.w - 2.0 + 0.5) : -1;
  bool inMedium = CausticsStretchInMedium(underSheet);
  float t = -1.0;
  vec3 n = vec3(0.0);
  bool landed = false, hidden = false, leftMirror = false;
  for (int reflection = 0; reflection <= maximumReflections; ++reflection)
  {
    landed = FindReceiver(p, d, t, n, hidden);
    float mirrorT;
    vec3 mirrorNormal;
    int mirrorMaterial;
    if (!FindReflector(p, d, landed ? t : airLength, mirrorT, mirrorNormal, mirrorMaterial))
    {
      break; // nothing in the way: it lands (or escapes)
    }
    landed = false;
    vec3 x = p + mirrorT * d;
    vec3 kept = CausticsMediumStretch(p, d, mirrorT, flux4.rgb, underSheet, sheetMaterial) *
      SheetTransmittance(sheetMaterial, mirrorT);
    vec3 facing = dot(d, mirrorNormal) < 0.0 ? mirrorNormal : -mirrorNormal;
    CausticsMaterial mirror = causticsMaterials[mirrorMaterial];
    if (reflection < maximumReflections)
    {
      kept *= FresnelConductor(
        clamp(-dot(d, facing), 0.0, 1.0), mirror.metalN.rgb, mirror.metalK.rgb);
    }
    else
    {
      kept = vec3(0.0); // one mirror too many: stopped there
    }
    AddFlux(STAT_FLUX_ABSORBED, Power(flux4.rgb) - Power(kept));
    flux4.rgb = kept;
    path += mirrorT;
    p = x;
    d = reflect(d, facing);
    leftMirror = true;
    if (!(Power(kept) > 0.0) || !AllFinite(p) || !AllFinite(d))
    {
      break;
    }
  }
  float power = Power(flux4.rgb);
  float stored = -1.0; // t of the receiver the caustic store takes the photon on
#ifdef CAUSTICS_STORE_ESCAPED
  if (!landed && power > 0.0 && AllFinite(p) && AllFinite(d))
  {
    stored = EscapedReceiver(p, d, leftMirror);
  }
#endif
  if (AllFinite(p) && AllFinite(d))
  {
    // The last piece: to the receiver, or across the scene when it escapes.
    CausticsAppendVolumeSegment(CausticsMakeMediumSegment(
      p, d, landed ? t : (stored > 0.0 ? stored : airLength), flux4.rgb, underSheet,
      sheetMaterial));
  }
#ifdef CAUSTICS_STORE_ESCAPED
  if (stored > 0.0)
  {
    vec3 kept = (inMedium ? flux4.rgb * CausticsMediumTransmittance(p, d, 0.0, stored) : flux4.rgb) *
      SheetTransmittance(sheetMaterial, stored);
    AddFlux(STAT_FLUX_ABSORBED, power - Power(kept));
    atomicAdd(statistics[STAT_STORED], 1u);
    AddFlux(STAT_FLUX_STORED, Power(kept));
    ImpostorDepositCaustic(p + stored * d, kept);
    imageStore(outPosition, texel, vec4(0.0));
    imageStore(outNormal, texel, vec4(0.0));
    imageStore(outFlux, texel, vec4(0.0));
    return;
  }
#endif
  vec3 hit = p + t * d;
  path += t;
  if (!landed || !AllFinite(hit) || !(path > 0.0) || isinf(path) || !(power > 0.0))
  {
    // Left the caustic map's view or the receivers' bounds (or stopped by a mirror).
    atomicAdd(statistics[STAT_ESCAPED], 1u);
    AddFlux(STAT_FLUX_ESCAPED, power);
    imageStore(outPosition, texel, vec4(0.0));
    imageStore(outNormal, texel, vec4(0.0));
    imageStore(outFlux, texel, vec4(0.0));
    return;
  }
  if (inMedium || sheetMaterial >= 0)
  {
    // The medium between the surface it left and the receiver, or the water.
    vec3 kept = (inMedium ? flux4.rgb * CausticsMediumTransmittance(p, d, 0.0, t) : flux4.rgb) *
      SheetTransmittance(sheetMaterial, t);
    AddFlux(STAT_FLUX_ABSORBED, power - Power(kept));
    flux4.rgb = kept;
    power = Power(kept);
  }
  atomicAdd(statistics[STAT_HITS], 1u);
  AddFlux(STAT_FLUX_HITS, power);
  if (hidden)
  {
    atomicAdd(statistics[STAT_HIDDEN_HITS], 1u);
    atomicOr(statistics[STAT_HIDDEN_DRAW + 1], 1u); // the hidden map has a caustic to show
    flux4.a = -flux4.a; // the hidden receivers' map's photon
  }
  imageStore(outPosition, texel, vec4(hit, path));
  imageStore(outNormal, texel, vec4(n, abs(dot(n, d))));
  imageStore(outFlux, texel, flux4);
}
#endif
