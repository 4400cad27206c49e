// Which triangles of the photon grid are caustic triangles
// (vtkCausticsPhotonTriangleCommon.glsl): bit t of cell (x, y) is set when its
// triangle t is. Written once per frame, read by the triangles' draw and by the
// splats of the photons whose triangles are not all valid, so both agree exactly.
layout(local_size_x = 16, local_size_y = 16) in;

layout(r32ui, binding = 0) uniform writeonly uimage2D triangleMask;

void main()
{
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(cell, hitGrid)))
  {
    return;
  }
  uint mask = 0u;
  for (int t = 0; t < 2; ++t)
  {
    CausticTriangle tri;
    if (LoadCausticTriangle(cell, t, tri))
    {
      mask |= 1u << uint(t);
    }
  }
  imageStore(triangleMask, cell, uvec4(mask));
}
