// Gathering the photon buffer into caustic map splats (001_7c07a484f7a872bb.txt).
// One dispatch per step; STAGE says which:
// - STAGE_FLAT: every photon of the buffer is transformed (Wyman & Davis 2006, as
//   improved by §4: photons fetched by index, nothing copied);
// - STAGE_NODES: one level k >= 1 of the hierarchical traversal (§3.1): a node
//   with no valid photon discards its whole subtree; with clustering (§3.2) a node
//   whose 4^k photons are all valid and land in one caustic map texel becomes one
//   splat with the intensity modifier 4^k; otherwise its four children go to the
//   list of level k - 1;
// - STAGE_PHOTONS: the photons (level 0) the traversal kept are transformed.
// TransformPhotons (§3.3): splat radius from the beam's divergence (Eq. 2 with the
// max-distance approximation), and the caustic map level whose texels keep the
// splat below splatSizeThreshold pixels across. Items come from the work list of
// their level (or, at the start level, from the whole level). Each stage is its
// own program (STAGE), so that no thread carries another stage's code. Appends
// are SSBO atomics per thread (a work-group reduction needs barriers, which cost
// more than the atomics on Mesa's llvmpipe).
layout(local_size_x = 64) in;

#define STAGE_FLAT 0
#define STAGE_NODES 1
#define STAGE_PHOTONS 2
const int SPLAT_CONSTANT = 0;
const int SPLAT_VARYING_SINGLE = 1;
const int SPLAT_VARYING_MULTIRES = 2;

uniform int level;            // k: 0 for photons
uniform int implicitList;     // 1: the items are the whole level, in row order
uniform ivec2 levelSize;      // nodes (or photons) of level k per row and column
uniform ivec2 childSize;      // of level k - 1
uniform uint nodeOffset;      // first node of level k in the node buffer
uniform uint listOffset;      // first entry of level k's work list
uniform uint childListOffset; // first entry of level k - 1's work list
uniform int testConvergence;  // §3.2 at this level
uniform int countValid;       // count the valid photons met by this step
uniform ivec2 gridSize;       // photon buffer
uniform int branchRows;       // rows per emission branch (the emitter's reflected branch
                              // starts at row branchRows; neighbours never cross it)
uniform uint splatRegion;     // entries per caustic map level in the splat list
uniform int lightType;        // 0 directional (measure in m^2), else point/spot (sr)
uniform int splatMode;
uniform float splatScale;         // kernel radius / photon spacing
uniform float maxDistanceFraction; // least spacing / the largest neighbour distance
uniform float constantRadiusPixels;
uniform float splatSizeThreshold; // largest splat diameter per level, in that level's pixels
uniform int dropCoarseSplats;     // 1: as the paper, drop splats needing level >= 4
uniform float fluxUnit;           // W per statistics unit
uniform CausticsView mapView;     // caustic map level 0
uniform CausticsView cameraView;  // the camera that will look at the caustic
uniform float minimumCameraRadiusPixels; // varying kernels' floor, camera pixel footprints
uniform sampler2D hitPosition;
uniform sampler2D hitNormal;
uniform sampler2D hitFlux;

layout(r32f, binding = 0) writeonly uniform image2D splatRadius;

struct Node
{
  uint count;
  uint boxLow;
  uint boxHigh;
  float fluxR, fluxG, fluxB;
  float x, y, z;
};

layout(std430, binding = CAUSTICS_HIERARCHY_NODES_BINDING) readonly buffer Nodes
{
  Node nodes[];
};
layout(std430, binding = CAUSTICS_HIERARCHY_CONTROL_BINDING) buffer Control
{
  uint control[];
};
layout(std430, binding = CAUSTICS_HIERARCHY_WORK_BINDING) buffer Work
{
  uint work[];
};
layout(std430, binding = CAUSTICS_HIERARCHY_SPLATS_BINDING) buffer Splats
{
  uint splats[];
};


struct Decision
{
  ivec2 coords;
  uint children;  // 0..4 children to visit at level k - 1
  int splatLevel; // caustic map level, -1: no splat
  uint entry;     // splat list entry
  float radius;   // m, for single photons
  float power;    // W (sum of channels) of the splat
  uint valid, cluster, clustered, coarse;
};

