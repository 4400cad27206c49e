// Final render with a caustic map (001_7c07a484f7a872bb.txt §2 and Eq. 3): the
// light's caustic map is projected onto the visible receivers like a shadow map.
// Every level of the pyramid is sampled bilinearly, each tap counting only if it
// shows the camera pixel's own surface (a receiver whose plane holds the pixel's
// point, with a similar normal): the visibility test. A pixel the map's finest
// level does not see (hidden from the light's view by another receiver) gets no
// caustic light. The levels store irradiance (W/m^2) from energy-normalized
// kernels; Eq. 3's (1/4)^i renormalizes energy counted per texel, whose area is
// 4^i times the finest texel's, so in irradiance it is a plain sum.
// Its kernels are at least a pixel footprint wide (MinimumCameraSplatRadius), so one
// bilinear tap at the pixel's centre reads the pixel's mean. (Caustic triangles,
// which have no kernel, go to the camera's view instead: vtkCausticsPhotonSplatter.)
// With CAUSTICS_STORE (vtkCausticsCausticMap::ApplyStore, glsl/vtkCausticsImpostorCommon.glsl
// before this file) the pass adds instead, at the receiver pixels neither this map nor
// the hidden receivers' map (bound as the front map) sees, the distance impostors'
// caustic store: the photons no receiver layer of the map's view landed.
uniform sampler2D gPosition; // camera G-buffer: world position, w = material (-1: none)
uniform sampler2D gNormal;   // normal as modelled, w = role
uniform sampler2D irradiance[4];
uniform sampler2D receiverPosition[4];
uniform sampler2D receiverNormal[4];
uniform CausticsView mapViews[4];
uniform int levels;
uniform CausticsView cameraView; // the camera the G-buffer was drawn with
// The hidden receivers' map (vtkCausticsCausticMap::Apply with a front map): a pixel
// the front map's finest level sees is the front map's, wholly; this map adds only
// where it does not, so that along the edge between the two layers (coplanar
// receivers, e.g. a floor half in a wall's shadow) no pixel takes both.
uniform bool hasFront;
uniform sampler2D frontPosition; // the front map's finest receivers (same view and size)
uniform sampler2D frontNormal;

layout(location = 0) out vec4 outIrradiance;

// Whether a map texel's receiver (position s, normal sn) is the surface (x, n):
// surfaces closer than `tolerance` to x's tangent plane count as x's own.
bool ShowsSurface(vec4 s, vec4 sn, vec3 x, vec3 n, float tolerance)
{
  return s.w >= 0.0 && dot(sn.xyz, n) >= 0.8 && abs(dot(x - s.xyz, sn.xyz)) <= tolerance;
}

// The same for texel `texel` of map level i.
bool TexelShows(int i, ivec2 texel, vec3 x, vec3 n, float tolerance)
{
  return ShowsSurface(texelFetch(receiverPosition[i], texel, 0),
    texelFetch(receiverNormal[i], texel, 0), x, n, tolerance);
}

// Bilinear irradiance of map level i at x, over the taps that show x's surface,
// and in alpha the same mean of the taps' half-set differences (CausticsDeposit: its
// square is the variance of this mean); `seen` tells whether any did.
vec4 SampleLevel(int i, vec3 x, vec3 n, out bool seen)
{
  seen = false;
  vec2 pixel;
  if (!ViewProject(mapViews[i], x, pixel))
  {
    return vec4(0.0);
  }
  // Surfaces closer than 1.5 texels to x's tangent plane count as x's own: a
  // plane holds them exactly, curvature moves them by far less than a texel.
  float tolerance = 1.5 * ViewTexelSize(mapViews[i], x);
  vec2 f = pixel - 0.5;
  ivec2 base = ivec2(floor(f));
  vec2 w = f - floor(f);
  vec4 sum = vec4(0.0);
  float weights = 0.0;
  ivec2 last = ivec2(mapViews[i].size) - 1;
  for (int b = 0; b < 2; ++b)
  {
    for (int a = 0; a < 2; ++a)
    {
      ivec2 texel = clamp(base + ivec2(a, b), ivec2(0), last);
      if (!TexelShows(i, texel, x, n, tolerance))
      {
        continue;
      }
      float weight = (a == 0 ? 1.0 - w.x : w.x) * (b == 0 ? 1.0 - w.y : w.y) + 1e-6;
      sum += weight * texelFetch(irradiance[i], texel, 0);
      weights += weight;
    }
  }
  seen = weights > 0.0;
  return seen ? sum / weights : vec4(0.0);
}

