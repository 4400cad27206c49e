// Screen-space refraction tracing (000_54cf099eeccf42d9.txt §4). For a pixel that
// sees a refractor, the viewing ray is refracted at the refractor's first layer
// and marched in screen space (pixel steps, sampled in strides: MarchRay), with one
// lookup per layer: it leaves the object where its depth passes the next layer's
// (or falls below the current one's), the "monotonic" assumption that the n-th
// intersection is in the (n+1)-th layer. There it is refracted out (Fresnel-weighted;
// total internal reflection keeps it inside) and marched on through the scene: the first opaque
// surface of the camera's opaque G-buffer it passes gives the colour (the paper's
// approximation: only what the camera would see without the refractor, Fig. 10),
// another layer of the refractor takes it back in, and leaving the view or the
// scene gives the background. The Fresnel-reflected part at the entry is traced
// the same way outside. Colours are in VTK's display units: VTK's own colour where
// VTK shows that surface, else albedo x (direct + caustic irradiance).
in vec2 texCoord;

SSP_LDI_TABLE(readonly);

uniform sampler2DArray refractorPosition; // xyz, w = material (-1: none)
uniform sampler2DArray refractorNormal;   // xyz as modelled, w = role
uniform sampler2D gPosition;              // opaque G-buffer
uniform sampler2D gNormal;
uniform sampler2D gAlbedo;
uniform sampler2D gDepth;
uniform sampler2D delegateColor;
uniform sampler2D delegateDepth;
uniform sampler2D causticIrradiance;
uniform sampler2D directIrradiance;
uniform int hasDirect;
uniform sampler2D lostShading; // VTK's shading specular actors block, per unit albedo
uniform int hasLostShading;
uniform mat4 worldToClip;
uniform vec2 viewport;
uniform vec4 viewOrigin; // camera position (w = 1) or view direction (w = 0)
// The closed refractor the eye is in (winding number >= 1/2 at the eye), -1: none. Where
// it is -1, each pixel reads the eye's medium from the first refractor surface it sees.
uniform int eyeMaterial;
uniform vec3 boundsMin;
uniform vec3 boundsMax;
uniform vec3 background;
uniform int maxEvents;
uniform int internalReflections; // follow the Fresnel-reflected branch at dielectrics (TracePath)
uniform float tolerance;      // m
uniform float pixelScale;     // world size of one pixel at clip w = 1, m
uniform float depthTolerance; // window depth: VTK's image and the G-buffers agree
// How rays are traced after the first surface (vtkCausticsRenderPass::CameraViewMethod):
// 0 the screen-space march; 1 the distance impostors (glsl/vtkCausticsImpostorCommon.glsl);
// 2 the march, then the impostors from where a march leaves the view or the scene.
uniform int viewMethod;
uniform int exactSpecular; // 1: glass and mirrors traced as triangles (SpecularTrace)

layout(location = 0) out vec4 outColor;

const int MARCH_STRIDE = 16;
const int MISS = 0;
const int OPAQUE = 1;
const int REFRACTOR = 2;
const int METHOD_IMPOSTORS = 1;
const int METHOD_BOTH = 2;
// A Fresnel-reflected branch (TracePath) is followed when it carries at least this
// share of the pixel's colour; lighter ones are dropped.
const float MIN_BRANCH_WEIGHT = 0.01;

struct March
{
  int kind;
  float t;      // along the ray, m
  ivec2 pixel;  // where it was found
  int layer;    // REFRACTOR: the layer
  vec3 normal;  // REFRACTOR: as modelled
  int material; // material index (OPAQUE: once CompleteHit ran)
  int role;     // the surface's role (once CompleteHit ran)
  vec3 radiance; // OPAQUE impostor hit the camera does not see: its map's colour
  bool leftView; // MISS of the march: the ray left the view before the scene's bounds
  bool hidden;   // what the ray meets the screen does not show: an OPAQUE hit met from
                 // behind or far from the surface the camera sees there, or a MISS
                 // within the pixels it starts in, leaving a surface there
  bool leaving;  // some sample was taken for the ray leaving an opaque surface
  bool exact;    // a specular triangle of the hierarchy (SpecularTrace)
  vec3 geometric; // exact: the face normal (on the normal's side); else the normal
};

// Distance along the view: clip w (perspective) or clip z (parallel), both growing away.
float ViewDepth(vec3 p)
{
  vec4 clip = worldToClip * vec4(p, 1.0);
  return viewOrigin.w > 0.0 ? clip.w : clip.z;
}

// From the surface point p towards the camera (not normalized): to the eye, or against a
// parallel view's direction.
vec3 ToCamera(vec3 p)
{
  return viewOrigin.w > 0.0 ? viewOrigin.xyz - p : -viewOrigin.xyz;
}

// The camera pixel's footprint at the point x (m).
float PixelFootprint(vec3 x)
{
  return abs((worldToClip * vec4(x, 1.0)).w) * pixelScale;
}

