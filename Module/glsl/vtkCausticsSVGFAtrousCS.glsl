// SVGF step 4, one a-trous wavelet iteration: the 5x5 B3-spline kernel with holes
// of stepSize pixels, over receiver pixels only, each tap weighted by SVGF's
// edge-stopping functions (depth, normal, and luminance against sigmaLuminance x
// the 3x3-blurred standard deviation).
//
// Energy: SVGF normalizes each output pixel's weights (E_p = sum_q w(p,q) E_q / W_p,
// W_p = sum_q w(p,q)), which keeps a constant but not the sum: on sparse,
// right-skewed photon noise the luminance weights pull pixels towards the more
// common dim values, and the cascaded ball lens lost 2.7 % of its flux in it
// (TestCascadedPhotonPass.DISABLED_DenoiserFluxByPart). Here the weights are symmetric (w(p,q) = w(q,p)) and
// balanced (Sinkhorn; Milanfar 2013, "Symmetrizing smoothing filters"): the filter is
// d_p w(p,q) d_q with d such that every row, hence every column, sums to one, so
// that both a constant and the sum of the irradiance over the receivers are kept.
// Two Sinkhorn steps from d = 1: on the ball lens the filter keeps 0.9995 of the flux.
// Four programs, one per stage (SVGF_ATROUS_STAGE), run in this order:
//   deviation: the 3x3-blurred standard deviation of luminance per pixel;
//   normalize: d_p = 1 / sqrt(W_p) (the first Sinkhorn step);
//   balance:   d_p = sqrt(d_p / sum_q w(p,q) d_q) (the second);
//   gather:    E_p = d_p sum_q w(p,q) d_q E_q, the variance with the squared weights.
#define SVGF_ATROUS_DEVIATION 0
#define SVGF_ATROUS_NORMALIZE 1
#define SVGF_ATROUS_BALANCE 2
#define SVGF_ATROUS_GATHER 3

layout(rgba32f, binding = 2) uniform readonly image2D source; // rgb W/m^2, a: variance
layout(r32f, binding = 4) uniform readonly image2D deviation; // blurred std of luminance
layout(r32f, binding = 5) uniform readonly image2D balance;   // d of the last step
#if SVGF_ATROUS_STAGE != SVGF_ATROUS_GATHER
layout(r32f, binding = 3) uniform writeonly image2D destination;
#else
layout(rgba32f, binding = 3) uniform writeonly image2D destination;
#endif
uniform int stepSize;
uniform float sigmaLuminance;

const float kernel[3] = float[](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

// The 3x3 Gaussian of the variance around p, over receivers.
float BlurredVariance(ivec2 p)
{
  const float gauss[2] = float[](1.0 / 4.0, 1.0 / 8.0);
  float sum = 0.0, total = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      ivec2 q = p + ivec2(dx, dy);
      if (SVGFInside(q) && SVGFReceiver(q))
      {
        float w = gauss[abs(dx)] * gauss[abs(dy)];
        sum += w * imageLoad(source, q).a;
        total += w;
      }
    }
  }
  return sum / max(total, 1e-12);
}

// What the weight of a pair needs of one of its pixels.
struct Tap
{
  vec3 x;    // world position, m
  vec3 n;    // normal
  float l;   // luminance, W/m^2
  float s;   // blurred standard deviation of luminance
  vec4 c;    // the source texel
};

Tap LoadTap(ivec2 p)
{
  Tap t;
  t.x = imageLoad(gPosition, p).xyz;
  t.n = normalize(imageLoad(gNormal, p).xyz);
  t.c = imageLoad(source, p);
  t.l = SVGFLuminance(t.c.rgb);
  t.s = imageLoad(deviation, p).r;
  return t;
}

// The symmetric weight of a pair of receiver pixels `offset` (in kernel taps) apart:
// the kernel, the geometric mean of the depth weights seen from either side, the
// normal weight, and the luminance difference against the pair's mean variance.
float PairWeight(Tap a, Tap b, ivec2 offset)
{
  float w = kernel[abs(offset.x)] * kernel[abs(offset.y)];
  if (offset == ivec2(0))
  {
    return w;
  }
  float pixels = length(vec2(offset)) * float(stepSize);
  float geometry = sqrt(SVGFGeometryWeight(a.x, a.n, b.x, b.n, pixels) *
    SVGFGeometryWeight(b.x, b.n, a.x, a.n, pixels));
  float difference = abs(a.l - b.l) / sigmaLuminance;
  return w * geometry *
    exp(-0.5 * (difference / (a.s + 1e-12) + difference / (b.s + 1e-12)));
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
    imageStore(destination, p, vec4(0.0));
    return;
  }
#if SVGF_ATROUS_STAGE == SVGF_ATROUS_DEVIATION
  imageStore(destination, p, vec4(sqrt(BlurredVariance(p))));
#else
  Tap tp = LoadTap(p);
  vec3 color = vec3(0.0);
  float variance = 0.0, total = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
  {
    for (int dx = -2; dx <= 2; ++dx)
    {
      ivec2 q = p + ivec2(dx, dy) * stepSize;
      if (!SVGFInside(q) || !SVGFReceiver(q))
      {
        continue;
      }
      Tap tq = LoadTap(q);
      float w = PairWeight(tp, tq, ivec2(dx, dy));
#if SVGF_ATROUS_STAGE != SVGF_ATROUS_NORMALIZE
      w *= imageLoad(balance, q).r;
#endif
#if SVGF_ATROUS_STAGE == SVGF_ATROUS_GATHER
      color += w * tq.c.rgb;
      variance += w * w * tq.c.a;
#endif
      total += w; // >= kernel[0]^2 d_p: p itself is a receiver
    }
  }
#if SVGF_ATROUS_STAGE == SVGF_ATROUS_NORMALIZE
  imageStore(destination, p, vec4(inversesqrt(total)));
#elif SVGF_ATROUS_STAGE == SVGF_ATROUS_BALANCE
  imageStore(destination, p, vec4(sqrt(imageLoad(balance, p).r / total)));
#else
  float d = imageLoad(balance, p).r;
  imageStore(destination, p, vec4(d * color, d * d * variance));
#endif
#endif
}
