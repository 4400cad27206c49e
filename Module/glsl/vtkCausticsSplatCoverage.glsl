// The share of a splat's kernel that lands on its receiver, for the caustic maps'
// splats (vtkCausticsCausticMapSplatVS). The fragment shader (vtkCausticsPhotonSplatFS)
// deposits a photon's kernel only on the texels that show the kernel's own plane;
// where the receiver ends inside the kernel (a floor meeting a wall, a table's edge)
// the rest of it was lost, and a photon beside the end lit it with part of its flux.
// Dividing the flux by the share that lands gives that part to the texels that take
// it: every splat deposits its whole flux. The vertex shader says which texels count
// as its plane's (KernelCountsTexel, defined after this file).
// The camera-view splats (vtkCausticsPhotonSplatVS) do not use it: a camera's view
// cannot tell a receiver's end from an occluder without a second layer, and where a
// grazing receiver is a few pixels tall the renormalized kernels piled its light on
// its edges (docs/accuracy.md, "Kernels at a receiver's end").
uniform sampler2D targetPosition; // the target view's receivers: xyz world, w = material
uniform sampler2D targetNormal;   // xyz normal as modelled, w = role
uniform float planeTolerance;     // the fragment shader's tests
uniform float normalTolerance;

// Whether texel `texel` of a receiver layer shows the plane (c, n) of a kernel of
// radius r as the fragment shader tests it (a receiver, on the plane, facing the same
// way), and the squared distance d2 in the plane from c it weighs it by (it deposits
// where d2 < r^2).
bool DepositsOn(sampler2D positions, sampler2D normals, ivec2 texel, vec3 c, vec3 n, float r,
  out float d2)
{
  vec4 s = texelFetch(positions, texel, 0);
  vec4 sn = texelFetch(normals, texel, 0);
  vec3 v = s.xyz - c;
  float height = dot(v, n);
  d2 = dot(v, v) - height * height;
  return s.w >= 0.0 && int(sn.w + 0.5) == ROLE_RECEIVER && dot(sn.xyz, n) >= normalTolerance &&
    abs(height) <= planeTolerance * r;
}

// The vertex shader's rule: whether texel `texel` (possibly outside the target) is the
// kernel's plane. d2 comes in as the squared distance from c of the texel's ray on the
// plane, and goes out as the distance the weight takes (the fragment shader's own,
// where it deposits).
bool KernelCountsTexel(ivec2 texel, vec3 c, vec3 n, float r, inout float d2);

// The kernel K = 1 - d^2/r^2 over the pixel centres the kernel covers on the plane
// (c, n), centred at `centre` (pixels), `stepX` and `stepY` one pixel along x and y
// on that plane: x, its sum over every covered centre; y, over those that count
// (KernelCountsTexel; all of them when `whole`). `stride` pixels between the centres
// sampled (a wide kernel's share needs no more than 15 x 15 of them).
vec2 KernelSums(vec2 centre, vec3 c, vec3 n, vec3 stepX, vec3 stepY, float r, float reach,
  int stride, bool whole)
{
  float r2 = r * r;
  int extent = (int(ceil(reach)) + 1) / stride;
  vec2 first = floor(centre) + 0.5;
  vec2 sums = vec2(0.0);
  for (int y = -extent; y <= extent; ++y)
  {
    for (int x = -extent; x <= extent; ++x)
    {
      vec2 pixel = first + vec2(x, y) * float(stride);
      vec2 delta = pixel - centre;
      vec3 offset = delta.x * stepX + delta.y * stepY;
      float d2 = dot(offset, offset);
      if (d2 >= r2)
      {
        continue;
      }
      sums.x += 1.0 - d2 / r2;
      if (whole || KernelCountsTexel(ivec2(floor(pixel)), c, n, r, d2))
      {
        sums.y += max(1.0 - d2 / r2, 0.0);
      }
    }
  }
  return sums;
}

// Whether the kernel's centre and eight points on its rim (0.85 r) all count: a
// kernel away from any end of its receiver, which needs no sum.
bool KernelWhole(vec2 centre, vec2 a, vec2 b, vec3 c, vec3 n, float r)
{
  for (int k = 0; k < 9; ++k)
  {
    float angle = float(k) * (CAUSTICS_PI / 4.0);
    vec2 pixel = k == 8 ? centre : centre + 0.85 * (cos(angle) * a + sin(angle) * b);
    float d2 = 0.0;
    if (!KernelCountsTexel(ivec2(floor(pixel)), c, n, r, d2))
    {
      return false;
    }
  }
  return true;
}

// Stride between the pixel centres a kernel of `reach` pixels samples: every one up
// to 7 pixels, then at most 15 per axis.
int KernelStride(float reach)
{
  return max(1, int(ceil((reach + 1.0) / 7.0)));
}

// The share of the kernel that lands, from KernelSums; a kernel that lands almost
// nowhere (a photon on a sliver of receiver) counts at least an eighth, so that it
// does not become a spike.
float LandedShare(vec2 sums)
{
  return sums.x > 0.0 ? max(sums.y, 0.125 * sums.x) / sums.x : 1.0;
}
