// The kernel radius of each landed photon from its grid neighbours
// (vtkCausticsImpostorPhotonPass, after the trace): the trace gives every photon the
// radius of `spacings` spacings of the unoccluded beam, which is right where the
// specular surfaces focus the light but leaves gaps between splats where they spread
// it (the ball lens's halo: photons one texel apart in the light land many spacings
// apart, and the splats print the photon grid as bands). Here the radius grows to
// `spacings` times the mean distance to the neighbours in the grid (same Fresnel
// branch) that landed within `stretch` unoccluded spacings (farther ones took another
// path or crossed a silhouette), never below the trace's radius. Splats are
// energy-normalized (vtkCausticsPhotonSplatter), so the radius changes only how the
// photon's flux is spread, never how much there is.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D landedPosition; // w > 0: landed
layout(r32f, binding = 3) uniform image2D landedRadius;
uniform ivec2 photonGrid;
uniform int branchRows; // rows of one Fresnel branch: neighbours never cross it
uniform float spacings;
uniform float stretch;

void main()
{
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, photonGrid)))
  {
    return;
  }
  vec4 p = imageLoad(landedPosition, g);
  float radius = imageLoad(landedRadius, g).x;
  if (!(p.w > 0.0) || !(radius > 0.0))
  {
    return;
  }
  float unoccluded = radius / spacings; // one spacing of the unoccluded beam
  int branch = g.y / branchRows;
  float sum = 0.0;
  int count = 0;
  for (int k = 0; k < 4; ++k)
  {
    ivec2 q = g + ivec2(k == 0 ? 1 : (k == 1 ? -1 : 0), k == 2 ? 1 : (k == 3 ? -1 : 0));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, photonGrid)) ||
      q.y / branchRows != branch)
    {
      continue;
    }
    vec4 n = imageLoad(landedPosition, q);
    float gap = distance(n.xyz, p.xyz);
    if (n.w > 0.0 && gap <= stretch * unoccluded)
    {
      sum += gap;
      ++count;
    }
  }
  if (count > 0)
  {
    imageStore(landedRadius, g, vec4(max(radius, spacings * sum / float(count))));
  }
}
