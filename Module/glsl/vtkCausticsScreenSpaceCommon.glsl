// Shared by the screen-space photon tracing stages (vtkCausticsLayeredDepth,
// vtkCausticsScreenSpaceLineTracer, vtkCausticsScreenSpacePhotonPass and its
// helpers; 000_54cf099eeccf42d9.txt). Host-side layouts must match
// (vtkCausticsLayeredDepth.h, vtkCausticsScreenSpaceLineTracer.h).

// Their shader storage binding points: CAUSTICS_LDI_* and CAUSTICS_SSP_* in
// vtkCausticsBindings.h.

// A ray to trace: origin.xyz (m), origin.w = state (0 none, 1 in air, 2 inside a
// refractor); direction.xyz unit, direction.w = material index of the surface the
// ray leaves (-1: none), used to ignore its own surface near the origin.
struct SspRay
{
  vec4 origin;
  vec4 direction;
};

// The ray's line on screen (window pixels), clipped to the scene bounds and the
// view frustum: start/end = (x, y, 1 / clip w, ray parameter t in m);
// info.x = fragment count n_f of its row (0: nothing to trace), info.y = the ray
// parameter below which hits on the origin's own surface are ignored.
struct SspLine
{
  vec4 start;
  vec4 end;
  vec4 info;
};

// First hit of a ray: position.xyz (m), position.w = t (m, -1: no hit);
// normal.xyz as modelled, normal.w = material index.
struct SspHit
{
  vec4 position;
  vec4 normal;
};

// The stages' shader storage buffers, each layout written once: a shader declares
// the ones it uses with the access it needs, e.g. `SSP_RAYS(readonly);` (an empty
// argument: read and write). The host binds them at the CAUSTICS_SSP_* points.
#define SSP_COUNTER(access) layout(std430, binding = CAUSTICS_SSP_COUNTER_BINDING) access buffer SspCounter { uint rayCount; }
#define SSP_RAYS(access) layout(std430, binding = CAUSTICS_SSP_RAY_BINDING) access buffer SspRays { SspRay rays[]; }
#define SSP_PAYLOADS(access) layout(std430, binding = CAUSTICS_SSP_PAYLOAD_BINDING) access buffer SspPayloads { SspPayload payloads[]; }
#define SSP_LINES(access) layout(std430, binding = CAUSTICS_SSP_LINE_BINDING) access buffer SspLines { SspLine lines[]; }
#define SSP_HITS(access) layout(std430, binding = CAUSTICS_SSP_HIT_BINDING) access buffer SspHits { SspHit hits[]; }
#define SSP_NEXT_RAYS(access) layout(std430, binding = CAUSTICS_SSP_NEXT_RAY_BINDING) access buffer SspNextRays { SspRay nextRays[]; }
#define SSP_NEXT_PAYLOADS(access) layout(std430, binding = CAUSTICS_SSP_NEXT_PAYLOAD_BINDING) access buffer SspNextPayloads { SspPayload nextPayloads[]; }
#define SSP_NEXT_COUNTER(access) layout(std430, binding = CAUSTICS_SSP_NEXT_COUNTER_BINDING) access buffer SspNextCounter { uint nextCount; }
// The layered depth image's table (vtkCausticsLayeredDepth): ldiHeader.x objects; of
// object i, ldiObjects[i].x is its first layer and .y its number of layers (packed:
// none behind an empty one).
#define SSP_LDI_TABLE(access) layout(std430, binding = CAUSTICS_LDI_TABLE_BINDING) access buffer SspLayerTable { uvec4 ldiHeader; uvec4 ldiObjects[]; }

// Ray parameter at the screen-linear parameter u in [0, 1] of a projected segment:
// t is perspective-correct, interpolated with 1/w as the rasterizer would.
float SspLineT(SspLine line, float u)
{
  float a = (1.0 - u) * line.start.z;
  float b = u * line.end.z;
  float denominator = a + b;
  return denominator > 0.0 ? (a * line.start.w + b * line.end.w) / denominator
                           : mix(line.start.w, line.end.w, u);
}

// Pixel sampled by fragment `column` of the line's row (its centre on the line).
ivec2 SspLinePixel(SspLine line, int column, ivec2 viewport)
{
  float u = (float(column) + 0.5) / line.info.x;
  vec2 s = mix(line.start.xy, line.end.xy, u);
  return clamp(ivec2(floor(s)), ivec2(0), viewport - 1);
}