// Whether x (view depth `depth`) is on the given side of the surface sample (p, n)
// of its pixel as the camera sees it (beyond: deeper along the view; else in
// front), or, within a few pixel footprints of p, on that side of its tangent
// plane (at grazing views the surface's depth varies more across one pixel than a
// step of the ray).
bool OnSide(vec3 x, float depth, vec3 p, vec3 n, bool beyond)
{
  vec4 clip = worldToClip * vec4(p, 1.0);
  float surfaceDepth = viewOrigin.w > 0.0 ? clip.w : clip.z;
  if (beyond ? depth >= surfaceDepth : depth <= surfaceDepth)
  {
    return true;
  }
  vec3 toCamera = ToCamera(p);
  float facing = dot(toCamera, n);
  float footprint = abs(clip.w) * pixelScale;
  float cosine = abs(facing) / max(length(toCamera), 1e-20);
  float reach = tolerance + 2.0 * footprint / max(cosine, 0.1);
  float side = dot(x - p, n) * facing;
  return (beyond ? side <= 0.0 : side >= 0.0) && distance(x, p) < reach;
}

bool Beyond(vec3 x, float depth, vec3 p, vec3 n)
{
  return OnSide(x, depth, p, n, true);
}

// In front of the surface sample (p, n): the converse, for leaving through it.
bool InFront(vec3 x, float depth, vec3 p, vec3 n)
{
  return OnSide(x, depth, p, n, false);
}

// Whether the ray o + t d, at x, is leaving the surface sample (p, n) rather than
// crossing it: within a few pixel footprints of p, on the camera's side of its tangent
// plane and moving away from it, as a ray that a mirror standing on the floor sends out
// from the wall's foot (in depth it passes behind the wall's pixel there; it crosses
// the floor next to it, not the wall).
bool Leaving(vec3 o, vec3 d, vec3 x, vec3 p, vec3 n)
{
  vec3 front = dot(ToCamera(p), n) >= 0.0 ? n : -n;
  float reach = tolerance + 4.0 * PixelFootprint(p);
  return dot(x - p, front) > 0.0 && dot(d, front) > 0.0 && distance(x, p) < reach;
}

// Whether a ray heading along d, found beyond the surface sample (p, n) the camera sees,
// meets it from behind: it heads towards the side that faces the camera, so it passed
// behind the surface rather than through it, and what it meets there the camera does
// not see (inside the ring, the floor its near wall hides, in a ray the far wall sends
// back).
bool FromBehind(vec3 d, vec3 p, vec3 n)
{
  vec3 front = dot(ToCamera(p), n) >= 0.0 ? n : -n;
  return dot(d, front) > 0.0;
}

// Whether the point c of the tangent plane of the surface sample (p, n) is within a few
// pixel footprints of p, as the crossing of a ray that meets the surface there is
// (one that passed under it, such as a ray in the pool's water below its near wall's
// top, crosses that plane far away, or behind its start).
bool NearSample(vec3 c, vec3 p, vec3 n)
{
  vec3 toCamera = ToCamera(p);
  float cosine = abs(dot(toCamera, n)) / max(length(toCamera) * length(n), 1e-20);
  return distance(c, p) < tolerance + 4.0 * PixelFootprint(p) / max(cosine, 0.1);
}

// Refines a crossing of the surface (p, n) near parameter t: the tangent-plane hit.
float PlaneHit(vec3 o, vec3 d, vec3 p, vec3 n, float t)
{
  float denominator = dot(d, n);
  float refined = abs(denominator) > 1e-4 ? dot(p - o, n) / denominator : t;
  return refined > 0.0 ? refined : t;
}

// Whether the march's sample o + t d (view depth `depth`, pixel q) has passed
// beyond (beyond = true) or come in front of the refractor's layer `layer`, whose
// position sample at q is p; if so, fills `result` with the crossing refined on
// the layer's tangent plane.
bool RefractorLayerHit(vec3 o, vec3 d, float t, float depth, ivec2 q, int layer, vec4 p,
  bool beyond, inout March result)
{
  vec3 n = texelFetch(refractorNormal, ivec3(q, layer), 0).xyz;
  vec3 x = o + t * d;
  if (p.w < 0.0 || !(beyond ? Beyond(x, depth, p.xyz, n) : InFront(x, depth, p.xyz, n)))
  {
    return false;
  }
  result.kind = REFRACTOR;
  result.t = PlaneHit(o, d, p.xyz, n, t);
  result.pixel = q;
  result.layer = layer;
  result.normal = n; // smoothed once the march ends (SmoothHitNormal)
  result.material = int(p.w + 0.5);
  return true;
}

// An opaque hit refined on the surface's tangent plane, with the pixel the exact
// crossing projects to (the step's sample can be a pixel beyond it).
void RefineOpaqueHit(vec3 o, vec3 d, inout March result)
{
  if (result.kind != OPAQUE)
  {
    return;
  }
  ivec2 q = result.pixel;
  vec3 p = texelFetch(gPosition, q, 0).xyz;
  vec3 n = texelFetch(gNormal, q, 0).xyz;
  result.t = PlaneHit(o, d, p, n, result.t);
  result.hidden = result.hidden || !NearSample(o + result.t * d, p, n);
  vec4 clip = worldToClip * vec4(o + result.t * d, 1.0);
  ivec2 exact = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * viewport));
  bool inside = clip.w > 0.0 && all(greaterThanEqual(exact, ivec2(0))) &&
    all(lessThan(exact, ivec2(viewport)));
  vec4 there = inside ? texelFetch(gPosition, exact, 0) : vec4(0.0, 0.0, 0.0, -1.0);
  // The same surface: near the crossing and of the same role (where a mirror stands
  // on the floor, the floor's crossing at the wall's foot projects onto the wall's
  // own pixel, within reach; the floor's tiles differ in material, not in role).
  bool same = there.w >= 0.0 &&
    texelFetch(gNormal, exact, 0).w == texelFetch(gNormal, q, 0).w &&
    distance(there.xyz, o + result.t * d) < 4.0 * abs(clip.w) * pixelScale + tolerance;
  result.pixel = same ? exact : q;
}

