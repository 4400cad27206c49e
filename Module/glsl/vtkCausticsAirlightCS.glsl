// Airlight and volume shadows of one light (vtkCausticsAirlight): the single scattering
// of the light's direct radiance along each camera pixel's ray, eq. 1 of
// 003_653219b45420e98f.txt §4 with L_in the light itself (§3, Fig. 2 A), in W/(m^2 sr).
// The ray runs from the near plane to the first visible surface (a refractor's too, as
// the reference's camera rays: what lies behind glass is seen refracted, in the
// technique's colour), clipped to the medium's box, in `steps` strata of length ds with
// one jittered sample x each (deterministic per pixel and stratum: no banding):
//   L += sigma_s(x) p_HG(theta) E_light(x) T_light(x) V(x) T_cam(stratum) W(ds)
// E_light: the light's irradiance (directional) or intensity / r^2 with the spot cone;
// V: the light's shadow map, every surface blocking (glass too: the light it passes on
// is the volume caustic, as the reference's shadow rays); T_light: closed form, or a
// march of at most `lightSteps` steps through a density grid; T_cam: closed form, the
// camera optical-depth volume, or the march along this ray; W: the stratum's own
// attenuation, integral of exp(-sigma_t rho u) over [0, ds] (ds for a thin medium,
// 1 / (sigma_t rho) for an opaque one, so an opaque medium stays finite).
// The first light stores, later lights (and a technique's volume caustic) add.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D volume;
uniform int accumulate; // 1: add to what `volume` holds
uniform ivec2 size;
uniform mat4 clipToWorld; // the camera's
uniform sampler2D gPosition; // camera G-buffer of opaque surfaces: world position, w < 0: none
uniform sampler2D gRefractivePosition; // the same of the refractors

uniform sampler2D shadowPosition; // the light's shadow map (positions, w < 0: none)
uniform sampler2D shadowNormal;   // its roles
uniform mat4 lightWorldToClip;
uniform int lightType; // 0 directional, 1 point, 2 spot
uniform vec3 lightPosition; // point/spot: the light; directional: its view's eye
uniform vec3 lightDirection;
uniform vec3 radiometric; // W/m^2 (directional) or W/sr
uniform float cosOuter;
uniform float cosInner;
uniform float texelWorldSize; // a shadow texel at unit distance (perspective) or absolute

uniform vec3 sigmaS;      // scattering, 1/m (per unit density with a grid)
uniform float anisotropy; // Henyey-Greenstein g
uniform int steps;
uniform int lightSteps;

// A well-mixed 32-bit hash (PCG's output permutation) to [0, 1).
float Jitter(ivec2 pixel, int k)
{
  uint state = uint(pixel.x) * 747796405u + uint(pixel.y) * 2891336453u + uint(k) * 277803737u;
  state = state * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  word = (word >> 22u) ^ word;
  return float(word >> 8u) * (1.0 / 16777216.0);
}

// What one unit of scattering coefficient at x sends towards the camera (along -v):
// E_light T_light V p_HG, W/(m^2 sr) per 1/m.
vec3 InScattered(vec3 x, vec3 v)
{
  vec3 toLight;
  vec3 incident = radiometric;
  if (lightType == 0)
  {
    toLight = -lightDirection;
  }
  else
  {
    vec3 d = lightPosition - x;
    float distance2 = dot(d, d);
    if (!(distance2 > 1e-20))
    {
      return vec3(0.0);
    }
    toLight = d * inversesqrt(distance2);
    float spot =
      lightType == 2 ? CausticsSpotFactor(dot(-toLight, lightDirection), cosOuter, cosInner) : 1.0;
    incident *= spot / distance2;
  }
  if (!any(greaterThan(incident, vec3(0.0))))
  {
    return vec3(0.0);
  }
  // Volume shadows: a point has no surface to tilt, so two texels and float noise.
  // Where the medium fills the refractors, a point behind a refractor's surface is in
  // it (under the water) and lit only through it, the volume caustic: float noise only.
  float distance = CausticsLightDistance(x, lightType, lightPosition, lightDirection);
  float texel = lightType == 0 ? texelWorldSize : texelWorldSize * distance;
  float noise = 1e-5 * abs(distance);
  float bias = 2.0 * texel + noise;
  float specular;
  float visibility = CausticsShadowVisibility(shadowPosition, shadowNormal,
    lightWorldToClip * vec4(x, 1.0), distance, bias,
    causticsMediumFillsRefractors != 0 ? noise : bias, lightType, lightPosition,
    lightDirection, x, vec3(0.0), specular);
  if (!(visibility > 0.0))
  {
    return vec3(0.0);
  }
  vec3 transmitted = lightType == 0
    ? CausticsMediumTransmittanceSteps(x, toLight, 0.0, 3.0e38, lightSteps)
    : CausticsMediumTransmittanceSteps(x, lightPosition - x, 0.0, 1.0, lightSteps);
  // Light travels along -toLight and leaves towards the camera along -v.
  float phase = CausticsHenyeyGreenstein(dot(toLight, v), anisotropy);
  return incident * transmitted * (visibility * phase);
}

