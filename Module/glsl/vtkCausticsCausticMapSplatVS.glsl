// One point sprite per entry of a caustic map level's splat list (drawn with
// glDrawArraysIndirect, the count written by the gather on the GPU). As
// 001_7c07a484f7a872bb.txt §4 recommends, nothing is copied into a vertex buffer:
// the entry names the photon, whose data is fetched from the photon buffer by
// index. A cluster (§3.2) is drawn at the centroid of its photons (the mean
// position of its mipmap node) with the node's mean flux times the intensity
// modifier 4^k, and the normal of its representative photon. The fragment shader is
// the shared receiver-oriented, energy-normalized kernel (vtkCausticsPhotonSplatFS).
uniform sampler2D hitPosition;
uniform sampler2D hitNormal;
uniform sampler2D hitFlux;
uniform sampler2D splatRadiusTexture; // m, per photon
uniform int gridWidth;
uniform uint listOffset;
uniform uint nodeOffsets[MAX_TRAVERSAL_LEVELS];
uniform int nodeRowLength[MAX_TRAVERSAL_LEVELS];
uniform CausticsView targetView; // the caustic map level drawn into
uniform float minimumRadiusPixels;
uniform float maximumRadiusPixels;
uniform float clusterRadiusPixels;
uniform CausticsView cameraView;
uniform float minimumCameraRadiusPixels; // clusters' floor in camera pixel footprints (0: none)
// The hidden receivers' map (vtkCausticsCausticMap): the photons that landed on a
// hidden receiver (the trace makes their measure, hitFlux.a, negative; a cluster
// goes by its representative photon), and those whose kernel reaches one of its
// receivers on their plane (a photon beside the edge of a wall's shadow lights both
// sides; the others would be drawn for nothing).
uniform bool hiddenOnly;
// targetPosition, targetNormal (the level's receivers), planeTolerance and
// normalTolerance: vtkCausticsSplatCoverage.glsl.
// The other receiver layer's same level (the hidden receivers' map for the map, the
// map for the hidden receivers'): the two share each kernel (KernelDeposit).
uniform bool hasOtherLayer;
uniform sampler2D otherPosition;
uniform sampler2D otherNormal;

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
layout(std430, binding = CAUSTICS_HIERARCHY_SPLATS_BINDING) readonly buffer Splats
{
  uint splats[];
};

flat out vec3 splatCentre;
flat out vec3 splatNormal;
flat out vec3 splatFlux;
flat out float splatRadius;
flat out float splatHalfSet; // CausticsHalfSet of the photon or cluster

void Discard()
{
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume
  gl_PointSize = 1.0;
  splatRadius = 0.0;
}

vec2 ToPixels(vec3 p)
{
  vec4 clip = targetView.worldToClip * vec4(p, 1.0);
  return (clip.xy / clip.w * 0.5 + 0.5) * targetView.size;
}

// Where the view's ray through `pixel` meets the plane through c with normal n.
vec3 OnPlane(vec2 pixel, vec3 c, vec3 n)
{
  vec2 ndc = pixel / targetView.size * 2.0 - 1.0;
  vec4 near = targetView.clipToWorld * vec4(ndc, -1.0, 1.0);
  vec4 far = targetView.clipToWorld * vec4(ndc, 1.0, 1.0);
  vec3 origin = near.xyz / near.w;
  vec3 direction = far.xyz / far.w - origin;
  return origin + dot(c - origin, n) / dot(direction, n) * direction;
}

// The texels of this level's plane (vtkCausticsSplatCoverage.glsl): those that show it
// in this map or in the other receiver layer. Past the map's frame the plane ends for
// the map: the caustic store holds the photons that land there, and the pixels there
// read it.
bool KernelCountsTexel(ivec2 texel, vec3 c, vec3 n, float r, inout float d2)
{
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(targetView.size))))
  {
    return false;
  }
  return DepositsOn(targetPosition, targetNormal, texel, c, n, r, d2) ||
    (hasOtherLayer && DepositsOn(otherPosition, otherNormal, texel, c, n, r, d2));
}

// What the fragment shaders will deposit per watt: the kernel of radius r (m) centred
// at `centre` (pixels; a and b: r along its two tangents, in pixels) on the plane
// (c, n), over the texels of this level, and of the other receiver layer, that show
// that plane, times each texel's area on it. Dividing the flux by it makes every splat
// deposit exactly its flux on the receivers it reaches
// (vtkCausticsSplatCoverage.glsl): a kernel cut by the plane's end, by the map's frame
// or by a shadow's edge the other layer holds gives the cut part to the rest (on the
// bunny's box a tenth of its walls' light was lost so), and small kernels lose the
// midpoint rule's error (up to 12 % at 1.5 pixels): kernels narrower than 4 pixels are
// summed over every pixel centre they cover. Wider ones count the share that lands
// (the continuous kernel integrates to 1).
float KernelDeposit(vec2 centre, vec2 a, vec2 b, vec3 c, vec3 n, float r, float reach, bool small)
{
  // One pixel step along x and y, on the plane (exact for orthographic views; the
  // perspective's change over a few pixels is of second order).
  vec3 stepX = OnPlane(centre + vec2(1.0, 0.0), c, n) - c;
  vec3 stepY = OnPlane(centre + vec2(0.0, 1.0), c, n) - c;
  float area = length(cross(stepX, stepY));
  if (!(area > 0.0) || isinf(area))
  {
    return 1.0;
  }
  bool whole = KernelWhole(centre, a, b, c, n, r);
  if (!small)
  {
    return whole ? 1.0
                 : LandedShare(KernelSums(centre, c, n, stepX, stepY, r, reach,
                     KernelStride(reach), false));
  }
  vec2 sums = KernelSums(centre, c, n, stepX, stepY, r, reach, 1, whole);
  return max(sums.y, 0.125 * sums.x) * 2.0 / (CAUSTICS_PI * r * r) * area;
}

