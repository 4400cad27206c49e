// SVGF step 4, one a-trous wavelet iteration: the 5x5 B3-spline kernel with holes
// of stepSize pixels, over receiver pixels only, each tap weighted by SVGF's
// edge-stopping functions (depth, normal, and luminance against sigmaLuminance x
// the 3x3-blurred standard deviation). The variance is filtered with the squared
// weights. The weights are normalized: a constant irradiance stays what it is.
layout(rgba32f, binding = 2) uniform readonly image2D source;       // rgb W/m^2, a: variance
layout(rgba32f, binding = 3) uniform writeonly image2D destination; // the same
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
  vec4 cp = imageLoad(source, p);
  vec3 xp = imageLoad(gPosition, p).xyz;
  vec3 np = normalize(imageLoad(gNormal, p).xyz);
  float lp = SVGFLuminance(cp.rgb);
  float scale = sigmaLuminance * sqrt(BlurredVariance(p)) + 1e-12;
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
      vec4 cq = imageLoad(source, q);
      float w = kernel[abs(dx)] * kernel[abs(dy)];
      if (dx != 0 || dy != 0)
      {
        w *= SVGFGeometryWeight(xp, np, imageLoad(gPosition, q).xyz,
               normalize(imageLoad(gNormal, q).xyz), length(vec2(dx, dy)) * float(stepSize)) *
          exp(-abs(lp - SVGFLuminance(cq.rgb)) / scale);
      }
      color += w * cq.rgb;
      variance += w * w * cq.a;
      total += w;
    }
  }
  imageStore(destination, p, vec4(color / total, variance / (total * total)));
}
