// Adds the photon kernels (vtkCausticsPhotonSplatter, KeepFluxAtReceiverEnds) to the
// caller's target, each pixel divided by the share of its own kernel disc that lies on
// its receiver. A kernel estimate at x reads the photons within r of x: where the
// receiver ends inside that disc (a floor meeting a wall, a wall's top, a table's edge)
// no photon lands on the rest of it, and the estimate reads only that share of the
// light. The reference renderer divides its estimate by the same share
// (docs/reference.md, KernelCoverage), so the two agree up to a receiver's end.
//
// What a single view can tell about a point s of the disc (on x's tangent plane):
// - the view shows x's plane there: receiver;
// - it shows nothing, or a surface beyond s: the plane ended before s;
// - it shows a receiver in front of s that stands on the plane near s (its height
//   above the plane no more than a wall rising from the plane between x and s would
//   show there): the surface the plane ends against (a wall's foot, a box standing on
//   the floor);
// - glass or a mirror in front of s, or a receiver well above the plane, is an
//   occluder: the plane is taken to go on behind it, as it does under a glass bunny or
//   behind a mirror ring's wall, since the photons that land there still splat onto
//   the pixels the view shows;
// - off the view: taken to go on (the splats there are not seen either) inside the
//   receivers' bounds, where those are known, and to have ended outside them (a wall
//   whose top is just above the image's top border).
uniform sampler2D kernelIrradiance; // the kernels alone: rgb W/m^2, a the half-set difference
uniform sampler2D kernelRadii;      // x: sum of w, y: sum of w r (w: a kernel's deposit luminance)
uniform sampler2D targetPosition;   // xyz world, w = material (-1: no surface)
uniform sampler2D targetNormal;     // xyz normal as modelled, w = role
uniform mat4 worldToClip;
uniform mat4 clipToWorld;
uniform vec2 viewport;
uniform float planeTolerance; // the splats' tests (vtkCausticsPhotonSplatFS)
uniform float normalTolerance;
uniform bool hasReceiverBounds; // the receivers' bounds (vtkCausticsPhotonSplatter)
uniform vec3 receiverMin;
uniform vec3 receiverMax;

layout(location = 0) out vec4 outIrradiance;

// Whether disc point s, off the view, is taken to lie on the receiver: inside the
// receivers' bounds (widened by a hundredth of the kernel's radius r, for the bounds'
// rounding), or anywhere where they are not known.
bool OffViewOnReceiver(vec3 s, float r)
{
  return !hasReceiverBounds ||
    (all(greaterThanEqual(s, receiverMin - 0.01 * r)) &&
      all(lessThanEqual(s, receiverMax + 0.01 * r)));
}

// Whether pixel `pixel` of the view, which disc point s (of the receiver (x, n),
// kernel radius r; at depth sDepth, NDC z) projects into or next to, shows that the
// receiver goes on at s. `rise`: how high above the plane a receiver rising from it
// within r before s shows at s's pixel.
bool PixelShowsReceiver(ivec2 pixel, vec3 s, float sDepth, vec3 x, vec3 n, float r, float rise)
{
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(viewport))))
  {
    return OffViewOnReceiver(s, r);
  }
  vec4 p = texelFetch(targetPosition, pixel, 0);
  if (p.w < 0.0)
  {
    return false; // the background where the plane would be
  }
  vec4 pn = texelFetch(targetNormal, pixel, 0);
  float height = dot(p.xyz - x, n);
  bool receiver = int(pn.w + 0.5) == ROLE_RECEIVER;
  if (receiver && dot(pn.xyz, n) >= normalTolerance && abs(height) <= planeTolerance * r)
  {
    return true;
  }
  vec4 q = worldToClip * vec4(p.xyz, 1.0);
  if (q.z / q.w >= sDepth)
  {
    return false; // seen past s: the plane ended before it
  }
  // In front of s. Glass and mirrors standing on the plane do not end it: light lands
  // beneath and behind them (under a glass bunny, on both sides of a mirror ring's
  // wall), and the kernels of those photons reach the pixels in front. A receiver
  // standing on it does (a wall's foot, a box on the floor).
  return !receiver || !(height >= -planeTolerance * r && height <= rise + planeTolerance * r);
}

