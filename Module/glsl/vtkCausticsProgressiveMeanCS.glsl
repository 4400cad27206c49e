// One step of a running mean: the frame's estimate joins the mean of the frames before
// it with weight 1 / (frames so far), and the frame's texture is left holding the mean,
// so that every later stage (denoised or not, composite, ReadBuffer) reads the mean.
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform image2D frame;
layout(rgba32f, binding = 1) uniform image2D mean;

uniform ivec2 size;
uniform float weight; // 1 / (frames averaged, this one included); 1: the first

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size)))
  {
    return;
  }
  vec4 estimate = imageLoad(frame, pixel);
  vec4 result = weight >= 1.0 ? estimate : mix(imageLoad(mean, pixel), estimate, weight);
  imageStore(mean, pixel, result);
  imageStore(frame, pixel, result);
}
