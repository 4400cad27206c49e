// In-scattered radiance of one fragment of a photon segment (003 Eq. 3 with
// physical units). The fragment stands for the length dl of the segment that projects
// to one step along its line's major axis; single scattering towards the camera gives
// the intensity sigma_s(x) p(theta) flux T_light dl (W/sr), and the camera receives it
// through T_camera as radiance over the pixel's footprint A (m^2, perpendicular to
// the view): L = sigma_s p flux T_light T_camera dl / A, W/(m^2 sr). T_light comes
// from the optical depth the re-sampling integrated once per segment, interpolated
// within the fragment's piece; T_camera from the camera optical-depth volume (one
// fetch) or, in a homogeneous medium, the closed form. When the medium fills the
// refractors, a piece inside an absorbing refractor also loses that refractor's own
// Beer-Lambert share from the segment's origin (its entry), and so does the camera's
// side when the eye is in that refractor (eyeMaterial). Summed over the image this
// conserves the scattered power; the Gaussian of Finish() spreads it.
flat in int segmentIndex;
flat in vec4 segment;
flat in float majorPixels;
noperspective in float lineParameter;

CAUSTICS_VOLUME_SEGMENTS(readonly);
CAUSTICS_VOLUME_DEPTHS(readonly);
uniform int pieces;

uniform sampler2D opaqueDepth;     // window depth of receivers and reflectors
uniform sampler2D refractiveDepth; // window depth of refractors
uniform mat4 clipToWorld;
uniform vec2 viewport;
uniform vec4 viewOrigin; // camera position (w = 1) or view direction (w = 0)
uniform vec3 sigmaS;     // 1/m (per unit density with CAUSTICS_MEDIUM_GRID)
uniform float anisotropy;
uniform int eyeMaterial; // the closed refractor the eye is in (-1: none)

layout(location = 0) out vec4 outRadiance;

vec3 Unproject(vec2 window, float ndcZ)
{
  vec4 p = clipToWorld * vec4(window / viewport * 2.0 - 1.0, ndcZ, 1.0);
  return p.xyz / p.w;
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  // Hidden behind the visible surface (§5.3).
  float sceneDepth =
    min(texelFetch(opaqueDepth, pixel, 0).r, texelFetch(refractiveDepth, pixel, 0).r);
  if (gl_FragCoord.z > sceneDepth || !(majorPixels > 0.0))
  {
    discard;
  }
  CausticsVolumeSegment s = volumeSegments[segmentIndex];
  vec3 o = s.origin.xyz;
  vec3 d = s.direction.xyz;
  // Perspective-correct ray parameter and its rate along the screen line.
  float u = clamp(lineParameter, 0.0, 1.0);
  float a = (1.0 - u) * segment.z;
  float b = u * segment.w;
  float t = (a * segment.x + b * segment.y) / (a + b);
  float dtdu = (segment.y - segment.x) * segment.z * segment.w / ((a + b) * (a + b));
  float dl = abs(dtdu) / max(majorPixels, 1.0);
  vec3 x = o + t * d;
#if defined(CAUSTICS_VOLUME_LINES_MARCH) && defined(CAUSTICS_MEDIUM_GRID)
  // Comparison mode (subSegments 0): the density marched from the origin per fragment.
  float m0 = 0.0;
  float m1 = t;
  float along = CausticsClipToBox(o, d, causticsMediumLow, causticsMediumHigh, m0, m1)
    ? CausticsMediumOpticalDepth(o, d, m0, m1)
    : 0.0;
#else
  // The optical depth along the photon, linear within the fragment's piece: the pieces
  // of the record's whole drawn part (CausticsVolumePiece, as the re-sampling stored
  // them), not of the part in front of the near plane that `segment` holds.
  float h = (s.direction.w - s.origin.w) / float(pieces);
  float f = clamp((t - s.origin.w) / max(h, 1e-30), 0.0, float(pieces));
  int k = min(int(f), pieces - 1);
  int base = segmentIndex * (pieces + 1) + k;
  float along = mix(volumeDepths[base], volumeDepths[base + 1], f - float(k));
#endif

  vec3 toCamera = viewOrigin.w > 0.0 ? viewOrigin.xyz - x : -viewOrigin.xyz * 1.0e6;
  float distanceToCamera = length(toCamera);
  vec3 v = toCamera / distanceToCamera;
  // To the camera from the near plane, as the composite, the airlight and the reference's
  // camera rays take it (the march's start when the volume does not serve).
  vec3 transmittance = CausticsTransmittance(causticsSigmaT, along) *
    CausticsMediumTransmittanceToCamera(x, Unproject(gl_FragCoord.xy, -1.0));
  int absorber = int(s.flux.w + 0.5) - 1;
  if (absorber >= 0)
  {
    transmittance *= CausticsTransmittance(causticsMaterials[absorber].attenuation.rgb, t);
  }
  if (eyeMaterial >= 0)
  {
    // From the eye, as the camera view of glass takes it (the medium above is taken
    // from the near plane, as VTK's view and the reference's camera rays begin there).
    transmittance *= CausticsTransmittance(
      causticsMaterials[eyeMaterial].attenuation.rgb, distanceToCamera);
  }
#ifdef CAUSTICS_MEDIUM_GRID
  vec3 scattering = sigmaS * CausticsMediumDensity(x);
#else
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
  float phase = CausticsHenyeyGreenstein(dot(d, v), anisotropy);
  outRadiance = vec4(scattering * phase * s.flux.rgb * transmittance * dl / area, 1.0);
}