// Whether the target level shows a receiver on the plane (p, n) at the kernel's
// centre or at the four ends of its reach (pixels of the level).
bool ReachesReceiver(vec2 centre, float reach, vec3 p, vec3 n, float tolerance)
{
  const vec2 offsets[5] =
    vec2[5](vec2(0.0), vec2(1.0, 0.0), vec2(-1.0, 0.0), vec2(0.0, 1.0), vec2(0.0, -1.0));
  ivec2 last = ivec2(targetView.size) - 1;
  for (int k = 0; k < 5; ++k)
  {
    ivec2 texel = clamp(ivec2(floor(centre + reach * offsets[k])), ivec2(0), last);
    vec4 s = texelFetch(targetPosition, texel, 0);
    if (s.w >= 0.0 && abs(dot(s.xyz - p, n)) <= tolerance)
    {
      return true;
    }
  }
  return false;
}

void main()
{
  uint entry = splats[listOffset + uint(gl_VertexID)];
  uint index = entry & SPLAT_INDEX_MASK;
  int k = int(entry >> SPLAT_LEVEL_SHIFT);
  ivec2 texel = ivec2(int(index % uint(gridWidth)), int(index / uint(gridWidth)));
  vec3 position = texelFetch(hitPosition, texel, 0).xyz;
  vec3 n = normalize(texelFetch(hitNormal, texel, 0).xyz);
  vec3 flux;
  float r;
  float smallest = minimumRadiusPixels;
  uint member = index; // the photon's, or its cluster's, index in its level's grid
  if (k == 0)
  {
    flux = texelFetch(hitFlux, texel, 0).rgb;
    r = texelFetch(splatRadiusTexture, texel, 0).r;
  }
  else
  {
    ivec2 node = texel >> k;
    member = uint(node.y * nodeRowLength[k] + node.x);
    Node cluster = nodes[nodeOffsets[k] + member];
    flux = vec3(cluster.fluxR, cluster.fluxG, cluster.fluxB) * float(1u << (2 * k));
    position = vec3(cluster.x, cluster.y, cluster.z);
    // Converged: the photons all land in one texel; no finer than the image though
    // (the gather gives single photons the same floor).
    r = minimumCameraRadiusPixels > 0.0
      ? minimumCameraRadiusPixels * CameraFootprint(cameraView, position, n)
      : 0.0;
    smallest = clusterRadiusPixels;
  }
  vec4 clip = targetView.worldToClip * vec4(position, 1.0);
  if (clip.w <= 0.0 || !(dot(flux, vec3(1.0)) > 0.0) || !AllFinite(position) || !AllFinite(n))
  {
    Discard();
    return;
  }
  vec3 e1, e2;
  CausticsTangents(n, e1, e2);
  // Projection is not linear under perspective: measure the splat's own radius
  // (a texel-sized probe for clusters).
  float probe = r > 0.0 ? r : ViewTexelSize(targetView, position);
  vec2 centre = ToPixels(position);
  vec2 a = ToPixels(position + probe * e1) - centre;
  vec2 b = ToPixels(position + probe * e2) - centre;
  float pixels = max(length(a), length(b));
  if (!(pixels > 0.0) || isinf(pixels))
  {
    Discard();
    return;
  }
  // Keep each kernel a few pixels wide (narrower ones fall between pixel centres
  // and lose energy) and bounded in cost; the kernel stays normalized for the
  // radius actually used.
  float clamped = r > 0.0 ? clamp(pixels, smallest, maximumRadiusPixels) : smallest;
  float scale = clamped / pixels;
  // The projected disk is the ellipse c + R (cos t a + sin t b), R = scale: its
  // half extents are R sqrt(a.x^2 + b.x^2) and R sqrt(a.y^2 + b.y^2); one pixel of
  // margin covers pixel centres on its edge.
  vec2 extent = scale * sqrt(a * a + b * b);
  float reach = max(extent.x, extent.y);
  splatRadius = probe * scale;
  if (hiddenOnly && !(texelFetch(hitFlux, texel, 0).a < 0.0) &&
    !ReachesReceiver(centre, reach, position, n, planeTolerance * splatRadius))
  {
    Discard();
    return;
  }
  float deposit =
    KernelDeposit(centre, scale * a, scale * b, position, n, splatRadius, reach, clamped < 4.0);
  splatCentre = position;
  splatNormal = n;
  splatFlux = deposit > 0.0 ? flux / deposit : flux;
  splatHalfSet = CausticsHalfSet(member);
  gl_Position = clip;
  gl_PointSize = min(2.0 * reach + 2.0, 1023.0);
}
