// In-scattered radiance of one fragment of a photon segment (§3.2, with physical
// units). The fragment stands for the length dl of the segment that projects to
// one step along its major axis; single scattering towards the camera gives the
// intensity sigma_s p(theta) flux(t) dl (W/sr), flux(t) attenuated by
// exp(-sigma_t s) along the segment within the medium, and the camera receives it
// through exp(-sigma_t s') as radiance over the pixel's footprint A (m^2,
// perpendicular to the view): L = sigma_s p flux T T' dl / A, W/(m^2 sr). Summed
// over the image this conserves the scattered power; the Gaussian blur that
// follows spreads it. A heterogeneous medium (CAUSTICS_MEDIUM_GRID) scatters with
// sigma_s times the density at the fragment and marches both transmittances.
flat in int rayIndex;
flat in vec4 segment;
flat in float majorPixels;
noperspective in float lineParameter;

SSP_RAYS(readonly);
SSP_PAYLOADS(readonly);

uniform sampler2D opaqueDepth;     // window depth of receivers and reflectors
uniform sampler2D refractiveDepth; // window depth of refractors
uniform mat4 clipToWorld;
uniform vec2 viewport;
uniform vec4 viewOrigin; // camera position (w = 1) or view direction (w = 0)
uniform vec3 sigmaS;     // 1/m (per unit density with CAUSTICS_MEDIUM_GRID)
uniform vec3 sigmaT;     // 1/m
uniform float anisotropy;
uniform vec3 boundsMin;
uniform vec3 boundsMax;

layout(location = 0) out vec4 outRadiance;

vec3 Unproject(vec2 window, float ndcZ)
{
  vec4 p = clipToWorld * vec4(window / viewport * 2.0 - 1.0, ndcZ, 1.0);
  return p.xyz / p.w;
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  // Hidden behind the visible surface.
  float sceneDepth =
    min(texelFetch(opaqueDepth, pixel, 0).r, texelFetch(refractiveDepth, pixel, 0).r);
  if (gl_FragCoord.z > sceneDepth || !(majorPixels > 0.0))
  {
    discard;
  }
  SspRay ray = rays[rayIndex];
  vec3 o = ray.origin.xyz;
  vec3 d = ray.direction.xyz;
  // Perspective-correct ray parameter and its rate along the screen line.
  float u = clamp(lineParameter, 0.0, 1.0);
  float a = (1.0 - u) * segment.z;
  float b = u * segment.w;
  float t = (a * segment.x + b * segment.y) / (a + b);
  float dtdu = (segment.y - segment.x) * segment.z * segment.w / ((a + b) * (a + b));
  float dl = abs(dtdu) / max(majorPixels, 1.0);
  vec3 x = o + t * d;

  // Extinction along the photon's segment inside the medium, and towards the camera.
#ifdef CAUSTICS_MEDIUM_GRID
  vec3 toCamera = viewOrigin.w > 0.0 ? viewOrigin.xyz - x : -viewOrigin.xyz * 1.0e6;
  float distanceToCamera = length(toCamera);
  vec3 v = toCamera / distanceToCamera;
  vec3 transmittance = CausticsMediumTransmittance(o, d, 0.0, t) *
    CausticsMediumTransmittanceToCamera(x, x + toCamera);
  vec3 scattering = sigmaS * CausticsMediumDensity(x);
#else
  float s0 = 0.0;
  float s1 = t;
  float along = CausticsClipToBox(o, d, boundsMin, boundsMax, s0, s1) ? s1 - s0 : 0.0;
  vec3 toCamera = viewOrigin.w > 0.0 ? viewOrigin.xyz - x : -viewOrigin.xyz * 1.0e6;
  float distanceToCamera = length(toCamera);
  vec3 v = toCamera / distanceToCamera;
  float c0 = 0.0;
  float c1 = distanceToCamera;
  float towards = CausticsClipToBox(x, v, boundsMin, boundsMax, c0, c1) ? c1 - c0 : 0.0;
  vec3 transmittance = exp(-sigmaT * (along + towards));
  vec3 scattering = sigmaS;
#endif

  // Footprint of the pixel at x, perpendicular to the view direction.
  float z = gl_FragCoord.z * 2.0 - 1.0;
  vec3 p00 = Unproject(gl_FragCoord.xy, z);
  vec3 p10 = Unproject(gl_FragCoord.xy + vec2(1.0, 0.0), z);
  vec3 p01 = Unproject(gl_FragCoord.xy + vec2(0.0, 1.0), z);
  float area = abs(dot(cross(p10 - p00, p01 - p00), v));
  if (!(area > 0.0))
  {
    discard;
  }
  vec3 flux = payloads[rayIndex].flux.rgb;
  float phase = SspHenyeyGreenstein(dot(d, v), anisotropy);
  outRadiance = vec4(scattering * phase * flux * transmittance * dl / area, 1.0);
}
