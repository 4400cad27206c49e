// SVGF step 3, variance: of the luminance, from the temporal moments. A history
// shorter than spatialFrames has too few frames for that:
// - where the technique wrote its photons' own variance (photonVariance: the squared
//   difference of its two halves' estimates; CausticsDeposit), that variance averaged over
//   the history, as it is (it comes from this frame's photons, not from a few frames,
//   so SVGF's 4 / frames does not apply: with the sum of squared deposits used before,
//   the pool's first denoised frame was 0.198 from the truth with it, 0.133 without;
//   with the halves' difference it is 0.078, the raw frame's 0.077;
//   TestCascadedPhotonPass);
// - otherwise SVGF's estimate, from the moments of the 7x7 neighbours on the same
//   surface (depth and normal weights), raised by 4 / frames. The neighbours' spread
//   counts a fine caustic's own structure as noise, which the a-trous filter then
//   blurs (0.233 on that frame).
// Stored in the integrated colour's alpha, which the a-trous filter carries.
layout(rgba32f, binding = 2) uniform readonly image2D historyMoments; // m1, m2, frames, v
layout(rgba32f, binding = 3) uniform image2D integratedColor;         // rgb; a: variance
uniform float spatialFrames;
uniform int photonVariance; // 1: the input's alpha held its photons' variance

void main()
{
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!SVGFInside(p) || !SVGFReceiver(p))
  {
    return;
  }
  vec4 m = imageLoad(historyMoments, p);
  float variance = max(m.g - m.r * m.r, 0.0);
  if (m.b < spatialFrames && photonVariance != 0)
  {
    variance = m.a;
  }
  else if (m.b < spatialFrames)
  {
    vec3 xp = imageLoad(gPosition, p).xyz;
    vec3 np = normalize(imageLoad(gNormal, p).xyz);
    vec2 sum = vec2(0.0);
    float total = 0.0;
    for (int dy = -3; dy <= 3; ++dy)
    {
      for (int dx = -3; dx <= 3; ++dx)
      {
        ivec2 q = p + ivec2(dx, dy);
        if (!SVGFInside(q) || !SVGFReceiver(q))
        {
          continue;
        }
        float w = dx == 0 && dy == 0 ? 1.0 :
          SVGFGeometryWeight(xp, np, imageLoad(gPosition, q).xyz,
            normalize(imageLoad(gNormal, q).xyz), length(vec2(dx, dy)));
        sum += w * imageLoad(historyMoments, q).rg;
        total += w;
      }
    }
    sum /= total;
    variance = max(sum.y - sum.x * sum.x, 0.0) * 4.0 / max(m.b, 1.0);
  }
  vec4 c = imageLoad(integratedColor, p);
  imageStore(integratedColor, p, vec4(c.rgb, variance));
}
