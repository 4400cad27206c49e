// God-rays (000_54cf099eeccf42d9.txt §3.2): every photon segment in the medium is
// drawn as a line primitive from where it starts (clipped to the scene's bounds
// and the view) to where it ends (its first hit, or where it leaves).
SSP_RAYS(readonly);
SSP_LINES(readonly);
SSP_HITS(readonly);

uniform mat4 worldToClip;
uniform vec2 viewport;

flat out int rayIndex;
flat out vec4 segment; // t0, t1 (m), 1 / w0, 1 / w1
flat out float majorPixels;
noperspective out float lineParameter;

void main()
{
  int ray = gl_VertexID / 2;
  int end = gl_VertexID % 2;
  rayIndex = ray;
  lineParameter = float(end);
  SspLine line = lines[ray];
  SspRay r = rays[ray];
  float t0 = line.start.w;
  float t1 = line.end.w;
  float hit = hits[ray].position.w;
  if (hit >= 0.0)
  {
    t1 = min(t1, hit);
  }
  // Refractors hold no medium; no line, nothing traced, nothing to draw.
  if (!(line.info.x > 0.0) || r.origin.w > 1.5 || !(t1 > t0))
  {
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
    segment = vec4(0.0);
    majorPixels = 0.0;
    return;
  }
  vec4 c0 = worldToClip * vec4(r.origin.xyz + t0 * r.direction.xyz, 1.0);
  vec4 c1 = worldToClip * vec4(r.origin.xyz + t1 * r.direction.xyz, 1.0);
  vec2 s0 = (c0.xy / c0.w * 0.5 + 0.5) * viewport;
  vec2 s1 = (c1.xy / c1.w * 0.5 + 0.5) * viewport;
  segment = vec4(t0, t1, 1.0 / c0.w, 1.0 / c1.w);
  majorPixels = max(abs(s1.x - s0.x), abs(s1.y - s0.y));
  gl_Position = end == 0 ? c0 : c1;
}
