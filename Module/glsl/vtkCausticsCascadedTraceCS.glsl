// Cascaded image-space photon tracing (vtkCausticsCascadedPhotonPass,
// 002_97e66a5090de9b07.txt §3.1-3.2). One thread per sampled photon:
// 1. ray generation (§3.1): a point of the R2 low-discrepancy sequence, rotated by a
//    per-frame offset, picks a texel of the emitter's grid (vtkCausticsPhotonEmitter:
//    the first specular event, both Fresnel branches of a refractor); the branch is
//    chosen with the exact Fresnel probability (the branches' fluxes are F and 1 - F
//    of the texel's), the flux divided by that probability and scaled by texels per
//    photon, so each frame is an unbiased estimate whatever the photon count;
// 2. inside a refractor: a march through the light's image against the refractors'
//    nearest and farthest faces seen from the light, to the exit, where the photon
//    refracts or reflects (Fresnel Russian roulette again, Beer-Lambert on the way,
//    and, when the medium fills the refractors, its extinction and volume caustic);
// 3. in air (§3.2): a march through the light's image against its opaque depth
//    (receivers and reflectors), the termination refined by Eq. 2 and accepted when
//    the point lies on the surface the texel shows; when the ray leaves the light's
//    view or passes behind what the light sees, its last position is reprojected into
//    the camera view and the march goes on against the camera's opaque G-buffer
//    (Fig. 5); a hit counts when the light arrives on the side the camera sees
//    (<-d, n> >= 0 with n facing the camera). Mirrors reflect (conductor Fresnel)
//    and refractors met in the light's view are entered, up to maximumEvents; a
//    participating medium attenuates every stretch in air (in the water under an
//    open sheet and inside closed refractors only when it fills the refractors, as in
//    the reference) and, when it scatters
//    (CAUSTICS_VOLUME_SEGMENT_APPEND), each stretch is appended for the line-based
//    volume caustics (vtkCausticsVolumeLines), as is the last one of a photon that
//    leaves the views (to where it leaves the scene);
// 4. output: landed photons in the photon record layout (vtkCausticsCommon.glsl) and
//    their kernel radii, for vtkCausticsPhotonSplatter (Eq. 3 by splatting);
// 5. where each photon's light went (vtkCausticsPhotonStatistics.glsl): landed
//    (STAT_HITS), left the views or landed where the camera does not see
//    (STAT_ESCAPED), or on a path the cascade cannot follow (STAT_LOST_INSIDE: a
//    march that starts hidden in the camera's view (Fig. 7), an exit from a refractor
//    not found in the light's view, the light's view left with the camera stage off,
//    MaximumEvents reached), so that the pass can say how much light its caustic
//    may lack.
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D emitPosition;   // xyz, w = 0 none, 1 in air, 2 inside a refractor
uniform sampler2D emitDirection;  // xyz unit, w = texel measure
uniform sampler2D emitFlux;       // rgb W
uniform sampler2D opaquePosition; // receivers and reflectors seen from the light
uniform sampler2D opaqueNormal;
uniform sampler2D frontPosition;  // refractors' nearest faces seen from the light
uniform sampler2D frontNormal;
uniform sampler2D backPosition;   // refractors' farthest faces seen from the light
uniform sampler2D backNormal;
uniform sampler2D cameraPosition; // the camera's opaque G-buffer
uniform sampler2D cameraNormal;
uniform CausticsView lightView;
uniform CausticsView cameraView;
uniform int emitResolution;  // N: the emitter's texels per side
uniform int emitBranches;    // 1, or 2 when rows N..2N-1 hold the reflected branch
uniform ivec2 photonGrid;    // the output grid
uniform int photonCount;     // photons sampled (<= photonGrid.x * photonGrid.y)
uniform uint frameOffsetX;   // Cranley-Patterson rotation of the sequence, 2^-32 units
uniform uint frameOffsetY;
uniform uint frameSeed;      // seed of the Russian roulette
uniform float fluxScale;     // emitter texels per photon: N^2 / photonCount
uniform int lightType;       // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;
uniform int cameraStage;     // 0: light view only
uniform int marchHiddenStarts; // 1: a camera march that starts hidden goes on behind (else Fig. 7)
uniform int marchSteps;      // most pixels per march
uniform int maximumEvents;
uniform float airLength;     // longest straight path through the scene (m)
uniform float spacings;      // kernel radius in photon spacings

