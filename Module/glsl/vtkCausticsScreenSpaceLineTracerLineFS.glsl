// One fragment of a photon ray's row (§2.1-2.2): the part of the ray that projects
// to this fragment's step along the line is tested against every layer of the
// layered depth image at the pixel it crosses. A layer's surface point P (normal
// N) is hit when the ray meets P's tangent plane within this step (plus the
// tolerance) and close to P; the nearest such hit is written with the frame's
// stamp, misses too, so that the row needs no clearing.
flat in SspRay lineRay;
flat in SspLine line;
SSP_LDI_TABLE(readonly);

uniform sampler2DArray ldiPosition;
uniform sampler2DArray ldiNormal;
uniform mat4 worldToClip;
uniform vec2 viewport;
uniform vec4 viewOrigin;  // camera position (w = 1) or view direction (w = 0, parallel)
uniform float tolerance;  // m
uniform float pixelScale; // world size of one pixel at clip w = 1, m
uniform uint stamp;

layout(location = 0) out uvec2 outHit;

void main()
{
  int column = int(gl_FragCoord.x);
  float n = line.info.x;
  if (float(column) >= n)
  {
    discard;
  }
  SspRay ray = lineRay;
  vec3 o = ray.origin.xyz;
  vec3 d = ray.direction.xyz;
  float tA = SspLineT(line, float(column) / n);
  float tB = SspLineT(line, float(column + 1) / n);
  // The step's span of the ray, widened by the tolerance and by one step on each
  // side: a pixel's tangent plane differs from the surface where the step crosses
  // it (curvature, grazing views), and the neighbouring fragments overlap.
  float step = abs(tB - tA);
  float lo = min(tA, tB) - tolerance - step;
  float hi = max(tA, tB) + tolerance + step;
  ivec2 pixel = SspLinePixel(line, column, ivec2(viewport));
  // One pixel's world size at this step's depth (clip w, interpolated as 1/w), and
  // the farthest a hit may lie from its sample (two footprints, stretched by a
  // grazing view by at most 3: beyond, near silhouettes, the tangent plane no
  // longer follows the surface).
  float footprint = pixelScale / mix(line.start.z, line.end.z, (float(column) + 0.5) / n);
  float reachMax = tolerance + 2.0 * footprint / 0.1;
  int ownMaterial = ray.direction.w >= 0.0 ? int(ray.direction.w + 0.5) : -1;
  bool inside = ray.origin.w > 1.5;

  float best = 3.0e38;
  uint bestLayer = 0u;
  uint objects = ldiHeader.x;
  for (uint object = 0u; object < objects; ++object)
  {
    uvec4 entry = ldiObjects[object];
    for (uint k = 0u; k < entry.y; ++k)
    {
      int layer = int(entry.x + k);
      vec4 p = texelFetch(ldiPosition, ivec3(pixel, layer), 0);
      if (p.w < 0.0)
      {
        break; // layers of an object are packed: none behind an empty one
      }
      // Cheap rejection first: the sample must lie near this step of the ray.
      vec3 offset = p.xyz - o;
      float along = dot(offset, d);
      vec3 across = offset - along * d;
      if (along < lo - reachMax || along > hi + reachMax ||
        dot(across, across) > reachMax * reachMax)
      {
        continue;
      }
      vec4 normalRole = texelFetch(ldiNormal, ivec3(pixel, layer), 0);
      vec3 normal = normalRole.xyz;
      float denominator = dot(d, normal);
      // Refractors (outward normals) are met from outside in air and from inside
      // within them; the other side is a neighbouring sample's tangent plane.
      bool refractor = int(normalRole.w + 0.5) == ROLE_REFRACTOR;
      if (refractor && (inside ? denominator < 0.0 : denominator > 0.0))
      {
        continue;
      }
      // Ray meets the tangent plane of the sample; along it when nearly parallel.
      float t = abs(denominator) > 1e-3 ? dot(p.xyz - o, normal) / denominator : dot(p.xyz - o, d);
      // Refractors are safe from their own surface by the side test: only a
      // hit at the origin itself is ignored. Other surfaces need the tolerance.
      if (t < lo || t > hi || t >= best || t <= (refractor ? 1e-3 * tolerance : tolerance))
      {
        continue;
      }
      if (!refractor && int(p.w + 0.5) == ownMaterial && t < line.info.y)
      {
        continue; // its own surface next to the origin (refractors: the side test)
      }
      float reach = SspSampleReach(viewOrigin, p.xyz, normal, footprint, tolerance);
      if (distance(o + t * d, p.xyz) > reach)
      {
        continue;
      }
      // Past a receiver's end its tangent plane goes on where the receiver does not.
      if (int(normalRole.w + 0.5) == ROLE_RECEIVER &&
        SspReceiverEndsBefore(ldiPosition, ldiNormal, worldToClip, viewport, viewOrigin, pixel,
          normal, o + t * d, reach))
      {
        continue;
      }
      best = t;
      bestLayer = uint(layer);
    }
  }
  outHit = uvec2(best < 3.0e38 ? floatBitsToUint(best) : 0xffffffffu, (stamp << 16) | bestLayer);
}