// Whether a bilinear tap of the front map's finest level shows x's surface (its
// SampleLevel(0) test, on its receivers).
bool FrontSees(vec3 x, vec3 n)
{
  vec2 pixel;
  if (!ViewProject(mapViews[0], x, pixel))
  {
    return false;
  }
  float tolerance = 1.5 * ViewTexelSize(mapViews[0], x);
  ivec2 base = ivec2(floor(pixel - 0.5));
  ivec2 last = ivec2(mapViews[0].size) - 1;
  for (int k = 0; k < 4; ++k)
  {
    ivec2 texel = clamp(base + ivec2(k & 1, k >> 1), ivec2(0), last);
    if (ShowsSurface(texelFetch(frontPosition, texel, 0), texelFetch(frontNormal, texel, 0),
          x, n, tolerance))
    {
      return true;
    }
  }
  return false;
}

#ifdef CAUSTICS_STORE
// Where the camera's ray through `pixel` (continuous pixel coordinates) meets the
// plane (x, n); false where it runs along the plane.
bool CameraRayOnPlane(vec2 pixel, vec3 x, vec3 n, out vec3 hit)
{
  vec2 ndc = pixel / cameraView.size * 2.0 - 1.0;
  vec4 near = cameraView.clipToWorld * vec4(ndc, -1.0, 1.0);
  vec4 far = cameraView.clipToWorld * vec4(ndc, 1.0, 1.0);
  vec3 origin = near.xyz / near.w;
  vec3 direction = far.xyz / far.w - origin;
  float along = dot(direction, n);
  hit = origin + dot(x - origin, n) / along * direction;
  return abs(along) > 1e-6 * length(direction) && AllFinite(hit);
}

// The side of camera pixel `pixel`'s footprint on the plane (x, n) (m; 0 where the
// camera's rays run along it): the store's read window spans at least that.
float FootprintWidth(ivec2 pixel, vec3 x, vec3 n)
{
  vec3 a, b, c;
  bool onPlane = CameraRayOnPlane(vec2(pixel), x, n, a) &&
    CameraRayOnPlane(vec2(pixel) + vec2(1.0, 0.0), x, n, b) &&
    CameraRayOnPlane(vec2(pixel) + vec2(0.0, 1.0), x, n, c);
  return onPlane ? sqrt(length(cross(b - a, c - a))) : 0.0;
}

// The caustic store's irradiance at x: the first environment map whose texel in x's
// direction shows the receiver at x (ImpostorDepositCaustic stored each map alike).
bool StoreIrradiance(vec3 x, float width, out vec3 irradiance)
{
  irradiance = vec3(0.0);
  for (int map = IMPOSTOR_REFRACTOR_ENVIRONMENT; map <= IMPOSTOR_REFLECTOR_ENVIRONMENT; map += 2)
  {
    ivec3 texel;
    if (ImpostorReceiverTexel(map, x, texel))
    {
      irradiance = max(ImpostorCausticIrradiance(texel, width), vec3(0.0));
      return true;
    }
  }
  return false;
}
#endif

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position = texelFetch(gPosition, pixel, 0);
  vec4 normalRole = texelFetch(gNormal, pixel, 0);
  if (position.w < 0.0 || int(normalRole.w + 0.5) != ROLE_RECEIVER)
  {
    discard;
  }
  vec3 x = position.xyz;
  vec3 n = normalize(normalRole.xyz);
  // Light lands on the side of a receiver it arrives from: the side the map's view
  // sees, and for the caustic store the side the normal points to (its deposit's
  // test). A camera that sees the other side (outside a box, under a floor) sees
  // none of it: the outside of the bunny box's walls showed their inside's caustic.
  float cameraSide = dot(ViewAway(cameraView, x), n);
#ifdef CAUSTICS_STORE
  if (cameraSide > 0.0)
  {
    discard;
  }
#else
  if (cameraSide * dot(ViewAway(mapViews[0], x), n) < 0.0)
  {
    discard;
  }
#endif
  if (hasFront && FrontSees(x, n))
  {
    discard; // the front map's pixel
  }
#ifdef CAUSTICS_STORE
  bool mapSees;
  SampleLevel(0, x, n, mapSees); // as this map's own final render tests it
  vec3 stored;
  if (mapSees || !StoreIrradiance(x, FootprintWidth(pixel, x, n), stored))
  {
    discard;
  }
  outIrradiance = vec4(stored, 0.0);
  return;
#endif
  bool seen;
  vec4 total = SampleLevel(0, x, n, seen);
  if (!seen)
  {
    discard; // the caustic map's view does not see this point
  }
  for (int i = 1; i < 4; ++i)
  {
    if (i < levels)
    {
      bool coarseSeen;
      total += SampleLevel(i, x, n, coarseSeen);
    }
  }
  outIrradiance = total;
}
