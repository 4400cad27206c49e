// Separable Gaussian of the volume lines' image: the normalized Gaussian that
// re-distributes the lines' irregular samples (003 §5.2, Fig. 5; 000 §3.2 "blurred with
// a Gaussian filter"), of constant screen-space support. The weights are normalized
// over the taps inside the image: a pixel near the border is the mean of the lines it
// sees, as the reference's kernel sums the beams on both sides of it (lines outside the
// view are not drawn, so taps there would count as dark and dim the border).
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform readonly image2D source;
layout(rgba32f, binding = 1) uniform writeonly image2D destination;

uniform ivec2 size;
uniform ivec2 axis;  // (1, 0) horizontal, (0, 1) vertical
uniform float sigma; // pixels; 0 copies
uniform int radius;

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size)))
  {
    return;
  }
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int k = -radius; k <= radius; ++k)
  {
    float w = sigma > 0.0 ? exp(-0.5 * float(k * k) / (sigma * sigma)) : (k == 0 ? 1.0 : 0.0);
    ivec2 q = pixel + k * axis;
    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)))
    {
      total += w;
      sum += w * imageLoad(source, q).rgb;
    }
  }
  imageStore(destination, pixel, vec4(sum / total, 1.0));
}