// TransformPhotons (§3.3) for one photon: returns the caustic map level (-1: no
// splat), the kernel radius (m) and whether it needed level 4 or coarser.
int TransformPhoton(
  ivec2 photon, out float radius, out float power, out bool valid, out bool coarse)
{
  radius = 0.0;
  power = 0.0;
  coarse = false;
  vec4 hit = texelFetch(hitPosition, photon, 0);
  valid = hit.w > 0.0;
  if (!valid)
  {
    return -1;
  }
  vec4 normal = texelFetch(hitNormal, photon, 0);
  vec4 flux = texelFetch(hitFlux, photon, 0);
  power = flux.r + flux.g + flux.b;
  // Footprint of the unoccluded beam on the receiver, omega_i d_i^2 / (N.D_i)
  // (omega_i is an area for directional lights: no d_i^2).
  // (omega_i is negated on a photon that landed on a hidden receiver.)
  float cosine = max(normal.w, 1e-3);
  float measure = abs(flux.a);
  float footprint = (lightType == 0 ? measure : measure * hit.w * hit.w) / cosine;
  // The beam's area A_i from the adjacent photons (same branch) that reached the
  // same receiver: the paper's max-distance approximation is the largest distance,
  // squared; a beam squeezed along one axis (a fold) is narrower than that, so its
  // width is the geometric mean of the largest distances along the grid's two axes,
  // kept above a fraction of the largest so that kernels still overlap along it.
  int branch = photon.y / branchRows;
  float spacing = 0.0, anySurface = 0.0;
  vec2 axes = vec2(0.0); // largest distance along the grid's x and y
  const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  for (int i = 0; i < 4; ++i)
  {
    ivec2 q = photon + offsets[i];
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, gridSize)) ||
      q.y / branchRows != branch)
    {
      continue;
    }
    vec4 neighbour = texelFetch(hitPosition, q, 0);
    if (neighbour.w > 0.0)
    {
      // Neighbours on the same receiver surface bound the beam (one that lands on
      // a wall next to the floor is another beam); a photon whose neighbours all
      // landed elsewhere still spread at least that far.
      float gap = distance(neighbour.xyz, hit.xyz);
      anySurface = max(anySurface, gap);
      // ... on a parallel surface elsewhere (a wall's top over the floor it shadows)
      // is another beam too: the same surface holds it near the photon's tangent plane.
      if (dot(texelFetch(hitNormal, q, 0).xyz, normal.xyz) > 0.9 &&
        abs(dot(neighbour.xyz - hit.xyz, normalize(normal.xyz))) <= 0.25 * gap)
      {
        spacing = max(spacing, gap);
        axes[i / 2] = max(axes[i / 2], gap);
      }
    }
  }
  if (axes.x > 0.0 && axes.y > 0.0)
  {
    spacing = max(sqrt(axes.x * axes.y), maxDistanceFraction * spacing);
  }
  spacing = spacing > 0.0 ? spacing : anySurface;
  // Eq. 2: r_i = sqrt(A_i (N.D_i) / (omega_i d_i^2)) = sqrt(A_i / footprint), the
  // inverse square root of the beam's magnification (without a landed neighbour:
  // 1, the unoccluded beam). Scaled by
  // the unoccluded footprint's radius it is the kernel radius on the receiver.
  float ri = spacing > 0.0 ? spacing * inversesqrt(footprint) : 1.0;
  float rho = splatScale * ri * sqrt(footprint);
  if (!(rho > 0.0) || isinf(rho))
  {
    return 0; // degenerate footprint: the smallest splat
  }
  if (splatMode != SPLAT_CONSTANT && minimumCameraRadiusPixels > 0.0)
  {
    // No finer than the image: the final render samples the map once per camera
    // pixel, so kernels narrower than the pixel's footprint on the receiver would
    // alias (behind the camera: no floor).
    float pixelFootprint = CameraFootprint(cameraView, hit.xyz, normalize(normal.xyz));
    rho = max(rho, minimumCameraRadiusPixels * pixelFootprint);
  }
  float pixels = ProjectedRadiusPixels(mapView, hit.xyz, normalize(normal.xyz), rho);
  if (!(pixels > 0.0) || isinf(pixels))
  {
    pixels = rho / max(ViewTexelSize(mapView, hit.xyz), 1e-30);
  }
  if (splatMode == SPLAT_CONSTANT)
  {
    radius = constantRadiusPixels * rho / pixels;
    return 0;
  }
  radius = rho;
  if (splatMode == SPLAT_VARYING_SINGLE)
  {
    return 0;
  }
  // photonMipLevel = trunc(log2(max(1, D_i / threshold))), D_i the diameter in pixels.
  int mapLevel = int(floor(log2(max(1.0, 2.0 * pixels / splatSizeThreshold))));
  if (mapLevel >= 4)
  {
    coarse = true;
    return dropCoarseSplats != 0 ? -1 : 3;
  }
  return mapLevel;
}