// Integral of exp(-sigma u) over u in [0, ds], per channel, stable for sigma ds -> 0.
vec3 StratumWeight(vec3 sigma, float ds)
{
  vec3 x = sigma * ds;
  vec3 series = ds * (1.0 - 0.5 * x);
  vec3 exact = ds * (1.0 - exp(-x)) / max(x, vec3(1e-30));
  return mix(exact, series, lessThan(x, vec3(1e-4)));
}

vec3 Airlight(ivec2 pixel)
{
  vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(size) - 1.0;
  vec4 nearPoint = clipToWorld * vec4(ndc, -1.0, 1.0);
  vec4 farPoint = clipToWorld * vec4(ndc, 1.0, 1.0);
  vec3 o = nearPoint.xyz / nearPoint.w;
  vec3 v = farPoint.xyz / farPoint.w - o;
  float far = length(v);
  v /= far;
  vec4 surface = texelFetch(gPosition, pixel, 0);
  vec4 glass = texelFetch(gRefractivePosition, pixel, 0);
  float t0 = 0.0;
  float t1 = surface.w >= 0.0 ? length(surface.xyz - o) : far;
  t1 = glass.w >= 0.0 ? min(t1, length(glass.xyz - o)) : t1;
  if (causticsMediumOn == 0 || !(t1 > 0.0) ||
    !CausticsClipToBox(o, v, causticsMediumLow, causticsMediumHigh, t0, t1))
  {
    return vec3(0.0);
  }
  float ds = (t1 - t0) / float(steps);
  vec3 radiance = vec3(0.0);
#if defined(CAUSTICS_MEDIUM_GRID) && !defined(CAUSTICS_CAMERA_OPTICAL_DEPTH)
  float depth = 0.0; // density x m from t0 to the stratum's start, marched along the ray
#endif
  for (int k = 0; k < steps; ++k)
  {
    float start = t0 + float(k) * ds;
    vec3 x = o + (start + Jitter(pixel, k) * ds) * v;
#ifdef CAUSTICS_MEDIUM_GRID
    float density = CausticsMediumDensity(x);
#ifdef CAUSTICS_CAMERA_OPTICAL_DEPTH
    vec3 toCamera = CausticsMediumTransmittanceToCamera(o + start * v, o);
#else
    vec3 toCamera = CausticsTransmittance(causticsSigmaT, depth);
    depth += CausticsMediumOpticalDepth(o, v, start, start + ds);
#endif
#else
    float density = 1.0;
    vec3 toCamera = CausticsTransmittance(causticsSigmaT, start - t0);
#endif
    if (!(density > 0.0))
    {
      continue; // nothing scatters here: no shadow test, no march to the light
    }
    radiance += sigmaS * density * toCamera * StratumWeight(causticsSigmaT * density, ds) *
      InScattered(x, v);
  }
  return radiance;
}

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size)))
  {
    return;
  }
  vec3 radiance = Airlight(pixel);
  // Bad input (NaN geometry, absurd coefficients) must not reach the image.
  if (any(isnan(radiance)) || any(isinf(radiance)))
  {
    radiance = vec3(0.0);
  }
  if (accumulate != 0)
  {
    radiance += imageLoad(volume, pixel).rgb;
  }
  imageStore(volume, pixel, vec4(radiance, 1.0));
}
