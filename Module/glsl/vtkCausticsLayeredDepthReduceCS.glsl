// Maximum of the per-pixel depth complexity, per object (§2.2: "the maximum over
// all pixels is then collected by a texture reduce-max operation"): a log-step
// reduction in shared memory per 16 x 16 tile, then one atomicMax per tile.
layout(local_size_x = 16, local_size_y = 16) in;

layout(r32ui, binding = 0) readonly uniform uimage2DArray complexity;
SSP_LDI_TABLE();

uniform ivec2 size;
uniform int objectCount;

shared uint partial[256];

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  uint local = gl_LocalInvocationIndex;
  bool inside = all(lessThan(pixel, size));
  for (int object = 0; object < objectCount; ++object)
  {
    partial[local] = inside ? imageLoad(complexity, ivec3(pixel, object)).r : 0u;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1)
    {
      if (local < stride)
      {
        partial[local] = max(partial[local], partial[local + stride]);
      }
      barrier();
    }
    if (local == 0u && partial[0] > 0u)
    {
      atomicMax(ldiObjects[object].z, partial[0]);
    }
    barrier();
  }
}