layout(rgba32f, binding = 0) uniform writeonly image2D outPosition;
layout(rgba32f, binding = 1) uniform writeonly image2D outNormal;
layout(rgba32f, binding = 2) uniform writeonly image2D outFlux;
layout(r32f, binding = 3) uniform writeonly image2D outRadius;

// March outcomes.
#define MARCH_NONE 0    // nothing met within the length
#define MARCH_HIT 1     // a surface: hitPoint, hitNormal, hitMaterial, hitRole
#define MARCH_LEFT 2    // left the view (or passed behind what it shows): lastPoint
#define MARCH_BLOCKED 3 // started hidden in the view (Fig. 7, the convex case; marchHiddenStarts 0)

// A photon's end, as the statistics count it (item 5 above).
#define FATE_NOT_FOLLOWED 0 // STAT_LOST_INSIDE
#define FATE_LEFT 1         // STAT_ESCAPED

vec3 hitPoint;
vec3 hitNormal;
int hitMaterial;
int hitRole;
vec3 lastPoint;

// The part [t0, t1] of o + t d, t in [0, tMax], inside view v's clip volume; false if none.
bool ClipToView(CausticsView v, vec3 o, vec3 d, float tMax, out float t0, out float t1)
{
  vec4 a = v.worldToClip * vec4(o, 1.0);
  vec4 b = v.worldToClip * vec4(d, 0.0);
  t0 = 0.0;
  t1 = tMax;
  for (int i = 0; i < 6; ++i)
  {
    int k = i >> 1;
    float s = (i & 1) == 0 ? 1.0 : -1.0;
    float f0 = a.w + s * a[k]; // inside where f0 + t f1 >= 0
    float f1 = b.w + s * b[k];
    if (abs(f1) < 1e-12)
    {
      if (f0 < 0.0)
      {
        return false;
      }
    }
    else if (f1 > 0.0)
    {
      t0 = max(t0, -f0 / f1);
    }
    else
    {
      t1 = min(t1, -f0 / f1);
    }
  }
  return t1 > t0;
}

// Parameter of the ray at screen fraction s of [t0, t1] (perspective-correct).
float StepParameter(CausticsView v, vec3 o, vec3 d, float t0, float t1, float s)
{
  float w0 = (v.worldToClip * vec4(o + t0 * d, 1.0)).w;
  float w1 = (v.worldToClip * vec4(o + t1 * d, 1.0)).w;
  float u = s * w0 / max((1.0 - s) * w1 + s * w0, 1e-30);
  return mix(t0, t1, clamp(u, 0.0, 1.0));
}

// Whether x lies on the surface (p, n) a texel shows, within a texel's width.
bool OnSurface(CausticsView v, vec3 x, vec3 p, vec3 n)
{
  return abs(dot(x - p, normalize(n))) <= ViewTexelSize(v, x) + 1e-5 * airLength;
}

// Eq. 2: the ray's and the surface's view depths, linear between two samples
// (r0 <= s0, r1 > s1), cross at u in [0, 1].
float Crossing(float r0, float s0, float r1, float s1)
{
  float denominator = (r1 - r0) - (s1 - s0);
  return clamp(abs(denominator) > 1e-12 ? (s0 - r0) / denominator : 1.0, 0.0, 1.0);
}

// Takes h as the hit when the texel it falls in shows a surface whose plane holds h
// (the acceptance of every crossing); false otherwise.
bool AcceptHit(CausticsView v, sampler2D position, sampler2D normal, vec3 h)
{
  vec2 pixel;
  ViewProject(v, h, pixel);
  ivec2 at = ViewTexel(v, pixel);
  vec4 hp = texelFetch(position, at, 0);
  vec4 hn = texelFetch(normal, at, 0);
  if (hp.w >= 0.0 && OnSurface(v, h, hp.xyz, hn.xyz) && dot(hn.xyz, hn.xyz) > 0.0)
  {
    hitPoint = h;
    hitNormal = normalize(hn.xyz);
    hitMaterial = int(hp.w + 0.5);
    hitRole = int(hn.w + 0.5);
    return true;
  }
  return false;
}

