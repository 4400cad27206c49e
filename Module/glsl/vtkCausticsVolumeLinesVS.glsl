// Light-ray blending (003 §5.2, vtkCausticsVolumeLines step 2b): piece k of segment s
// is line gl_VertexID / 2 = s x pieces + k, drawn between its two vertices with the
// optical depth along the photon that the re-sampling stored at them.
CAUSTICS_VOLUME_SEGMENTS(readonly);
CAUSTICS_VOLUME_DEPTHS(readonly);

uniform mat4 worldToClip;
uniform vec2 viewport;
uniform int pieces;

flat out int segmentIndex;
flat out vec4 piece;       // t0, t1 (m), 1 / w0, 1 / w1
flat out vec2 pieceDepths; // optical depth along the photon at t0 and t1
flat out float majorPixels;
noperspective out float lineParameter;

void main()
{
  int line = gl_VertexID / 2;
  int end = gl_VertexID % 2;
  int index = line / pieces;
  int k = line - index * pieces;
  segmentIndex = index;
  lineParameter = float(end);
  CausticsVolumeSegment s = volumeSegments[index];
  if (!(s.direction.w > s.origin.w))
  {
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
    piece = vec4(0.0);
    pieceDepths = vec2(0.0);
    majorPixels = 0.0;
    return;
  }
  vec2 t = CausticsVolumePiece(s, k, pieces);
  int base = index * (pieces + 1) + k;
  pieceDepths = vec2(volumeDepths[base], volumeDepths[base + 1]);
  vec4 c0 = worldToClip * vec4(s.origin.xyz + t.x * s.direction.xyz, 1.0);
  vec4 c1 = worldToClip * vec4(s.origin.xyz + t.y * s.direction.xyz, 1.0);
  vec2 s0 = (c0.xy / c0.w * 0.5 + 0.5) * viewport;
  vec2 s1 = (c1.xy / c1.w * 0.5 + 0.5) * viewport;
  piece = vec4(t.x, t.y, 1.0 / c0.w, 1.0 / c1.w);
  majorPixels = max(abs(s1.x - s0.x), abs(s1.y - s0.y));
  gl_Position = end == 0 ? c0 : c1;
}
