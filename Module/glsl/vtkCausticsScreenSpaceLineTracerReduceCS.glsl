// First hit along each row (§2.1: "the first intersection along each ray can then
// be determined using a log-step texture reduce operation"): 16 invocations per
// row (16 rows per work group) scan its n_f fragments, then halve the candidates
// in shared memory; the winner's surface (position on the ray, normal and
// material from the layered depth image) is the ray's hit.
layout(local_size_x = 16, local_size_y = 16) in;

SSP_COUNTER(readonly);
SSP_RAYS(readonly);
SSP_LINES(readonly);
SSP_HITS(writeonly);

uniform usampler2D rowHits;
uniform sampler2DArray ldiPosition;
uniform sampler2DArray ldiNormal;
uniform mat4 worldToClip;
uniform float pixelScale; // world size of one pixel at clip w = 1, m
uniform vec2 viewport;
uniform int batchBase;
uniform int capacity;
uniform uint stamp;

shared uint candidateT[16][16];
shared uint candidateColumn[16][16];

void main()
{
  int row = int(gl_WorkGroupID.x) * 16 + int(gl_LocalInvocationID.y);
  uint slot = gl_LocalInvocationID.y;
  uint local = gl_LocalInvocationID.x;
  int ray = batchBase + row;
  bool valid = ray < int(min(rayCount, uint(capacity)));
  SspLine line;
  line.info = vec4(0.0);
  if (valid)
  {
    line = lines[ray];
  }
  int n = int(line.info.x);
  // Non-negative floats order like their bits: reduce on the bits.
  uint bestT = 0xffffffffu;
  uint bestColumn = 0u;
  for (int column = int(local); column < n; column += 16)
  {
    uvec2 value = texelFetch(rowHits, ivec2(column, row), 0).rg;
    if ((value.g >> 16) == (stamp & 0xffffu) && value.r < bestT)
    {
      bestT = value.r;
      bestColumn = uint(column);
    }
  }
  candidateT[slot][local] = bestT;
  candidateColumn[slot][local] = bestColumn;
  barrier();
  for (uint stride = 8u; stride > 0u; stride >>= 1)
  {
    if (local < stride)
    {
      uint other = local + stride;
      if (candidateT[slot][other] < candidateT[slot][local] ||
        (candidateT[slot][other] == candidateT[slot][local] &&
          candidateColumn[slot][other] < candidateColumn[slot][local]))
      {
        candidateT[slot][local] = candidateT[slot][other];
        candidateColumn[slot][local] = candidateColumn[slot][other];
      }
    }
    barrier();
  }
  if (local != 0u || !valid)
  {
    return;
  }
  SspHit hit;
  hit.position = vec4(0.0, 0.0, 0.0, -1.0);
  hit.normal = vec4(0.0, 0.0, 0.0, -1.0);
  if (candidateT[slot][0] != 0xffffffffu)
  {
    int column = int(candidateColumn[slot][0]);
    uvec2 value = texelFetch(rowHits, ivec2(column, row), 0).rg;
    int layer = int(value.g & 0xffffu);
    ivec2 pixel = SspLinePixel(line, column, ivec2(viewport));
    float t = uintBitsToFloat(candidateT[slot][0]);
    SspRay r = rays[ray];
    vec4 surface = texelFetch(ldiPosition, ivec3(pixel, layer), 0);
    vec3 normal = texelFetch(ldiNormal, ivec3(pixel, layer), 0).xyz;
    vec3 x = r.origin.xyz + t * r.direction.xyz;
    hit.position = vec4(x, t);
    hit.normal = vec4(SspSmoothNormal(ldiPosition, ldiNormal, worldToClip, viewport, pixelScale, x,
                        pixel, layer, surface.w, normal),
      surface.w);
  }
  hits[ray] = hit;
}