// Where the ray, in front of surface (p, n) at tPrevious, meets that surface's plane
// before t: the crossing's parameter, or -1. A surface that ends between two samples
// (a floor's edge, the next texel empty or farther) is never seen behind the ray, so
// its crossing is found on the plane of the last texel that showed it.
float PlaneCrossing(vec3 o, vec3 d, float tPrevious, float t, vec4 p, vec3 n)
{
  float facing = dot(n, d);
  if (p.w < 0.0 || !(abs(facing) > 1e-12) || !(dot(n, n) > 0.0))
  {
    return -1.0;
  }
  float tc = dot(n, p.xyz - o) / facing;
  return tc >= tPrevious && tc <= t ? tc : -1.0;
}

// Marches o + t d, t in [0, tMax], through view v against the surfaces of
// (position, normal), one pixel per step. With `leaveWhenBehind` a ray that passes
// behind what the view shows (not on its surface) stops there (MARCH_LEFT); otherwise
// it marches on until it comes out in front again. Refractors of the light's front
// layer (`refractors`) are entered when met; passing behind them is not an exit.
int March(CausticsView v, sampler2D position, sampler2D normal, bool refractors, vec3 o, vec3 d,
  float tMax, bool leaveWhenBehind)
{
  float t0, t1;
  lastPoint = o;
  if (!ClipToView(v, o, d, tMax, t0, t1))
  {
    return MARCH_LEFT;
  }
  vec2 p0, p1;
  ViewProject(v, o + t0 * d, p0);
  ViewProject(v, o + t1 * d, p1);
  int steps = clamp(int(ceil(length(p1 - p0))), 1, marchSteps);
  float tPrevious = t0;
  float rPrevious = 0.0, sPrevious = 0.0;
  bool front = true; // the previous sample was in front of the view's surface
  vec4 surfacePrevious = vec4(0.0, 0.0, 0.0, -1.0); // the surface the previous sample's texel shows
  ivec2 texelPrevious = ivec2(-1);
  for (int k = 0; k <= steps; ++k)
  {
    float t = StepParameter(v, o, d, t0, t1, float(k) / float(steps));
    vec3 x = o + t * d;
    vec2 pixel;
    ViewProject(v, x, pixel);
    ivec2 texel = ViewTexel(v, pixel);
    vec4 surface = texelFetch(position, texel, 0);
    float r = ViewDepth(v, x);
    float s = surface.w < 0.0 ? 1e30 : ViewDepth(v, surface.xyz);
    bool behind = r > s;
    if (k == 0 && !refractors)
    {
      // Hidden at the start: the light's view leaves there (below); the camera's
      // rejects it in the paper (§3.2, Fig. 7), or marches on behind what it shows
      // until the ray comes out in front (marchHiddenStarts): a mirror's light from
      // faces the camera does not see reaches the receivers it does see.
      vec3 n = texelFetch(normal, texel, 0).xyz;
      bool hidden = behind && !leaveWhenBehind && !OnSurface(v, x, surface.xyz, n);
      if (hidden && marchHiddenStarts == 0)
      {
        return MARCH_BLOCKED;
      }
      behind = hidden; // leaving a surface it is on does not stop the photon
    }
    else if (k == 0)
    {
      // A photon that starts on a refractor's face (the one it just crossed) must
      // come out clearly in front of a face before it can enter one.
      behind = r > s - ViewTexelSize(v, x);
    }
    else if (k > 0 && behind && front)
    {
      float u = Crossing(rPrevious, sPrevious, r, s);
      if (AcceptHit(v, position, normal, o + mix(tPrevious, t, u) * d))
      {
        return MARCH_HIT;
      }
      if (leaveWhenBehind && !refractors)
      {
        lastPoint = o + tPrevious * d;
        return MARCH_LEFT;
      }
    }
    else if (k > 1 && front && texel != texelPrevious &&
      (surface.w < 0.0 || surface.w != surfacePrevious.w))
    {
      // In front of another surface, or of none: did the ray cross the previous one?
      float tc = PlaneCrossing(
        o, d, tPrevious, t, surfacePrevious, texelFetch(normal, texelPrevious, 0).xyz);
      if (tc >= 0.0 && AcceptHit(v, position, normal, o + tc * d))
      {
        return MARCH_HIT;
      }
    }
    front = !behind;
    surfacePrevious = surface;
    texelPrevious = texel;
    tPrevious = t;
    rPrevious = r;
    sPrevious = s;
  }
  lastPoint = o + t1 * d;
  return t1 < tMax * 0.999 ? MARCH_LEFT : MARCH_NONE;
}