// Clips o + t d to the clip volume of worldToClip (Liang-Barsky on -w <= x, y, z <= w).
bool SspClipToFrustum(mat4 worldToClip, vec3 o, vec3 d, inout float t0, inout float t1)
{
  vec4 c0 = worldToClip * vec4(o, 1.0);
  vec4 cd = worldToClip * vec4(d, 0.0);
  for (int a = 0; a < 3; ++a)
  {
    for (int s = -1; s <= 1; s += 2)
    {
      // Inside: w + s * c[a] >= 0.
      float p = c0.w + float(s) * c0[a];
      float q = cd.w + float(s) * cd[a];
      if (abs(q) < 1e-20)
      {
        if (p < 0.0)
        {
          return false;
        }
        continue;
      }
      float t = -p / q;
      if (q > 0.0)
      {
        t0 = max(t0, t);
      }
      else
      {
        t1 = min(t1, t);
      }
    }
  }
  return t0 < t1;
}

// What a photon carries besides its ray: flux.rgb (W), flux.a = specular events
// so far; info.x = a stable photon id (its emitter texel: deterministic Russian
// roulette, neighbours for the radius rule), info.y = its path length from the
// light so far (m, float bits), info.z = its emission texel's measure (m^2 or sr,
// float bits): what a landed photon record holds (vtkCausticsCommon.glsl).
struct SspPayload
{
  vec4 flux;
  uvec4 info;
};

// How far from a layered depth image sample (point p, normal n as modelled, a pixel
// `footprint` wide there) a ray may meet the sample's tangent plane and still hit its
// surface: the tolerance and two footprints, stretched by a grazing view by at most 10
// (beyond, near silhouettes, the tangent plane no longer follows the surface).
// viewOrigin: camera position (w = 1) or view direction (w = 0, parallel).
float SspSampleReach(vec4 viewOrigin, vec3 p, vec3 n, float footprint, float tolerance)
{
  vec3 view = viewOrigin.w > 0.0 ? normalize(p - viewOrigin.xyz) : viewOrigin.xyz;
  return tolerance + 2.0 * footprint / max(abs(dot(view, n)), 0.1);
}

// Whether surface sample s (xyz world, w material, -1: none; sn: normal as modelled,
// w role) at the pixel x projects to shows that a receiver (normal n) goes on at x, a
// point of its tangent plane, `reach` being how far from a sample a ray may meet its
// tangent plane at that pixel (SspSampleReach): s is a receiver sample on x's plane near
// x, or the surface the receiver ends against (or one standing on it) with x within
// the reach of its plane, in the part of the pixel the receiver covers (a wall's foot).
bool SspSampleContinues(vec4 s, vec4 sn, vec3 n, vec3 x, float reach)
{
  if (s.w < 0.0 || !(dot(sn.xyz, sn.xyz) > 0.0))
  {
    return false;
  }
  vec3 m = normalize(sn.xyz);
  return (int(sn.w + 0.5) == ROLE_RECEIVER && abs(dot(s.xyz - x, n)) <= 0.5 * reach &&
           dot(m, n) >= 0.5 * length(n)) ||
    abs(dot(x - s.xyz, m)) <= reach;
}

// Whether the receiver of a layered depth image sample (normal n, at pixel
// `samplePixel`) ends before x, a point of the sample's tangent plane within its
// `reach`. A ray passing just beyond a receiver's end (a wall's top, a floor's far
// edge) meets the tangent plane of the receiver's last pixels within that reach; taken
// as a hit, it lands on nothing there, and such photons pile up along every end the
// light passes. Told by x's own pixel q: the image holds every layer of a pixel (a
// receiver's layers are as many as its depth complexity), so a surface in front of x
// does not hide the receiver's sample there. The receiver goes on where q holds a
// sample on x's plane, or the surface it ends against (SspSampleContinues). x off the
// view, or in the sample's own pixel, or a receiver seen nearly edge-on (where its
// samples are sparse), says nothing.
bool SspReceiverEndsBefore(sampler2DArray positions, sampler2DArray normals, mat4 worldToClip,
  vec2 viewport, vec4 viewOrigin, ivec2 samplePixel, vec3 n, vec3 x, float reach)
{
  vec3 view = viewOrigin.w > 0.0 ? normalize(x - viewOrigin.xyz) : viewOrigin.xyz;
  if (abs(dot(view, n)) < 0.35 * length(n))
  {
    return false;
  }
  vec4 clip = worldToClip * vec4(x, 1.0);
  if (!(clip.w > 0.0))
  {
    return false;
  }
  ivec2 q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * viewport));
  if (q == samplePixel || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(viewport))))
  {
    return false;
  }
  int layers = textureSize(positions, 0).z;
  for (int l = 0; l < layers; ++l)
  {
    if (SspSampleContinues(
          texelFetch(positions, ivec3(q, l), 0), texelFetch(normals, ivec3(q, l), 0), n, x, reach))
    {
      return false;
    }
  }
  return true;
}

