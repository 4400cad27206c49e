// SVGF step 1, reprojection: each receiver pixel's world position (this frame's
// camera G-buffer) taken to where its surface point was in the last frame (its
// mesh's motion: the last model matrix times the inverse of this one, identity for
// a still actor) and projected with the previous frame's world-to-clip; the last
// frame's history is read there (bilinear over the 2x2 previous pixels that show the
// same surface: the same mesh, a receiver, the same tangent plane within
// depthTolerance x the distance to the camera, normals within normalTolerance).
// A moving actor is followed (per-actor motion vectors); a disocclusion, a mesh
// without a last frame (a new actor) and a deformed surface where it changed are
// rejected. Counts the receiver pixels and those that reprojected, for the
// camera-cut test of the next step.
struct SVGFMotion
{
  mat4 previousFromCurrent; // world to world, column-major
  vec4 previousIndex;       // x: the mesh's index (material) last frame, -1: none
};
layout(std430, binding = CAUSTICS_SVGF_MOTION_BINDING) readonly buffer SVGFMotionTable
{
  SVGFMotion motions[];
};
uniform int meshCount; // entries in the table (this frame's meshes)
layout(rgba32f, binding = 2) uniform readonly image2D previousPosition;
layout(rgba16f, binding = 3) uniform readonly image2D previousNormal;
layout(rgba32f, binding = 4) uniform readonly image2D historyColor;   // rgb W/m^2
layout(rgba32f, binding = 5) uniform readonly image2D historyMoments; // m1, m2, frames
layout(rgba32f, binding = 6) uniform writeonly image2D reprojectedColor;
layout(rgba32f, binding = 7) uniform writeonly image2D reprojectedMoments;
layout(r32ui, binding = 8) uniform uimage2D counts; // (0,0): receivers, (1,0): reprojected
uniform mat4 previousWorldToClip;
uniform int hasHistory;
uniform float depthTolerance;
uniform float normalTolerance;

void main()
{
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!SVGFInside(p))
  {
    return;
  }
  vec4 color = vec4(0.0);
  vec4 moments = vec4(0.0);
  if (SVGFReceiver(p))
  {
    imageAtomicAdd(counts, ivec2(0, 0), 1u);
    vec4 x = imageLoad(gPosition, p);
    vec3 n = normalize(imageLoad(gNormal, p).xyz);
    int mesh = int(x.w);
    SVGFMotion motion = motions[clamp(mesh, 0, max(meshCount - 1, 0))];
    float previousMesh = mesh < meshCount ? motion.previousIndex.x : -1.0;
    // Where this surface point was, and its normal then (normals go with the inverse
    // transpose, so a scaled actor keeps them right).
    vec3 xp = (motion.previousFromCurrent * vec4(x.xyz, 1.0)).xyz;
    vec3 np = normalize(transpose(inverse(mat3(motion.previousFromCurrent))) * n);
    vec4 clip = previousWorldToClip * vec4(xp, 1.0);
    if (hasHistory != 0 && previousMesh >= 0.0 && clip.w > 0.0)
    {
      vec2 q = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
      ivec2 q0 = ivec2(floor(q));
      vec2 f = q - vec2(q0);
      float tolerance = depthTolerance * max(distance(x.xyz, eye), SVGFFootprint(x.xyz));
      float total = 0.0;
      for (int j = 0; j < 2; ++j)
      {
        for (int i = 0; i < 2; ++i)
        {
          ivec2 t = q0 + ivec2(i, j);
          float w = (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y);
          if (w <= 0.0 || !SVGFInside(t))
          {
            continue;
          }
          vec4 px = imageLoad(previousPosition, t);
          vec4 pn = imageLoad(previousNormal, t);
          bool same = px.w == previousMesh && abs(pn.w - 1.0) < 0.5 &&
            abs(dot(np, px.xyz - xp)) <= tolerance && dot(np, normalize(pn.xyz)) >= normalTolerance;
          if (same)
          {
            color += w * imageLoad(historyColor, t);
            moments += w * imageLoad(historyMoments, t);
            total += w;
          }
        }
      }
      if (total > 1e-3)
      {
        color /= total;
        moments /= total;
        imageAtomicAdd(counts, ivec2(1, 0), 1u);
      }
      else
      {
        color = vec4(0.0);
        moments = vec4(0.0);
      }
    }
  }
  imageStore(reprojectedColor, p, color);
  imageStore(reprojectedMoments, p, moments);
}