// Marches a photon inside a refractor through the light's view to where it leaves:
// behind the farthest face or in front of the nearest one (a convex refractor's
// texel holds its inside between them). False if it leaves the light's view first.
bool MarchInside(vec3 o, vec3 d, float tMax)
{
  float t0, t1;
  if (!ClipToView(lightView, o, d, tMax, t0, t1) || t0 > 0.0)
  {
    return false;
  }
  vec2 p0, p1;
  ViewProject(lightView, o, p0);
  ViewProject(lightView, o + t1 * d, p1);
  int steps = clamp(int(ceil(length(p1 - p0))), 1, marchSteps);
  float tPrevious = 0.0, rPrevious = ViewDepth(lightView, o);
  vec4 backPrevious = vec4(0.0, 0.0, 0.0, -1.0), frontPrevious = backPrevious;
  vec4 backNormalPrevious = vec4(0.0), frontNormalPrevious = vec4(0.0);
  for (int k = 0; k <= steps; ++k)
  {
    float t = StepParameter(lightView, o, d, 0.0, t1, float(k) / float(steps));
    vec3 x = o + t * d;
    vec2 pixel;
    ViewProject(lightView, x, pixel);
    ivec2 texel = ViewTexel(lightView, pixel);
    vec4 back = texelFetch(backPosition, texel, 0);
    vec4 front = texelFetch(frontPosition, texel, 0);
    vec4 backN = texelFetch(backNormal, texel, 0);
    vec4 frontN = texelFetch(frontNormal, texel, 0);
    float r = ViewDepth(lightView, x);
    if (k > 0)
    {
      bool outside = back.w < 0.0; // past the refractor's silhouette
      bool pastBack = !outside && r > ViewDepth(lightView, back.xyz);
      bool pastFront = !outside && r < ViewDepth(lightView, front.xyz);
      if (outside || pastBack || pastFront)
      {
        // Leaving past the silhouette: through the face the photon heads for, where
        // the previous sample saw it; otherwise Eq. 2 between the two samples.
        bool useBack = outside ? dot(d, ViewAway(lightView, x)) >= 0.0 : pastBack;
        vec4 m = useBack ? backPrevious : frontPrevious;
        vec4 n = useBack ? backNormalPrevious : frontNormalPrevious;
        float u = 0.0;
        if (!outside)
        {
          vec4 s1 = useBack ? back : front;
          float a = m.w >= 0.0 ? ViewDepth(lightView, m.xyz) : ViewDepth(lightView, s1.xyz);
          float b = ViewDepth(lightView, s1.xyz);
          u = useBack ? Crossing(rPrevious, a, r, b) : Crossing(-rPrevious, -a, -r, -b);
          if (u >= 0.5 || m.w < 0.0)
          {
            m = s1;
            n = useBack ? backN : frontN;
          }
        }
        hitPoint = o + mix(tPrevious, t, u) * d;
        if (m.w < 0.0 || dot(n.xyz, n.xyz) <= 0.0)
        {
          return false;
        }
        hitNormal = normalize(n.xyz);
        hitMaterial = int(m.w + 0.5);
        return true;
      }
    }
    tPrevious = t;
    rPrevious = r;
    backPrevious = back;
    frontPrevious = front;
    backNormalPrevious = backN;
    frontNormalPrevious = frontN;
  }
  return false;
}

