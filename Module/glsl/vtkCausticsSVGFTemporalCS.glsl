// SVGF step 2, temporal accumulation: this frame's irradiance blended into the
// reprojected history with weight max(alpha, 1/(frames + 1)), and the first and
// second moments of its luminance likewise. No history where almost nothing
// reprojected (a camera cut: fewer than minimumFraction of the receivers).
// Light that moves over a still receiver (the caustic of a moving ball) is no
// disocclusion of a surface: a history that differs from this frame's 5x5
// neighbourhood mean by more than rejectSigmas standard errors of the difference of
// the two means (sigma sqrt(1/N + 1/n): N pixels this frame, a history of n frames,
// sigma the neighbourhood's spread) is dropped, as a disoccluded one is. (Against
// mean +- 2 sigma, the spread of one pixel, a history of zero where sparse photons had
// just arrived passed and faded in over some ten frames: the lag of a moving ball.)
// Only a history older than the last change of what lights the receivers (more frames
// than framesSinceLightChanged) can hold light that is gone, so only such a history is
// tested: one that restarted after the change is left to grow, and a still light
// field is not tested at all. On sparse photons a 5x5 neighbourhood where few photons
// landed this frame has a small spread, so testing every frame dropped good history
// in dim frames more often than in bright ones and took 4.5 % off a still caustic's
// flux (TestCascadedPhotonPass). A
// non-finite input texel is rejected (the history stays as it was, or zero without
// one); a negative one counts as zero. The input's alpha, where the reconstruction
// wrote one (CausticsDeposit: the difference of the estimates of the frame's two
// halves of photons), gives this frame's photon variance (CausticsPhotonVariance),
// averaged like the moments into the moments' fourth channel.
layout(rgba32f, binding = 2) uniform readonly image2D irradiance; // W/m^2, this frame
layout(rgba32f, binding = 3) uniform readonly image2D reprojectedColor;
layout(rgba32f, binding = 4) uniform readonly image2D reprojectedMoments;
layout(rgba32f, binding = 5) uniform writeonly image2D integratedColor; // rgb, a: 0
layout(rgba32f, binding = 6) uniform writeonly image2D historyMoments;  // m1, m2, frames, v
layout(r32ui, binding = 7) uniform readonly uimage2D counts;
uniform float temporalAlpha;
uniform float momentsAlpha;
uniform float maximumFrames;
uniform float rejectSigmas;
uniform float framesSinceLightChanged; // 0: it changed in this frame
uniform float minimumFraction;

// This frame's irradiance at q as the filter takes it: finite, not negative; alpha
// its photon variance.
vec4 SampleWithVariance(ivec2 q, out bool finite)
{
  vec4 c = imageLoad(irradiance, q);
  finite = SVGFFinite(c);
  return finite ? vec4(max(c.rgb, vec3(0.0)), CausticsPhotonVariance(c.a)) : vec4(0.0);
}

vec3 Sample(ivec2 q, out bool finite)
{
  return SampleWithVariance(q, finite).rgb;
}

// Whether the history (a mean of `frames` frames) agrees with this frame's neighbourhood
// mean (finite receiver texels) within rejectSigmas standard errors, in every channel;
// an exponential mean of weight alpha holds (2 - alpha) / alpha frames at most.
bool InNeighbourhood(ivec2 p, vec3 history, float frames)
{
  vec3 sum = vec3(0.0), sum2 = vec3(0.0);
  float count = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
  {
    for (int dx = -2; dx <= 2; ++dx)
    {
      ivec2 q = p + ivec2(dx, dy);
      if (!SVGFInside(q) || !SVGFReceiver(q))
      {
        continue;
      }
      bool finite;
      vec3 c = Sample(q, finite);
      if (finite)
      {
        sum += c;
        sum2 += c * c;
        count += 1.0;
      }
    }
  }
  vec3 mean = sum / max(count, 1.0);
  vec3 deviation = sqrt(max(sum2 / max(count, 1.0) - mean * mean, vec3(0.0)));
  float historyFrames = min(frames, (2.0 - temporalAlpha) / temporalAlpha);
  float spread = sqrt(1.0 / max(count, 1.0) + 1.0 / max(historyFrames, 1.0));
  return all(lessThanEqual(abs(history - mean), rejectSigmas * spread * deviation));
}

void main()
{
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!SVGFInside(p))
  {
    return;
  }
  if (!SVGFReceiver(p))
  {
    imageStore(integratedColor, p, vec4(0.0));
    imageStore(historyMoments, p, vec4(0.0));
    return;
  }
  float receivers = float(imageLoad(counts, ivec2(0, 0)).x);
  float reprojected = float(imageLoad(counts, ivec2(1, 0)).x);
  bool cut = reprojected < minimumFraction * receivers;
  vec4 history = cut ? vec4(0.0) : imageLoad(reprojectedColor, p);
  vec4 historyM = cut ? vec4(0.0) : imageLoad(reprojectedMoments, p);
  float frames = min(historyM.b, maximumFrames);
  bool finite;
  vec4 deposit = SampleWithVariance(p, finite);
  vec3 c = deposit.rgb;
  if (!finite && frames > 0.0)
  {
    imageStore(integratedColor, p, vec4(history.rgb, 0.0)); // nothing new here
    imageStore(historyMoments, p, vec4(historyM.rg, frames, historyM.a));
    return;
  }
  if (frames > framesSinceLightChanged && rejectSigmas > 0.0 &&
    !InNeighbourhood(p, history.rgb, frames))
  {
    frames = 0.0; // light moved here or away: a disocclusion of the light
  }
  float alpha = max(temporalAlpha, 1.0 / (frames + 1.0));
  float alphaM = max(momentsAlpha, 1.0 / (frames + 1.0));
  float l = SVGFLuminance(c);
  vec3 moments = mix(historyM.rga, vec3(l, l * l, deposit.a), alphaM);
  float kept = finite ? min(frames + 1.0, maximumFrames) : 0.0;
  imageStore(integratedColor, p, vec4(mix(history.rgb, c, alpha), 0.0));
  imageStore(historyMoments, p, vec4(moments.xy, kept, moments.z));
}