// The normal of a refractor hit, smoothed across pixels, or the refracted image
// shows the pixel grid. Outside the march's loop: on llvmpipe, code in a loop
// runs for a whole group of pixels whenever one of them takes it.
void SmoothHitNormal(vec3 o, vec3 d, inout March result)
{
  if (result.kind == REFRACTOR)
  {
    result.normal = SspSmoothNormal(refractorPosition, refractorNormal, worldToClip, viewport,
      pixelScale, o + result.t * d, result.pixel, result.layer, float(result.material),
      result.normal);
  }
}

// The march's sample j of `steps` along `line` (pixel-step centres, the last at the
// segment's end): true when it meets the opaque G-buffer or a refractor layer
// (see MarchRay), with `result` filled; untouched otherwise. `covered` says which of
// the surfaces it consults hold a surface at its pixel (bits 1: opaque, 2: next,
// 4: current).
bool MarchSample(vec3 o, vec3 d, SspLine line, vec2 depthLine, int j, int steps, int next,
  int current, int layers, inout March result, out int covered)
{
  float u = min(1.0, (float(j) + 0.5) / float(steps));
  vec2 s = mix(line.start.xy, line.end.xy, u);
  ivec2 q = clamp(ivec2(floor(s)), ivec2(0), ivec2(viewport) - 1);
  float t = SspLineT(line, u);
  bool useNext = next >= 0 && next < layers;
  bool useCurrent = current >= 0 && current < layers;
  vec4 opaque = texelFetch(gPosition, q, 0);
  vec4 nextSample = useNext ? texelFetch(refractorPosition, ivec3(q, max(next, 0)), 0)
                            : vec4(0.0, 0.0, 0.0, -1.0);
  vec4 currentSample = useCurrent ? texelFetch(refractorPosition, ivec3(q, max(current, 0)), 0)
                                  : vec4(0.0, 0.0, 0.0, -1.0);
  covered = (opaque.w >= 0.0 ? 1 : 0) + (nextSample.w >= 0.0 ? 2 : 0) +
    (currentSample.w >= 0.0 ? 4 : 0);
  if (t <= tolerance)
  {
    return false;
  }
  vec3 x = o + t * d;
  float depth = depthLine.x + t * depthLine.y; // ViewDepth(x): affine in t
  vec3 opaqueNormal = texelFetch(gNormal, q, 0).xyz;
  bool beyondOpaque = opaque.w >= 0.0 && Beyond(x, depth, opaque.xyz, opaqueNormal);
  if (beyondOpaque && Leaving(o, d, x, opaque.xyz, opaqueNormal))
  {
    result.leaving = true;
  }
  else if (beyondOpaque)
  {
    result.kind = OPAQUE; // refined once the march ends (RefineOpaqueHit)
    result.t = t;
    result.pixel = q;
    result.hidden = FromBehind(d, opaque.xyz, opaqueNormal);
    return true;
  }
  if (useNext && RefractorLayerHit(o, d, t, depth, q, next, nextSample, true, result))
  {
    return true;
  }
  return useCurrent && j > 1 &&
    RefractorLayerHit(o, d, t, depth, q, current, currentSample, false, result);
}

