// The caustic store's coarse level (vtkCausticsDistanceImpostors): per cell of
// IMPOSTOR_COARSE x IMPOSTOR_COARSE texels of a map's face, the area (m^2) of the
// receivers its texels show, the denominator of the coarse density estimate
// (ImpostorCausticIrradiance). Computed when the maps are made, not every frame:
// the areas depend on the maps alone.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(r32f, binding = 0) uniform writeonly image2DArray causticArea;

void main()
{
  ivec3 cell = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(cell, imageSize(causticArea))))
  {
    return;
  }
  // The last cell of a row also takes the texels beyond the last whole cell
  // (ImpostorCoarseCell clamps them there).
  ivec2 first = cell.xy * IMPOSTOR_COARSE;
  ivec2 end = first + IMPOSTOR_COARSE;
  ivec2 last = ivec2(cell.x == impostorCausticCells - 1 ? impostorResolution : end.x,
    cell.y == impostorCausticCells - 1 ? impostorResolution : end.y);
  float area = 0.0;
  for (int y = first.y; y < last.y; ++y)
  {
    for (int x = first.x; x < last.x; ++x)
    {
      ivec3 texel = ivec3(x, y, cell.z);
      if (int(texelFetch(impostorNormal, texel, 0).w + 0.5) == ROLE_RECEIVER &&
        texelFetch(impostorPosition, texel, 0).w >= 0.0)
      {
        area += ImpostorTexelArea(cell.z / 6, texel);
      }
    }
  }
  imageStore(causticArea, cell, vec4(area));
}