struct Emitted
{
  vec4 position;  // xyz, w = state
  vec4 direction; // xyz unit, w = texel measure
  vec3 flux;
};

// The emitted photon of one branch at continuous texel coordinate c (texel i spans
// [i, i + 1)): bilinear between the four emitted photons around c when all four
// exist in the same state (first-order exact on a smooth surface, so that samples
// are not tied to texel centres), else the photon of the texel c falls in.
Emitted EmittedAt(vec2 c, int branch)
{
  ivec2 row = ivec2(0, branch * emitResolution);
  ivec2 last = ivec2(emitResolution - 1);
  ivec2 nearest = clamp(ivec2(floor(c)), ivec2(0), last) + row;
  Emitted e = Emitted(texelFetch(emitPosition, nearest, 0),
    texelFetch(emitDirection, nearest, 0), texelFetch(emitFlux, nearest, 0).rgb);
  vec2 b = c - 0.5;
  ivec2 base = ivec2(floor(b));
  vec2 f = b - vec2(base);
  Emitted sum = Emitted(vec4(0.0), vec4(0.0), vec3(0.0));
  for (int k = 0; k < 4; ++k)
  {
    ivec2 corner = clamp(base + ivec2(k & 1, k >> 1), ivec2(0), last) + row;
    vec4 position = texelFetch(emitPosition, corner, 0);
    if (position.w != e.position.w)
    {
      return e;
    }
    float weight = ((k & 1) == 1 ? f.x : 1.0 - f.x) * ((k >> 1) == 1 ? f.y : 1.0 - f.y);
    sum.position += weight * position;
    sum.direction += weight * texelFetch(emitDirection, corner, 0);
    sum.flux += weight * texelFetch(emitFlux, corner, 0).rgb;
  }
  sum.position.w = e.position.w;
  sum.direction.xyz = normalize(sum.direction.xyz);
  return AllFinite(sum.direction.xyz) ? sum : e;
}

// An open refractor (a water surface: one sheet) has no back face behind the entry:
// the farthest refractor surface the light sees there is the entry itself, facing
// the light. The photon stays in that medium and goes on to the receivers (as the
// caustic maps' trace does), absorbed by the water on the way (TravelOutside).
bool OpenRefractor(vec3 x, out int material)
{
  material = -1;
  vec2 pixel;
  if (!ViewProject(lightView, x, pixel))
  {
    return false;
  }
  ivec2 texel = ViewTexel(lightView, pixel);
  vec4 back = texelFetch(backPosition, texel, 0);
  vec3 n = texelFetch(backNormal, texel, 0).xyz;
  material = int(back.w + 0.5);
  return back.w >= 0.0 && distance(back.xyz, x) <= 2.0 * ViewTexelSize(lightView, x) &&
    dot(n, ViewAway(lightView, x)) < -0.1 * length(n);
}

// In the water under an open sheet (OpenRefractor): the reference holds no medium
// there (a photon inside a refractor) unless the medium fills the refractors, so
// neither extinction nor volume caustic; the sheet's own absorption, as inside a
// closed refractor (sheetMaterial: the sheet's material).
bool underSheet = false;
int sheetMaterial = -1;

// A straight stretch from a to b, in air (or under an open sheet: underSheet) or
// inside a closed refractor: the path grows, and where the participating medium
// (vtkCausticsCommon.glsl: homogeneous, or a density grid) holds the stretch
// (CausticsStretchInMedium) it is handed to the volume caustics and the medium takes
// its share (CausticsMediumStretch).
void Travel(vec3 a, vec3 b, bool insideRefractor, int absorber, inout vec3 flux, inout float path)
{
  float length = distance(a, b);
  if (length > 0.0)
  {
    flux = CausticsMediumStretch(a, (b - a) / length, length, flux, insideRefractor, absorber);
  }
  path += length;
}