// Marches o + t d across the screen up to t = tLimit. next/current: refractor layers
// whose surfaces end the march when the ray's depth passes beyond (next) or comes in
// front of (current) them; -1 to ignore. The march strides MARCH_STRIDE pixels
// and walks the pixels of the stride back one by one once a sample has met
// something, so the first crossing is found at pixel steps: the surfaces it
// meets stay behind (or in front) once passed, and only a feature thinner than
// the stride, passed and left within it, can be missed. On llvmpipe the march
// is most of a frame's time (docs/technique-screen-space.md, "Refraction").
March MarchRay(vec3 o, vec3 d, int next, int current, float tLimit)
{
  March result;
  result.kind = MISS;
  result.t = 0.0;
  result.pixel = ivec2(0);
  result.layer = -1;
  result.normal = vec3(0.0);
  result.material = -1;
  result.role = ROLE_NONE;
  result.radiance = vec3(0.0);
  result.leftView = false;
  result.hidden = false;
  result.leaving = false;
  result.exact = false;
  result.geometric = vec3(0.0);
  float t0 = 0.0;
  float t1 = 3.0e38;
  if (!CausticsClipToBox(o, d, boundsMin - vec3(tolerance), boundsMax + vec3(tolerance), t0, t1))
  {
    return result;
  }
  float tScene = t1;
  bool inView = SspClipToFrustum(worldToClip, o, d, t0, t1);
  result.leftView = !inView || t1 < tScene;
  if (!inView || t0 >= tLimit)
  {
    return result;
  }
  // Past tLimit the caller has its hit already (a specular triangle).
  t1 = min(t1, tLimit);
  // Where the march of a ray leaving a mirror ends at the scene's box on nothing, a
  // second, short segment two pixel footprints past it: a ray that crosses the floor at
  // the box's bottom next to the mirror's foot ends at the crossing, where its last
  // sample projects onto the wall and sees nothing beyond. A hit found there must cross
  // its surface's plane at the box's face (a floor's plane met past its edge, or far
  // behind, is nothing). One loop, so that the march's code is compiled once.
  bool extend = !result.leftView && t1 < tLimit;
  float tBox = t1;
  int layers = int(ldiObjects[0].y);
  vec4 clipOrigin = worldToClip * vec4(o, 1.0);
  vec4 clipDirection = worldToClip * vec4(d, 0.0);
  vec2 depthLine = viewOrigin.w > 0.0 ? vec2(clipOrigin.w, clipDirection.w)
                                      : vec2(clipOrigin.z, clipDirection.z);
  int firstSteps = 0;
  bool inMargin = false;
  for (int segment = 0; segment < 2 && result.kind == MISS; ++segment)
  {
    if (segment == 1)
    {
      t0 = tBox;
      t1 = tBox + tolerance + 2.0 * PixelFootprint(o + tBox * d);
      if (!extend || !result.leaving || !SspClipToFrustum(worldToClip, o, d, t0, t1))
      {
        break;
      }
    }
    vec4 c0 = worldToClip * vec4(o + t0 * d, 1.0);
    vec4 c1 = worldToClip * vec4(o + t1 * d, 1.0);
    SspLine line;
    line.start = vec4((c0.xy / c0.w * 0.5 + 0.5) * viewport, 1.0 / c0.w, t0);
    line.end = vec4((c1.xy / c1.w * 0.5 + 0.5) * viewport, 1.0 / c1.w, t1);
    vec2 span = abs(line.end.xy - line.start.xy);
    int steps = int(clamp(ceil(max(span.x, span.y)), 1.0, max(viewport.x, viewport.y) + 1.0));
    line.info = vec4(float(steps), 0.0, 0.0, 0.0);
    firstSteps = segment == 0 ? steps : firstSteps;
    // One sample per pixel step, at the step's centre, and one at the segment's end;
    // each is compared with the surfaces of the pixel it projects to. Inside a
    // refractor too the march strides, and it also walks back where a surface it
    // consults ends (the stride's sample has left the surface's outline, the ball's
    // back layer at its rim): a crossing just before the outline would be missed.
    int wasCovered = 0;
    for (int coarse = 0; coarse < steps + MARCH_STRIDE; coarse += MARCH_STRIDE)
    {
      int j = min(coarse, steps);
      int covered;
      bool hit =
        MarchSample(o, d, line, depthLine, j, steps, next, current, layers, result, covered);
      if (hit || (wasCovered & ~covered) != 0)
      {
        // The first sample of the stride that meets a surface replaces the stride's.
        bool earlier = false;
        int unused;
        for (int fine = max(j - MARCH_STRIDE + 1, 0); fine < j && !earlier; ++fine)
        {
          earlier =
            MarchSample(o, d, line, depthLine, fine, steps, next, current, layers, result, unused);
        }
        hit = hit || earlier;
      }
      if (hit)
      {
        break;
      }
      wasCovered = covered;
    }
    inMargin = segment == 1 && result.kind != MISS;
  }
  // A ray that ends on nothing within the pixel or two it starts in, where it was taken
  // for leaving a surface, is one the screen cannot resolve: from a mirror's foot it
  // crosses the floor within the wall's own pixel, then leaves the scene under it.
  result.hidden = result.hidden ||
    (result.kind == MISS && !result.leftView && result.leaving && firstSteps <= 2);
  if (inMargin && result.kind == OPAQUE)
  {
    // The surface's tangent plane, met at the box's face (within the margin before it).
    vec3 p = texelFetch(gPosition, result.pixel, 0).xyz;
    vec3 n = texelFetch(gNormal, result.pixel, 0).xyz;
    float along = dot(d, n);
    float crossing = abs(along) > 1e-4 ? dot(p - o, n) / along : -1.0;
    float reach = tolerance + 2.0 * PixelFootprint(o + tBox * d);
    inMargin = !(crossing > max(tBox - reach, 0.0) && crossing <= tBox + tolerance);
  }
  RefineOpaqueHit(o, d, result);
  if (inMargin)
  {
    result.kind = MISS;
    result.t = 0.0;
    result.hidden = false;
  }
  SmoothHitNormal(o, d, result);
  return result;
}

// Display colour of the opaque surface at pixel q.
vec3 Shade(ivec2 q)
{
  int role = int(texelFetch(gNormal, q, 0).w + 0.5);
  vec3 albedo = texelFetch(gAlbedo, q, 0).rgb;
  vec3 caustic =
    role == ROLE_RECEIVER ? max(texelFetch(causticIrradiance, q, 0).rgb, vec3(0.0)) : vec3(0.0);
  if (abs(texelFetch(delegateDepth, q, 0).r - texelFetch(gDepth, q, 0).r) <= depthTolerance)
  {
    // As the composite shows it: VTK's colour, less the light specular actors block.
    vec3 color = texelFetch(delegateColor, q, 0).rgb;
    if (role == ROLE_RECEIVER && hasLostShading != 0)
    {
      color = max(color - albedo * texelFetch(lostShading, q, 0).rgb, vec3(0.0));
    }
    return color + albedo * caustic;
  }
  if (role == ROLE_RECEIVER)
  {
    vec3 direct = hasDirect != 0 ? texelFetch(directIrradiance, q, 0).rgb : vec3(0.0);
    return albedo * (direct + caustic);
  }
  return background; // a surface hidden from VTK's view: not in any image
}

