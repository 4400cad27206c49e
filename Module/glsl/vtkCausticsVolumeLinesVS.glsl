// Light-ray blending (003 §5.2, vtkCausticsVolumeLines step 2b): segment s is line
// gl_VertexID / 2, drawn whole from t0 to t1 (pieces shorter than a pixel would be lost
// to the rasterization rules); its fragments find their piece and the optical depth
// the re-sampling stored at its vertices.
CAUSTICS_VOLUME_SEGMENTS(readonly);

uniform mat4 worldToClip;
uniform vec2 viewport;

flat out int segmentIndex;
flat out vec4 segment; // t0, t1 (m), 1 / w0, 1 / w1
flat out float majorPixels;
noperspective out float lineParameter;

void main()
{
  int index = gl_VertexID / 2;
  int end = gl_VertexID % 2;
  segmentIndex = index;
  lineParameter = float(end);
  CausticsVolumeSegment s = volumeSegments[index];
  if (!(s.direction.w > s.origin.w))
  {
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
    segment = vec4(0.0);
    majorPixels = 0.0;
    return;
  }
  // The part in front of the near plane (z + w >= 0 in clip space, affine in t).
  vec4 cA = worldToClip * vec4(s.origin.xyz, 1.0);
  vec4 cD = worldToClip * vec4(s.direction.xyz, 0.0);
  float t0 = s.origin.w, t1 = s.direction.w;
  float f0 = cA.z + cA.w + t0 * (cD.z + cD.w), f1 = cA.z + cA.w + t1 * (cD.z + cD.w);
  if (f0 < 0.0 && f1 < 0.0)
  {
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
    segment = vec4(0.0);
    majorPixels = 0.0;
    return;
  }
  if (f0 < 0.0 || f1 < 0.0)
  {
    float tc = -(cA.z + cA.w) / (cD.z + cD.w);
    t0 = f0 < 0.0 ? tc : t0;
    t1 = f1 < 0.0 ? tc : t1;
  }
  vec4 c0 = cA + t0 * cD;
  vec4 c1 = cA + t1 * cD;
  vec2 s0 = (c0.xy / c0.w * 0.5 + 0.5) * viewport;
  vec2 s1 = (c1.xy / c1.w * 0.5 + 0.5) * viewport;
  segment = vec4(t0, t1, 1.0 / c0.w, 1.0 / c1.w);
  majorPixels = max(abs(s1.x - s0.x), abs(s1.y - s0.y));
  gl_Position = end == 0 ? c0 : c1;
}
