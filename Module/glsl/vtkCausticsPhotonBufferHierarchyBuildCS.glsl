// One level of the photon buffer's validity mipmap (001_7c07a484f7a872bb.txt §3.1):
// node (x, y) of level k covers the photons (2^k x .. 2^k x + 2^k - 1, same in y).
// It stores how many of them are valid, the bounding box of the caustic map
// texels (level 0) they land in (for the convergence test of §3.2), and their
// mean flux and mean hit position over the 4^k slots (what box-filtered mipmaps
// of the photon buffer hold: 4^k x mean flux is their total, and for a full node
// the mean position is the cluster's centroid). Level 1 reads the photon buffer,
// level k > 1 the level below.
layout(local_size_x = 8, local_size_y = 8) in;

uniform int level;
uniform ivec2 levelSize;
uniform ivec2 childSize;
uniform uint levelOffset; // first node of this level in the node buffer
uniform uint childOffset; // first node of the level below (k > 1)
uniform sampler2D hitPosition; // photon buffer: xyz, w > 0 for a hit
uniform sampler2D hitFlux;     // rgb W
uniform CausticsView mapView;  // caustic map level 0

struct Node
{
  uint count;
  uint boxLow;  // min texel x | min texel y << 16
  uint boxHigh; // max texel x | max texel y << 16
  float fluxR, fluxG, fluxB;
  float x, y, z;
};

layout(std430, binding = CAUSTICS_HIERARCHY_NODES_BINDING) buffer Nodes
{
  Node nodes[];
};

void main()
{
  ivec2 node = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(node, levelSize)))
  {
    return;
  }
  uint count = 0u;
  uvec2 low = uvec2(0xFFFFu), high = uvec2(0u);
  vec3 flux = vec3(0.0);
  vec3 position = vec3(0.0);
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 child = 2 * node + ivec2(i, j);
      if (any(greaterThanEqual(child, childSize)))
      {
        continue; // beyond the buffer's edge: an empty slot
      }
      if (level == 1)
      {
        vec4 p = texelFetch(hitPosition, child, 0);
        vec2 pixel;
        if (p.w > 0.0)
        {
          ViewProject(mapView, p.xyz, pixel);
          uvec2 texel = uvec2(ViewTexel(mapView, pixel));
          count += 1u;
          low = min(low, texel);
          high = max(high, texel);
          flux += texelFetch(hitFlux, child, 0).rgb;
          position += p.xyz;
        }
      }
      else
      {
        Node c = nodes[childOffset + uint(child.y * childSize.x + child.x)];
        if (c.count > 0u)
        {
          count += c.count;
          low = min(low, uvec2(c.boxLow & 0xFFFFu, c.boxLow >> 16));
          high = max(high, uvec2(c.boxHigh & 0xFFFFu, c.boxHigh >> 16));
          flux += vec3(c.fluxR, c.fluxG, c.fluxB);
          position += vec3(c.x, c.y, c.z);
        }
      }
    }
  }
  // Children hold means over 4^(k-1) slots: the mean over 4^k slots is their sum / 4.
  flux *= 0.25;
  position *= 0.25;
  Node result;
  result.count = count;
  result.boxLow = low.x | (low.y << 16);
  result.boxHigh = high.x | (high.y << 16);
  result.fluxR = flux.r;
  result.fluxG = flux.g;
  result.fluxB = flux.b;
  result.x = position.x;
  result.y = position.y;
  result.z = position.z;
  nodes[levelOffset + uint(node.y * levelSize.x + node.x)] = result;
}