// Display colour at the point h of the opaque surface that pixel q shows: bilinear over
// the four pixels around h's projection that show a surface of q's role through h's
// neighbourhood (within a few pixel footprints of q's tangent plane), or q's own colour.
// The reference shades the exact point; the nearest pixel shifted a tiled floor seen
// through water by up to half a pixel.
vec3 ShadeAt(vec3 h, ivec2 q)
{
  vec4 clip = worldToClip * vec4(h, 1.0);
  if (!(clip.w > 0.0))
  {
    return Shade(q);
  }
  vec2 s = (clip.xy / clip.w * 0.5 + 0.5) * viewport - 0.5;
  vec2 base = floor(s);
  vec2 f = s - base;
  vec4 normalRole = texelFetch(gNormal, q, 0);
  vec3 n = normalize(normalRole.xyz);
  float reach = 4.0 * clip.w * pixelScale + tolerance;
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 p = ivec2(base) + ivec2(i, j);
      if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(viewport))))
      {
        continue;
      }
      vec4 there = texelFetch(gPosition, p, 0);
      bool same = there.w >= 0.0 && texelFetch(gNormal, p, 0).w == normalRole.w &&
        abs(dot(there.xyz - h, n)) < reach && distance(there.xyz, h) < 2.0 * reach;
      float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      if (same && w > 0.0)
      {
        sum += w * Shade(p);
        weights += w;
      }
    }
  }
  return weights > 0.0 ? sum / weights : Shade(q);
}

// The role, normal and material of a hit: the opaque G-buffer's at the march's
// pixel (an impostor hit brings its own, from its map).
void CompleteHit(inout March m)
{
  if (m.kind == OPAQUE && m.role == ROLE_NONE)
  {
    vec4 normalRole = texelFetch(gNormal, m.pixel, 0);
    m.role = int(normalRole.w + 0.5);
    m.normal = normalize(normalRole.xyz);
    m.material = int(texelFetch(gPosition, m.pixel, 0).w + 0.5);
  }
  else if (m.kind == REFRACTOR)
  {
    m.role = ROLE_REFRACTOR;
  }
}

// The camera pixel that shows the surface point h, of role `role`, in the opaque
// G-buffer (within `slack` m and a few pixel footprints), or (-1, -1) where the camera
// does not see it (a surface of another role within reach, such as a mirror wall whose
// foot stands on the floor at h, is not it).
ivec2 CameraPixel(vec3 h, float slack, int role)
{
  vec4 clip = worldToClip * vec4(h, 1.0);
  if (!(clip.w > 0.0))
  {
    return ivec2(-1);
  }
  ivec2 q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * viewport));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(viewport))))
  {
    return ivec2(-1);
  }
  vec4 there = texelFetch(gPosition, q, 0);
  bool same = there.w >= 0.0 && int(texelFetch(gNormal, q, 0).w + 0.5) == role &&
    distance(there.xyz, h) < 4.0 * clip.w * pixelScale + slack + tolerance;
  return same ? q : ivec2(-1);
}

// o + t d traced against the distance impostors (004 §2-4): outside, against the
// map of what surrounds the kind of object the ray left (`leftRole`), and, leaving a
// mirror after `bounces` mirror-to-mirror reflections in a row, the mirrors' own
// map (ImpostorEnvironmentSearch: a concave mirror sees itself); inside a
// refractor, against its own map (the exit point and its normal, §4) and the
// environment's, whichever is nearer (an open refractor such as a water surface
// has no exit below: the ray meets the pool's floor). An opaque hit carries the
// camera pixel that shows it (Shade()), or (-1, -1) and its map's colour, with the
// caustic store read over at least the pixel's footprint there (`width`: m at o, and
// its growth per metre along d).
March ImpostorRay(vec3 o, vec3 d, bool inside, int leftRole, int bounces, vec2 width)
{
  March m;
  m.kind = MISS;
  m.t = 0.0;
  m.pixel = ivec2(-1);
  m.layer = -1;
  m.normal = vec3(0.0);
  m.material = -1;
  m.role = ROLE_NONE;
  m.radiance = vec3(0.0);
  m.leftView = false;
  m.hidden = false;
  m.leaving = false;
  m.exact = false;
  m.geometric = vec3(0.0);
  float t;
  ivec3 texel;
  bool found = ImpostorEnvironmentSearch(o, d, inside ? ROLE_REFRACTOR : leftRole, bounces,
    boundsMin, boundsMax, tolerance, t, texel);
  float tExit;
  ivec3 exitTexel;
  if (inside && exactSpecular == 0 && ImpostorSearch(
                  IMPOSTOR_REFRACTOR_SURFACE, o, d, boundsMin, boundsMax, tolerance, tExit, exitTexel) &&
    (!found || tExit < t))
  {
    found = true;
    t = tExit;
    texel = exitTexel;
  }
  if (!found)
  {
    return m;
  }
  vec4 position = texelFetch(impostorPosition, texel, 0);
  vec4 normalRole = texelFetch(impostorNormal, texel, 0);
  m.t = t;
  m.material = int(position.w + 0.5);
  m.role = int(normalRole.w + 0.5);
  m.normal = normalize(normalRole.xyz);
  m.kind = m.role == ROLE_REFRACTOR ? REFRACTOR : OPAQUE;
  if (m.kind == OPAQUE)
  {
    vec3 h = o + t * d;
    float texelSize = 4.0 * distance(h, impostorCentre[texel.z / 6]) / float(impostorResolution);
    m.pixel = CameraPixel(h, texelSize, m.role);
    // The map's direct light, and the caustic a photon technique stored there (net
    // of the light the specular objects block: no shadow otherwise).
    m.radiance = max(texelFetch(impostorRadiance, texel, 0).rgb +
        causticsMaterials[m.material].albedoRole.rgb *
          ImpostorCausticIrradiance(texel, width.x + width.y * t),
      vec3(0.0));
  }
  return m;
}