// A stretch outside closed refractors: in air, or in the water under an open sheet,
// whose Beer-Lambert absorption it then takes (the water has no exit face to measure
// it to: the photon lands in it).
void TravelOutside(vec3 a, vec3 b, inout vec3 flux, inout float path)
{
  int absorber = underSheet ? sheetMaterial : -1;
  Travel(a, b, underSheet, absorber, flux, path);
  if (absorber >= 0)
  {
    flux *= CausticsTransmittance(causticsMaterials[absorber].attenuation.rgb, distance(a, b));
  }
}

void NoPhoton(ivec2 g)
{
  imageStore(outPosition, g, vec4(0.0));
  imageStore(outNormal, g, vec4(0.0));
  imageStore(outFlux, g, vec4(0.0));
  imageStore(outRadius, g, vec4(0.0));
}

void main()
{
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, photonGrid)))
  {
    return;
  }
  uint index = uint(g.x + g.y * photonGrid.x);
  if (index >= uint(photonCount))
  {
    NoPhoton(g);
    return;
  }
  // 1. The R2 sequence (plastic-number increments in 32-bit fixed point), rotated.
  uvec2 fixedPoint = uvec2(index * 0xc13fa9a9u, index * 0x91e10da6u) + uvec2(frameOffsetX, frameOffsetY);
  vec2 u = vec2(fixedPoint >> 8u) * (1.0 / 16777216.0);
  vec2 c = u * float(emitResolution);
  uint rng = CausticsHash(index ^ CausticsHash(frameSeed));
  Emitted e0 = EmittedAt(c, 0);
  Emitted e1 = emitBranches > 1 ? EmittedAt(c, 1) : Emitted(vec4(0.0), vec4(0.0), vec3(0.0));
  float w0 = e0.position.w > 0.0 ? CausticsChannelSum(e0.flux) : 0.0;
  float w1 = e1.position.w > 0.0 ? CausticsChannelSum(e1.flux) : 0.0;
  if (!(w0 + w1 > 0.0))
  {
    NoPhoton(g);
    return;
  }
  // The branches hold F and 1 - F of the texel's flux: choosing one with that
  // probability and dividing by it gives the texel's flux to the branch followed.
  bool second = CausticsRandom(rng) * (w0 + w1) >= w0;
  Emitted e = second ? e1 : e0;
  vec4 p = e.position;
  float measure = e.direction.w * fluxScale; // the beam one photon stands for
  vec3 flux = e.flux * ((w0 + w1) / (second ? w1 : w0)) * fluxScale;
  atomicAdd(statistics[STAT_PHOTONS], 1u);
  AddFlux(STAT_FLUX_IN, CausticsChannelSum(flux));
  vec3 d = e.direction.xyz;
  vec3 o = p.xyz;
  bool inside = p.w > 1.5;
  float path = lightType == 0 ? dot(o - lightView.eye, lightView.axis) : length(o - lightOrigin);
  // The participating medium between the light and the first specular surface.
  float reach = lightType == 0 ? 3.0e38 : distance(o, lightOrigin);
  flux *= CausticsMediumTransmittance(o, -ViewAway(lightView, o), 0.0, reach);
  float nudge = 1e-5 * airLength;

  int fate = FATE_NOT_FOLLOWED; // also when MaximumEvents ends the path
  for (int event = 0; event < maximumEvents && CausticsChannelSum(flux) > 0.0; ++event)
  {
    int sheet;
    if (inside && OpenRefractor(o, sheet))
    {
      inside = false; // in the water under a surface sheet: on to the receivers
      underSheet = true;
      sheetMaterial = sheet; // the sheet it entered by
    }
    if (inside)
    {
      // 2. To the refractor's exit, as the light sees its faces.
      if (!MarchInside(o, d, airLength))
      {
        break;
      }
      // The medium, when it fills the refractors, then the refractor's own absorption.
      vec3 sigma = causticsMaterials[hitMaterial].attenuation.rgb;
      float chord = length(hitPoint - o);
      Travel(o, hitPoint, true, hitMaterial, flux, path);
      flux *= CausticsTransmittance(sigma, chord);
      CausticsScatterOneBranch(hitNormal, causticsMaterials[hitMaterial], ROLE_REFRACTOR, d, flux, inside, rng);
      o = hitPoint + nudge * d;
      continue;
    }
    // 3. In air: the light's view first, then, from where it stops, the camera's.
    int result = March(lightView, opaquePosition, opaqueNormal, false, o, d, airLength, true);
    if (result == MARCH_HIT)
    {
      // A refractor met in air (the light's front faces) before the opaque hit.
      vec3 opaqueHit = hitPoint;
      vec3 opaqueNormal = hitNormal;
      int opaqueMaterial = hitMaterial, opaqueRole = hitRole;
      float reach = length(opaqueHit - o);
      if (March(lightView, frontPosition, frontNormal, true, o, d, reach, false) == MARCH_HIT &&
        hitRole == ROLE_REFRACTOR)
      {
        TravelOutside(o, hitPoint, flux, path);
        CausticsScatterOneBranch(hitNormal, causticsMaterials[hitMaterial], ROLE_REFRACTOR, d, flux, inside, rng);
        // Back out of the water, or into another refractor: its own stretches decide.
        underSheet = false;
        o = hitPoint + nudge * d;
        continue;
      }
      hitPoint = opaqueHit;
      hitNormal = opaqueNormal;
      hitMaterial = opaqueMaterial;
      hitRole = opaqueRole;
    }
    else if (result == MARCH_LEFT && cameraStage != 0)
    {
      // Reprojection into the camera view (§3.2, Fig. 5): march on from the last
      // position the light's view could vouch for.
      TravelOutside(o, lastPoint, flux, path);
      o = lastPoint;
      result = March(cameraView, cameraPosition, cameraNormal, false, o, d, airLength, false);
    }
    if (result != MARCH_HIT)
    {
      // Left the camera's view, or the light's where the camera stage is off (then
      // it may land in view: not followed).
      fate = result == MARCH_BLOCKED || (result == MARCH_LEFT && cameraStage == 0)
        ? FATE_NOT_FOLLOWED
        : FATE_LEFT;
      if (result != MARCH_BLOCKED)
      {
        // It leaves the views: its scattering up to where it leaves the scene.
        CausticsAppendVolumeSegment(
          CausticsMakeMediumSegment(o, d, airLength, flux, underSheet, underSheet ? sheetMaterial : -1));
      }
      break;
    }
    TravelOutside(o, hitPoint, flux, path);
    if (hitRole == ROLE_REFLECTOR)
    {
      CausticsScatterOneBranch(hitNormal, causticsMaterials[hitMaterial], ROLE_REFLECTOR, d, flux, inside, rng);
      o = hitPoint + nudge * d;
      continue;
    }
    // The normal check: light arrives on the side of the receiver the camera sees.
    vec3 towardsCamera = -ViewAway(cameraView, hitPoint);
    vec3 facing = dot(hitNormal, towardsCamera) >= 0.0 ? hitNormal : -hitNormal;
    float cosine = dot(-d, facing);
    if (hitRole != ROLE_RECEIVER || !(cosine >= 0.0) || !AllFinite(flux) || !AllFinite(hitPoint))
    {
      // Light on the receiver's side the camera does not see lands out of sight.
      fate = hitRole == ROLE_RECEIVER && !(cosine >= 0.0) ? FATE_LEFT : FATE_NOT_FOLLOWED;
      break;
    }
    // 4. The landed record; the radius spans `spacings` photon spacings of the
    // unoccluded beam one photon stands for.
    float distance = lightType == 0 ? 1.0 : path;
    float radius = spacings * distance * sqrt(measure / max(cosine, 1e-3));
    imageStore(outPosition, g, vec4(hitPoint, max(path, 1e-6)));
    imageStore(outNormal, g, vec4(hitNormal, abs(dot(hitNormal, d))));
    imageStore(outFlux, g, vec4(flux, measure));
    imageStore(outRadius, g, vec4(radius));
    atomicAdd(statistics[STAT_HITS], 1u);
    AddFlux(STAT_FLUX_HITS, CausticsChannelSum(flux));
    return;
  }
  float power = AllFinite(flux) ? CausticsChannelSum(flux) : 0.0;
  if (fate == FATE_LEFT)
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