// The normal at the hit point x. Normals constant per pixel would bend photons in
// pixel-sized steps (printing the pixel grid into the caustic), and where the
// camera sees the surface at a grazing angle a pixel's sample lies far from x.
// So the normal is extrapolated to first order from the layer's sample nearest to
// x (within 3 x 3 pixels, same material): its neighbours' positions and normals
// give dn/dp along two directions, and n(x) = n(p) + alpha dn_a + beta dn_b with
// x - p ~ alpha a + beta b (least squares, |alpha|, |beta| <= 1.5).
bool SspSameSurface(sampler2DArray positions, sampler2DArray normals, vec2 viewport, ivec2 q,
  int layer, float material, out vec4 p, out vec3 n)
{
  p = vec4(0.0);
  n = vec3(0.0);
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(viewport))))
  {
    return false;
  }
  p = texelFetch(positions, ivec3(q, layer), 0);
  n = texelFetch(normals, ivec3(q, layer), 0).xyz;
  return p.w == material;
}

// Central (or one-sided) difference of position and normal along one screen axis.
bool SspDifference(sampler2DArray positions, sampler2DArray normals, vec2 viewport, ivec2 q,
  ivec2 axis, int layer, float material, vec4 p, vec3 n, float reach, out vec3 dp, out vec3 dn)
{
  vec4 pa, pb;
  vec3 na, nb;
  bool hasA = SspSameSurface(positions, normals, viewport, q - axis, layer, material, pa, na) &&
    distance(pa.xyz, p.xyz) < reach && dot(na, n) > 0.5;
  bool hasB = SspSameSurface(positions, normals, viewport, q + axis, layer, material, pb, nb) &&
    distance(pb.xyz, p.xyz) < reach && dot(nb, n) > 0.5;
  if (hasA && hasB)
  {
    dp = pb.xyz - pa.xyz;
    dn = nb - na;
  }
  else if (hasB)
  {
    dp = pb.xyz - p.xyz;
    dn = nb - n;
  }
  else if (hasA)
  {
    dp = p.xyz - pa.xyz;
    dn = n - na;
  }
  else
  {
    dp = vec3(0.0);
    dn = vec3(0.0);
  }
  return hasA || hasB;
}

vec3 SspSmoothNormal(sampler2DArray positions, sampler2DArray normals, mat4 worldToClip,
  vec2 viewport, float pixelScale, vec3 x, ivec2 pixel, int layer, float material, vec3 fallback)
{
  // The nearest sample of the same surface around the hit's pixel.
  ivec2 best = pixel;
  float bestDistance = 3.0e38;
  vec4 p;
  vec3 n;
  for (int j = -1; j <= 1; ++j)
  {
    for (int i = -1; i <= 1; ++i)
    {
      vec4 pq;
      vec3 nq;
      if (SspSameSurface(
            positions, normals, viewport, pixel + ivec2(i, j), layer, material, pq, nq) &&
        dot(nq, fallback) > 0.5 && distance(pq.xyz, x) < bestDistance)
      {
        bestDistance = distance(pq.xyz, x);
        best = pixel + ivec2(i, j);
      }
    }
  }
  if (!SspSameSurface(positions, normals, viewport, best, layer, material, p, n))
  {
    return fallback;
  }
  vec4 clip = worldToClip * vec4(p.xyz, 1.0);
  float reach = 8.0 * abs(clip.w) * pixelScale / 0.33; // a few stretched footprints
  vec3 a, na, b, nb;
  bool hasA = SspDifference(
    positions, normals, viewport, best, ivec2(1, 0), layer, material, p, n, reach, a, na);
  bool hasB = SspDifference(
    positions, normals, viewport, best, ivec2(0, 1), layer, material, p, n, reach, b, nb);
  vec3 offset = x - p.xyz;
  float alpha = 0.0;
  float beta = 0.0;
  float aa = dot(a, a);
  float bb = dot(b, b);
  float ab = dot(a, b);
  float determinant = aa * bb - ab * ab;
  if (hasA && hasB && determinant > 1e-6 * aa * bb)
  {
    alpha = (bb * dot(a, offset) - ab * dot(b, offset)) / determinant;
    beta = (aa * dot(b, offset) - ab * dot(a, offset)) / determinant;
  }
  else if (hasA && aa > 0.0)
  {
    alpha = dot(a, offset) / aa;
  }
  else if (hasB && bb > 0.0)
  {
    beta = dot(b, offset) / bb;
  }
  alpha = clamp(alpha, -1.5, 1.5);
  beta = clamp(beta, -1.5, 1.5);
  vec3 result = n + alpha * na + beta * nb;
  return dot(result, result) > 1e-12 ? normalize(result) : fallback;
}