// The glass or mirror triangle o + t d meets first (exactSpecular), as a hit of the
// march: its exact point, face normal and interpolated normal.
bool ExactSpecularHit(vec3 o, vec3 d, out March m)
{
  SpecularHit s;
  bool found = exactSpecular != 0 && SpecularTrace(o, d, 0.01 * tolerance, 3.0e38, s);
  m.role = found ? int(causticsMaterials[s.material].albedoRole.a + 0.5) : ROLE_NONE;
  m.kind = !found ? MISS : (m.role == ROLE_REFRACTOR ? REFRACTOR : OPAQUE);
  m.t = s.t;
  m.pixel = ivec2(-1);
  m.layer = -1;
  m.normal = s.shading;
  m.material = s.material;
  m.radiance = vec3(0.0);
  m.leftView = false;
  m.hidden = false;
  m.leaving = false;
  m.exact = found;
  m.geometric = s.geometric;
  return found;
}

// The normals of hit m on d's side, as the reference's FacingNormals: the face decides
// the side (exact hits; otherwise the interpolated normal is the face), `n` is the
// interpolated normal turned to it.
void FacingNormals(vec3 d, March m, out vec3 n, out vec3 face)
{
  face = m.exact ? m.geometric : m.normal;
  bool front = dot(d, face) <= 0.0;
  n = front ? m.normal : -m.normal;
  face = front ? face : -face;
}

// The mirror normal of hit m for d: the interpolated one, or the face's own where the
// interpolated one would send the mirrored ray into the surface.
vec3 FacingNormal(vec3 d, March m)
{
  vec3 n, face;
  FacingNormals(d, m, n, face);
  return dot(d, n) >= 0.0 || dot(reflect(d, n), face) <= 0.0 ? face : n;
}

// The dielectric interface of hit m met by d, from index n1 into n2 (CausticsDielectric),
// on the interpolated normal unless a direction would leave on the wrong side of the
// face, then on the face (as the reference). False under total internal reflection.
bool ScatterDielectric(vec3 d, March m, float n1, float n2, out float reflectance,
  out vec3 reflected, out vec3 refracted)
{
  vec3 n, face;
  FacingNormals(d, m, n, face);
  bool transmits =
    CausticsDielectric(d, n, clamp(-dot(d, n), 0.0, 1.0), n1, n2, reflectance, reflected, refracted);
  if (m.exact &&
    !(dot(d, n) < 0.0 && dot(reflected, face) > 0.0 && (!transmits || dot(refracted, face) < 0.0)))
  {
    transmits = CausticsDielectric(
      d, face, clamp(-dot(d, face), 0.0, 1.0), n1, n2, reflectance, reflected, refracted);
  }
  return transmits;
}

// One camera path's state along TracePath: where it is and heads, what it still
// carries, the refractor layers it is between, and the events it has used.
struct CameraPath
{
  vec3 o;          // origin of the next march
  vec3 d;          // direction
  vec3 throughput; // the share of the pixel's colour it carries
  vec3 absorption; // Beer-Lambert coefficients while inside
  bool inside;     // inside a refractor
  bool impostor;   // traced against the distance impostors from here on
  int current;     // refractor layers it is between (-1: not consulted)
  int next;
  int event;       // interfaces met
  int leftRole;    // role of the surface it left
  int bounces;     // mirror-to-mirror reflections in a row
  float width;     // the pixel's footprint at o (m), as flat mirrors carry it
  bool spreads;    // whether it still grows with the distance (not after glass: a
                   // lens can focus it, and a footprint too wide blurs what it shows)
};

// The footprint's growth per metre of a path that left the camera's surfaces: a
// perspective camera's pixels diverge by pixelScale radians; an orthographic one's
// are parallel.
float FootprintGrowth(bool spreads)
{
  return spreads && viewOrigin.w > 0.0 ? pixelScale : 0.0;
}

