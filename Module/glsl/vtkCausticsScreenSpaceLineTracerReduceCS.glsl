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

SSP_LDI_TABLE(readonly);

uniform usampler2D rowHits;
uniform sampler2DArray ldiPosition;
uniform sampler2DArray ldiNormal;
uniform mat4 worldToClip;
uniform vec4 viewOrigin;  // camera position (w = 1) or view direction (w = 0, parallel)
uniform float tolerance;  // m
uniform float pixelScale; // world size of one pixel at clip w = 1, m
uniform vec2 viewport;
uniform int batchBase;
uniform int capacity;
uniform uint stamp;

shared uint candidateT[16][16];

// The row's first hit x (at t, on `layer` at `pixel`) may not be the ray's first: where
// the ray ends within a pixel of another surface the image shows (the floor's strip
// along a wall's foot, whose pixels' centres show the wall), the row's fragments tested
// only the wall, and the ray met the wall's plane beyond the floor, below it. The
// surfaces of the eight pixels around the hit are tested as the row's fragments test
// theirs (vtkCausticsScreenSpaceLineTracerLineFS): the earliest receiver the ray meets
// close to its sample takes the hit (glass and mirrors keep the row's answer: next to
// a glass bunny's silhouette, rays that had just left it met its tangent planes again).
// Returns whether one did (t, pixel and layer updated).
bool EarlierNeighbour(SspRay ray, float ownLimit, inout float t, inout ivec2 pixel, inout int layer)
{
  vec3 o = ray.origin.xyz;
  vec3 d = ray.direction.xyz;
  int ownMaterial = ray.direction.w >= 0.0 ? int(ray.direction.w + 0.5) : -1;
  ivec2 centre = pixel;
  bool found = false;
  uint objects = ldiHeader.x;
  for (int j = -1; j <= 1; ++j)
  {
    for (int i = -1; i <= 1; ++i)
    {
      ivec2 q = centre + ivec2(i, j);
      if ((i == 0 && j == 0) || any(lessThan(q, ivec2(0))) ||
        any(greaterThanEqual(q, ivec2(viewport))))
      {
        continue;
      }
      for (uint object = 0u; object < objects; ++object)
      {
        uvec4 entry = ldiObjects[object];
        for (uint k = 0u; k < entry.y; ++k)
        {
          int l = int(entry.x + k);
          vec4 p = texelFetch(ldiPosition, ivec3(q, l), 0);
          if (p.w < 0.0)
          {
            break;
          }
          vec4 normalRole = texelFetch(ldiNormal, ivec3(q, l), 0);
          vec3 normal = normalRole.xyz;
          float denominator = dot(d, normal);
          if (int(normalRole.w + 0.5) != ROLE_RECEIVER || abs(denominator) <= 1e-3)
          {
            continue;
          }
          float candidate = dot(p.xyz - o, normal) / denominator;
          if (candidate >= t || candidate <= tolerance ||
            (int(p.w + 0.5) == ownMaterial && candidate < ownLimit))
          {
            continue;
          }
          float footprint = pixelScale * abs((worldToClip * vec4(p.xyz, 1.0)).w);
          float reach = SspSampleReach(viewOrigin, p.xyz, normal, footprint, tolerance);
          if (distance(o + candidate * d, p.xyz) > reach ||
            SspReceiverEndsBefore(ldiPosition, ldiNormal, worldToClip, viewport, viewOrigin, q,
              normal, o + candidate * d, reach))
          {
            continue;
          }
          t = candidate;
          pixel = q;
          layer = l;
          found = true;
        }
      }
    }
  }
  return found;
}
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
    EarlierNeighbour(r, line.info.y, t, pixel, layer);
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