Decision Decide(uint item)
{
  Decision d;
  d.coords = ivec2(0);
  d.children = 0u;
  d.splatLevel = -1;
  d.entry = 0u;
  d.radius = 0.0;
  d.power = 0.0;
  d.valid = d.cluster = d.clustered = d.coarse = 0u;
  if (item >= control[CONTROL_LIST_COUNT + level])
  {
    return d;
  }
  if (implicitList != 0)
  {
    d.coords = ivec2(int(item % uint(levelSize.x)), int(item / uint(levelSize.x)));
  }
  else
  {
    uint code = work[listOffset + item];
    d.coords = ivec2(int(code & 0xFFFFu), int(code >> 16));
  }
#if STAGE == STAGE_NODES
  {
    Node node = nodes[nodeOffset + uint(d.coords.y * levelSize.x + d.coords.x)];
    d.valid = countValid != 0 ? node.count : 0u;
    if (node.count == 0u)
    {
      return d; // no valid photon below: the whole subtree is discarded
    }
    uint slots = 1u << (2 * level);
    if (testConvergence != 0 && node.count == slots && node.boxLow == node.boxHigh)
    {
      // DoChildrenConverge: every photon below is valid and lands in one texel.
      ivec2 photon = (d.coords << level) + ivec2(1 << (level - 1));
      d.splatLevel = 0;
      d.entry = uint(photon.y * gridSize.x + photon.x) | (uint(level) << SPLAT_LEVEL_SHIFT);
      d.power = float(slots) * (node.fluxR + node.fluxG + node.fluxB);
      d.cluster = 1u;
      d.clustered = slots;
      return d;
    }
    for (int j = 0; j < 2; ++j)
    {
      for (int i = 0; i < 2; ++i)
      {
        d.children += all(lessThan(2 * d.coords + ivec2(i, j), childSize)) ? 1u : 0u;
      }
    }
    return d;
  }
#else
  bool valid, coarse;
  d.splatLevel = TransformPhoton(d.coords, d.radius, d.power, valid, coarse);
  d.entry = uint(d.coords.y * gridSize.x + d.coords.x);
  d.valid = valid && countValid != 0 ? 1u : 0u;
  d.coarse = coarse ? 1u : 0u;
  return d;
#endif
}

void AddFlux(uint slot, float watts)
{
  CAUSTICS_ADD_FIXED_POINT(control, slot, watts, fluxUnit)
}

void main()
{
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  Decision d = Decide(group * 64u + gl_LocalInvocationIndex);
  if (d.valid > 0u)
  {
    atomicAdd(control[CONTROL_VALID], d.valid);
  }
  if (d.children > 0u)
  {
    uint next = childListOffset + atomicAdd(control[CONTROL_LIST_COUNT + level - 1], d.children);
    for (int j = 0; j < 2; ++j)
    {
      for (int i = 0; i < 2; ++i)
      {
        ivec2 child = 2 * d.coords + ivec2(i, j);
        if (all(lessThan(child, childSize)))
        {
          work[next] = uint(child.x) | (uint(child.y) << 16);
          next += 1u;
        }
      }
    }
  }
  if (d.coarse > 0u)
  {
    atomicAdd(control[CONTROL_COARSE_SPLATS], 1u);
    AddFlux(uint(CONTROL_COARSE_FLUX), d.power);
  }
  if (d.splatLevel >= 0)
  {
    uint slot = atomicAdd(control[CONTROL_DRAW + 4 * d.splatLevel], 1u);
    splats[uint(d.splatLevel) * splatRegion + slot] = d.entry;
    AddFlux(uint(CONTROL_SPLAT_FLUX + 2 * d.splatLevel), d.power);
    if (d.cluster > 0u)
    {
      atomicAdd(control[CONTROL_CLUSTERS], 1u);
      atomicAdd(control[CONTROL_CLUSTERED_PHOTONS], d.clustered);
    }
    else
    {
      imageStore(splatRadius, d.coords, vec4(d.radius));
    }
  }
}