// What a path that leaves a surface the camera sees brings back, in display
// colour: o + t d marched through the refractor's layers (`inside` the refractor
// between layers `current` and `next`; next = -1: the layers are not consulted,
// as for rays that mirrors turned, whose order along the view the layers no
// longer give), refracted with exact Fresnel weights (total internal reflection
// stays inside), reflected by mirrors with the conductor's Fresnel reflectance,
// until it meets another opaque surface (its colour) or leaves (the background),
// at most maxEvents interfaces. At a dielectric that transmits, the Fresnel-
// reflected part (weight R) is not dropped: it is kept as one deferred branch and
// traced once the refracted path ends (the internal reflections inside glass: at
// the ball lens's far side 4 % at normal incidence, all of it towards the rim), with
// the events it has left; while the branch is held, further reflected parts are
// dropped (their weight is R x R' at most). One loop with one march, so that the
// march's code is compiled once (llvmpipe compiles each inlined copy). `spreads`: the
// pixel's footprint grows along the path (reflected at the camera's surface; a path
// refracted there, as one refracted later, keeps the footprint it had).
vec3 TracePath(vec3 o, vec3 d, bool inside, int current, int next, vec3 absorption,
  int leftRole, bool spreads)
{
  vec3 color = vec3(0.0);
  CameraPath path = CameraPath(o, d, vec3(1.0), absorption, inside,
    viewMethod == METHOD_IMPOSTORS, current, next, 0, leftRole, 0, PixelFootprint(o),
    spreads);
  // The deferred reflected branch (held: its throughput is not zero).
  bool held = false;
  CameraPath branch = path;
  for (int step = 0; step < 2 * maxEvents; ++step)
  {
    // The path ends: on a surface, leaving, or out of events; then the held branch.
    bool ends = path.event >= maxEvents;
    vec3 ending = background;
    vec3 x = path.o;
    March m;
    if (!ends)
    {
      // Glass and mirrors traced as triangles: the march and the impostors look for
      // what lies around them, up to the triangle, and the layers are not consulted.
      March specular;
      bool exact = ExactSpecularHit(path.o, path.d, specular);
      bool layers = exactSpecular == 0;
      if (!path.impostor)
      {
        m = MarchRay(path.o, path.d, layers ? path.next : -1,
          layers && path.inside ? path.current : -1, exact ? specular.t + tolerance : 3.0e38);
        // The combined view takes the impostors where the march cannot see: the ray
        // left the view, or what it meets the screen does not show (March.hidden).
        path.impostor =
          viewMethod == METHOD_BOTH && ((m.kind == MISS && m.leftView) || m.hidden);
      }
      if (path.impostor)
      {
        m = ImpostorRay(path.o, path.d, path.inside, path.leftRole, path.bounces,
          vec2(path.width, FootprintGrowth(path.spreads)));
      }
      if (exact && (m.kind == MISS || specular.t <= m.t + tolerance))
      {
        m = specular;
      }
      CompleteHit(m);
      if (path.inside)
      {
        path.throughput *= CausticsTransmittance(path.absorption, m.t);
      }
      x = path.o + m.t * path.d;
      ends = m.kind == MISS || (m.kind == OPAQUE && m.role != ROLE_REFLECTOR);
      if (m.kind == OPAQUE && m.role != ROLE_REFLECTOR)
      {
        ending = m.pixel.x >= 0 ? ShadeAt(x, m.pixel) : m.radiance;
      }
    }
    if (ends)
    {
      color += path.throughput * ending;
      if (!held)
      {
        return color;
      }
      held = false;
      path = branch;
      continue;
    }
    ++path.event;
    path.width += FootprintGrowth(path.spreads) * m.t;
    if (m.kind == OPAQUE)
    {
      CausticsMaterial mirror = causticsMaterials[m.material];
      vec3 facing = FacingNormal(path.d, m);
      path.bounces = path.leftRole == ROLE_REFLECTOR ? path.bounces + 1 : 0;
      path.throughput *= FresnelConductor(
        clamp(-dot(path.d, facing), 0.0, 1.0), mirror.metalN.rgb, mirror.metalK.rgb);
      path.d = reflect(path.d, facing);
      path.next = -1;
      path.current = -1;
      path.inside = false;
      path.leftRole = ROLE_REFLECTOR;
    }
    else
    {
      CausticsMaterial hitMaterial = causticsMaterials[m.material];
      float hitIor = max(hitMaterial.params.x, 1.0);
      // An exact hit's face says which side the ray is on (a closed mesh's inside);
      // otherwise the path's own count of crossings does.
      path.inside = m.exact ? dot(path.d, m.geometric) > 0.0 : path.inside;
      float n1 = path.inside ? hitIor : 1.0;
      float n2 = path.inside ? 1.0 : hitIor;
      float r;
      vec3 mirrored, refracted;
      if (ScatterDielectric(path.d, m, n1, n2, r, mirrored, refracted))
      {
        vec3 reflectedThroughput = path.throughput * r;
        if (internalReflections != 0 && !held &&
          max(reflectedThroughput.r, max(reflectedThroughput.g, reflectedThroughput.b)) >=
            MIN_BRANCH_WEIGHT)
        {
          // The reflected part stays on this side: inside, between the same layers
          // (as total internal reflection); outside, off the layers' order. It starts
          // its mirror-to-mirror count afresh.
          held = true;
          branch = path;
          branch.o = x;
          branch.d = mirrored;
          branch.throughput = reflectedThroughput;
          branch.current = path.inside ? path.current : -1;
          branch.next = path.inside ? path.next : -1;
          branch.leftRole = ROLE_REFRACTOR;
          branch.bounces = 0;
        }
        path.throughput *= 1.0 - r;
        path.d = refracted;
        path.inside = !path.inside;
        path.absorption = hitMaterial.attenuation.rgb;
        path.current = m.layer;
        path.next = path.current + 1;
        path.leftRole = ROLE_REFRACTOR;
        path.spreads = false;
      }
      else
      {
        path.d = mirrored; // total internal reflection: still between the same layers
      }
    }
    path.o = x;
  }
  // Out of steps with a path still going: it ends as one out of events does.
  return color + path.throughput * background +
    (held ? branch.throughput * background : vec3(0.0));
}