// How much of the disc point s of the receiver (x, n), kernel radius r, lies on the
// receiver, 0 to 1: the view's pixel under s alone, or with `bilinear`, the four pixel
// centres around s weighed as a bilinear tap (a pixel tells about its centre only, and
// a probe next to an edge is on the receiver or not by where the edge passes between
// centres).
float OnReceiver(vec3 x, vec3 n, float r, vec3 s, bool bilinear)
{
  vec4 clip = worldToClip * vec4(s, 1.0);
  vec3 ndc = clip.xyz / max(clip.w, 1e-30);
  if (!(clip.w > 0.0) || any(lessThan(ndc.xy, vec2(-1.0))) ||
    any(greaterThanEqual(ndc.xy, vec2(1.0))))
  {
    return OffViewOnReceiver(s, r) ? 1.0 : 0.0;
  }
  // A receiver rising from the plane at distance delta < r before s shows at s's pixel
  // at height delta tan(b), b the angle between the view's ray and the plane.
  vec4 near = clipToWorld * vec4(ndc.xy, -1.0, 1.0);
  vec4 far = clipToWorld * vec4(ndc.xy, 1.0, 1.0);
  vec3 ray = normalize(far.xyz / far.w - near.xyz / near.w);
  float sine = min(abs(dot(ray, n)), 0.999);
  float rise = r * sine / sqrt(1.0 - sine * sine);
  vec2 pixel = (ndc.xy * 0.5 + 0.5) * viewport;
  if (!bilinear)
  {
    return PixelShowsReceiver(ivec2(pixel), s, ndc.z, x, n, r, rise) ? 1.0 : 0.0;
  }
  vec2 f = pixel - 0.5;
  ivec2 base = ivec2(floor(f));
  vec2 w = f - floor(f);
  float on = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    ivec2 corner = ivec2(k & 1, k >> 1);
    vec2 weights = mix(1.0 - w, w, vec2(corner));
    if (PixelShowsReceiver(base + corner, s, ndc.z, x, n, r, rise))
    {
      on += weights.x * weights.y;
    }
  }
  return on;
}

// The share of the Epanechnikov disc of radius r around x on the receiver (x, n), as
// the reference renderer takes it (KernelCoverage): one when the eight rim points at
// 0.85 r are all on it (each by the pixel under it), else the kernel-weighted share of
// 36 points on three rings (each by a bilinear tap of the four pixel centres around
// it: a pixel tells about its centre only, and the receiver's edge passes somewhere
// between two centres), at least a quarter (a pixel on a sliver of receiver must not
// become a spike).
float ReceiverShare(vec3 x, vec3 n, float r)
{
  vec3 e1, e2;
  CausticsTangents(n, e1, e2);
  bool whole = true;
  for (int k = 0; k < 8 && whole; ++k)
  {
    float angle = float(k) * (CAUSTICS_PI / 4.0);
    whole = OnReceiver(x, n, r, x + 0.85 * r * (cos(angle) * e1 + sin(angle) * e2), false) > 0.5;
  }
  if (whole)
  {
    return 1.0;
  }
  float on = 0.0;
  float all = 0.0;
  for (int ring = 0; ring < 3; ++ring)
  {
    float rho = (float(ring) + 0.5) / 3.0;
    float weight = (1.0 - rho * rho) * rho; // the kernel times the ring's length
    for (int k = 0; k < 12; ++k)
    {
      float angle = (float(k) + 0.5 * float(ring)) * (CAUSTICS_PI / 6.0);
      vec3 s = x + rho * r * (cos(angle) * e1 + sin(angle) * e2);
      all += weight;
      on += weight * OnReceiver(x, n, r, s, true);
    }
  }
  return max(on / all, 0.25);
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 irradiance = texelFetch(kernelIrradiance, pixel, 0);
  if (all(equal(irradiance, vec4(0.0))))
  {
    discard;
  }
  vec2 radii = texelFetch(kernelRadii, pixel, 0).xy;
  vec4 x = texelFetch(targetPosition, pixel, 0);
  vec3 n = texelFetch(targetNormal, pixel, 0).xyz;
  float r = radii.x > 0.0 ? radii.y / radii.x : 0.0;
  float share = x.w >= 0.0 && r > 0.0 && !any(isnan(n)) && !any(isinf(n)) && dot(n, n) > 0.0
    ? ReceiverShare(x.xyz, normalize(n), r)
    : 1.0;
  outIrradiance = irradiance / share;
}
