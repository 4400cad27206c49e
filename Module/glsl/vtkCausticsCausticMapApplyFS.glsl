// Final render with a caustic map (001_7c07a484f7a872bb.txt §2 and Eq. 3): the
// light's caustic map is projected onto the visible receivers like a shadow map.
// Every level of the pyramid is sampled bilinearly, each tap counting only if it
// shows the camera pixel's own surface (a receiver whose plane holds the pixel's
// point, with a similar normal): the visibility test. A pixel the map's finest
// level does not see (hidden from the light's view by another receiver) gets no
// caustic light. The levels store irradiance (W/m^2) from energy-normalized
// kernels; Eq. 3's (1/4)^i renormalizes energy counted per texel, whose area is
// 4^i times the finest texel's, so in irradiance it is a plain sum.
uniform sampler2D gPosition; // camera G-buffer: world position, w = material (-1: none)
uniform sampler2D gNormal;   // normal as modelled, w = role
uniform sampler2D irradiance[4];
uniform sampler2D receiverPosition[4];
uniform sampler2D receiverNormal[4];
uniform CausticsView mapViews[4];
uniform int levels;

layout(location = 0) out vec4 outIrradiance;

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
      vec4 s = texelFetch(receiverPosition[i], texel, 0);
      vec4 sn = texelFetch(receiverNormal[i], texel, 0);
      if (s.w < 0.0 || dot(sn.xyz, n) < 0.8 || abs(dot(x - s.xyz, sn.xyz)) > tolerance)
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