// The camera's first surface at x (normal n as the G-buffer has it) along the view
// direction v, as a hit: the exact triangle where the hierarchy meets it there (x
// moves onto it), whose face then decides the side the camera sees, as the
// reference's does.
March FirstSurface(inout vec3 x, vec3 v, vec3 n, int material)
{
  vec3 o = viewOrigin.w > 0.0 ? viewOrigin.xyz : x - distance(boundsMin, boundsMax) * v;
  March m;
  if (ExactSpecularHit(o, v, m) && distance(o + m.t * v, x) < PixelFootprint(x) + tolerance)
  {
    x = o + m.t * v;
    return m;
  }
  m.exact = false;
  m.t = distance(o, x);
  m.normal = n;
  m.geometric = n;
  m.material = material;
  return m;
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outColor = vec4(0.0);
  vec4 opaque = texelFetch(gPosition, pixel, 0);
  vec4 front = ldiObjects[0].y > 0u ? texelFetch(refractorPosition, ivec3(pixel, 0), 0)
                                    : vec4(0.0, 0.0, 0.0, -1.0);
  // The paths that leave the surface the camera sees: weight, direction.
  vec3 weights[2];
  vec3 directions[2];
  int paths = 0;
  vec3 x;
  vec3 absorption = vec3(0.0);
  int leftRole = ROLE_REFLECTOR;
  int eyeIn = -1; // the refractor the eye is in, as this pixel sees it; -1: air
  if (front.w < 0.0 || (opaque.w >= 0.0 && ViewDepth(opaque.xyz) < ViewDepth(front.xyz)))
  {
    // No refractor in front: a mirror, where VTK drew it (VTK shows no reflection
    // of the scene), reflects the view.
    vec4 normalRole = texelFetch(gNormal, pixel, 0);
    if (opaque.w < 0.0 || int(normalRole.w + 0.5) != ROLE_REFLECTOR ||
      abs(texelFetch(delegateDepth, pixel, 0).r - texelFetch(gDepth, pixel, 0).r) > depthTolerance)
    {
      return;
    }
    x = opaque.xyz;
    vec3 v = viewOrigin.w > 0.0 ? normalize(x - viewOrigin.xyz) : viewOrigin.xyz;
    March first = FirstSurface(x, v, normalize(normalRole.xyz), int(opaque.w + 0.5));
    vec3 facing = FacingNormal(v, first);
    CausticsMaterial mirror = causticsMaterials[int(opaque.w + 0.5)];
    weights[0] =
      FresnelConductor(clamp(-dot(v, facing), 0.0, 1.0), mirror.metalN.rgb, mirror.metalK.rgb);
    directions[0] = reflect(v, facing);
    paths = 1;
  }
  else
  {
    // Only where the refractor is what VTK drew.
    vec4 frontClip = worldToClip * vec4(front.xyz, 1.0);
    float frontDepth = frontClip.z / frontClip.w * 0.5 + 0.5;
    if (abs(texelFetch(delegateDepth, pixel, 0).r - frontDepth) > 1e-4)
    {
      return;
    }
    x = front.xyz;
    vec3 v = viewOrigin.w > 0.0 ? normalize(x - viewOrigin.xyz) : viewOrigin.xyz;
    March first =
      FirstSurface(x, v, texelFetch(refractorNormal, ivec3(pixel, 0), 0).xyz, int(front.w + 0.5));
    CausticsMaterial material = causticsMaterials[first.material];
    float ior = max(material.params.x, 1.0);
    bool backFace = dot(v, first.geometric) > 0.0;
    // The eye's medium: the closed refractor it is in (eyeMaterial), else, as the
    // reference decides at every surface, the refractor whose surface this pixel sees
    // from its back side (the side its normal does not point to): a camera under an
    // open water sheet (one surface, normal up) is in the water, one above it is in
    // air. A camera beside the sheet is in air where it sees the sheet's front, in the
    // water where it sees its back (below the sheet's plane), as the reference takes it
    // though no water is modelled around the eye. The interpolated normal decides: at a
    // closed refractor's silhouette, seen from outside, it can face away from the eye
    // (a grazing pixel, mostly reflected either way). From the eye's medium into the
    // other: from air into the refractor, or out of it (the surface seen first is the
    // way out, and the light has crossed the medium up to it).
    eyeIn = eyeMaterial >= 0 ? eyeMaterial : (backFace ? first.material : -1);
    bool eyeInGlass = eyeIn >= 0;
    float n1 = eyeInGlass ? max(causticsMaterials[eyeIn].params.x, 1.0) : 1.0;
    float n2 = eyeInGlass ? 1.0 : ior;
    float reflectance;
    vec3 reflected, refracted;
    bool transmits = ScatterDielectric(v, first, n1, n2, reflectance, reflected, refracted);
    vec3 crossed = eyeInGlass ? CausticsTransmittance(
      causticsMaterials[eyeIn].attenuation.rgb, distance(x, viewOrigin.xyz)) : vec3(1.0);
    weights[0] = crossed * reflectance; // reflected, staying in the eye's medium
    directions[0] = reflected;
    weights[1] = crossed * (1.0 - reflectance); // refracted, into the other
    directions[1] = refracted;
    paths = transmits ? 2 : 1;
    absorption = (eyeInGlass ? causticsMaterials[eyeIn] : material).attenuation.rgb;
    leftRole = ROLE_REFRACTOR;
  }
  vec3 color = vec3(0.0);
  for (int k = 0; k < paths; ++k)
  {
    // In the glass: the refracted path from air, the reflected one from inside. Only
    // the path from air into the glass follows the refractor's layers along the pixel
    // (the next is layer 1); the others have turned off that line.
    bool inside = (k == 1) != (eyeIn >= 0);
    bool alongLayers = k == 1 && eyeIn < 0;
    color += weights[k] *
      TracePath(x, directions[k], inside, alongLayers ? 0 : -1, alongLayers ? 1 : -1,
        absorption, leftRole, k == 0);
  }
  outColor = vec4(color, 1.0);
}
