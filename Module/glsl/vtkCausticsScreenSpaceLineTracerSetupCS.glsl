// Line setup (000_54cf099eeccf42d9.txt §2.1): each ray is clipped to the scene's
// bounds and to the view frustum, projected to the screen, and given the number of
// fragments n_f its line covers (at least the minimum line length, so that rays
// almost parallel to the view direction are still sampled finely).
layout(local_size_x = 64) in;

SSP_COUNTER(readonly);
SSP_RAYS(readonly);
SSP_LINES(writeonly);

uniform mat4 worldToClip;
uniform vec2 viewport;
uniform vec3 boundsMin;
uniform vec3 boundsMax;
uniform float tolerance;     // m
uniform float pixelScale;    // world size of one pixel at clip w = 1, m
uniform float minimumLength; // fragments
uniform float maximumLength; // fragments (the row width)
uniform float guardPixels;   // own-surface guard, in pixels at the origin
uniform int capacity;

vec2 ToWindow(vec4 clip)
{
  return (clip.xy / clip.w * 0.5 + 0.5) * viewport;
}

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(rayCount, uint(capacity)))
  {
    return;
  }
  SspRay ray = rays[i];
  SspLine line;
  line.start = vec4(0.0);
  line.end = vec4(0.0);
  line.info = vec4(0.0);
  vec3 o = ray.origin.xyz;
  vec3 d = ray.direction.xyz;
  float t0 = 0.0;
  float t1 = 3.0e38;
  vec3 slack = vec3(tolerance);
  if (ray.origin.w > 0.0 && dot(d, d) > 0.5 &&
    CausticsClipToBox(o, d, boundsMin - slack, boundsMax + slack, t0, t1) &&
    SspClipToFrustum(worldToClip, o, d, t0, t1))
  {
    vec4 c0 = worldToClip * vec4(o + t0 * d, 1.0);
    vec4 c1 = worldToClip * vec4(o + t1 * d, 1.0);
    if (c0.w > 0.0 && c1.w > 0.0)
    {
      vec2 s0 = ToWindow(c0);
      vec2 s1 = ToWindow(c1);
      vec2 span = abs(s1 - s0);
      float n = clamp(max(ceil(max(span.x, span.y)), minimumLength), 1.0, maximumLength);
      float w = abs((worldToClip * vec4(o, 1.0)).w);
      line.start = vec4(s0, 1.0 / c0.w, t0);
      line.end = vec4(s1, 1.0 / c1.w, t1);
      line.info = vec4(n, guardPixels * w * pixelScale, 0.0, 0.0);
    }
  }
  lines[i] = line;
}
