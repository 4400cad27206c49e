// Camera optical depth (vtkCausticsCameraOpticalDepth): one invocation per column of the
// volume integrates the medium's density along its viewing ray, from the near plane
// through the column's centre, and stores the running optical depth (density x m) at
// `slices` distances spread evenly over `range`. Compiled with CAUSTICS_MEDIUM_GRID.
layout(local_size_x = 8, local_size_y = 8) in;

layout(r32f, binding = 0) uniform writeonly image3D opticalDepth;
uniform mat4 clipToWorld;
uniform ivec2 columns;
uniform int slices;
uniform vec2 range; // distances (m) from the near plane of the first and the last slice

void main()
{
  ivec2 column = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(column, columns)))
  {
    return;
  }
  vec2 ndc = 2.0 * (vec2(column) + 0.5) / vec2(columns) - 1.0;
  vec4 near = clipToWorld * vec4(ndc, -1.0, 1.0);
  vec4 far = clipToWorld * vec4(ndc, 1.0, 1.0);
  vec3 o = near.xyz / near.w;
  vec3 d = normalize(far.xyz / far.w - o);
  float depth = 0.0;
  float t = 0.0;
  for (int k = 0; k < slices; ++k)
  {
    float next = mix(range.x, range.y, float(k) / float(slices - 1));
    float t0 = t, t1 = next;
    if (causticsMediumOn != 0 && CausticsClipToBox(o, d, causticsMediumLow, causticsMediumHigh, t0, t1))
    {
      depth += CausticsMediumOpticalDepth(o, d, t0, t1);
    }
    t = next;
    imageStore(opticalDepth, ivec3(column, k), vec4(depth));
  }
}
