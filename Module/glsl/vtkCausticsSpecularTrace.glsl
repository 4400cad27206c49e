// The scene's glass and mirror triangles in a bounding volume hierarchy
// (vtkCausticsSpecularHierarchy, which documents the layout): rays meet them where the
// geometry puts them, with the face normal that tells the side and the interpolated
// normal that shades.
layout(std430, binding = CAUSTICS_SPECULAR_NODE_BINDING) readonly buffer CausticsSpecularNodes
{
  vec4 specularNodes[]; // two per node
};
layout(std430, binding = CAUSTICS_SPECULAR_TRIANGLE_BINDING) readonly buffer CausticsSpecularTriangles
{
  vec4 specularTriangles[]; // six per triangle
};
uniform int specularNodeCount; // 0: no hierarchy (nothing specular, or not traced)

const int SPECULAR_STACK = 32;

struct SpecularHit
{
  float t;
  int material;
  vec3 geometric; // unit face normal, on the side of the interpolated one
  vec3 shading;   // unit interpolated normal, as modelled
};

// Where o + t d enters the box (lo, hi) with 1 / d = inverse, or 3e38 if it misses it
// within (tMin, tMax).
float SpecularBoxEntry(vec3 o, vec3 inverse, vec3 lo, vec3 hi, float tMin, float tMax)
{
  vec3 a = (lo - o) * inverse;
  vec3 b = (hi - o) * inverse;
  vec3 near = min(a, b);
  vec3 far = max(a, b);
  float enter = max(max(near.x, near.y), max(near.z, tMin));
  float leave = min(min(far.x, far.y), min(far.z, tMax));
  return enter <= leave ? enter : 3.0e38;
}

// The nearest specular triangle o + t d meets with tMin < t < tMax (Moeller-Trumbore).
bool SpecularTrace(vec3 o, vec3 d, float tMin, float tMax, out SpecularHit hit)
{
  hit = SpecularHit(tMax, -1, vec3(0.0), vec3(0.0));
  if (specularNodeCount <= 0)
  {
    return false;
  }
  // A zero component divides to infinity, which the slabs take as they should.
  vec3 inverse = 1.0 / d;
  int best = -1;
  vec2 bestUV = vec2(0.0);
  int stack[SPECULAR_STACK];
  int top = 0;
  int node = 0;
  if (SpecularBoxEntry(o, inverse, specularNodes[0].xyz, specularNodes[1].xyz, tMin, hit.t) >
    1.0e38)
  {
    return false;
  }
  for (int visits = 0; visits < 4 * specularNodeCount; ++visits)
  {
    vec4 lo = specularNodes[2 * node];
    vec4 hi = specularNodes[2 * node + 1];
    int count = floatBitsToInt(hi.w);
    if (count > 0)
    {
      int first = floatBitsToInt(lo.w);
      for (int k = first; k < first + count; ++k)
      {
        vec3 p0 = specularTriangles[6 * k].xyz;
        vec3 e1 = specularTriangles[6 * k + 1].xyz;
        vec3 e2 = specularTriangles[6 * k + 2].xyz;
        vec3 pv = cross(d, e2);
        float det = dot(e1, pv);
        if (abs(det) < 1e-30)
        {
          continue;
        }
        float inv = 1.0 / det;
        vec3 tv = o - p0;
        float u = dot(tv, pv) * inv;
        vec3 qv = cross(tv, e1);
        float v = dot(d, qv) * inv;
        float t = dot(e2, qv) * inv;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > tMin && t < hit.t)
        {
          hit.t = t;
          best = k;
          bestUV = vec2(u, v);
        }
      }
    }
    else
    {
      // Both children's boxes: the nearer is visited next, the farther waits.
      int left = node + 1;
      int right = floatBitsToInt(lo.w);
      float tl = SpecularBoxEntry(o, inverse, specularNodes[2 * left].xyz,
        specularNodes[2 * left + 1].xyz, tMin, hit.t);
      float tr = SpecularBoxEntry(o, inverse, specularNodes[2 * right].xyz,
        specularNodes[2 * right + 1].xyz, tMin, hit.t);
      if (tl < 1.0e38 || tr < 1.0e38)
      {
        bool leftFirst = tl <= tr;
        node = leftFirst ? left : right;
        if (max(tl, tr) < 1.0e38 && top < SPECULAR_STACK)
        {
          stack[top++] = leftFirst ? right : left;
        }
        continue;
      }
    }
    // Next waiting subtree that the nearest hit so far does not hide.
    bool found = false;
    while (top > 0 && !found)
    {
      node = stack[--top];
      found = SpecularBoxEntry(o, inverse, specularNodes[2 * node].xyz,
                specularNodes[2 * node + 1].xyz, tMin, hit.t) < 1.0e38;
    }
    if (!found)
    {
      break;
    }
  }
  if (best < 0)
  {
    return false;
  }
  vec4 p0 = specularTriangles[6 * best];
  vec3 e1 = specularTriangles[6 * best + 1].xyz;
  vec3 e2 = specularTriangles[6 * best + 2].xyz;
  vec3 shading = (1.0 - bestUV.x - bestUV.y) * specularTriangles[6 * best + 3].xyz +
    bestUV.x * specularTriangles[6 * best + 4].xyz + bestUV.y * specularTriangles[6 * best + 5].xyz;
  vec3 geometric = normalize(cross(e1, e2));
  // A mesh without normals shades with its faces.
  shading = dot(shading, shading) > 1e-12 ? normalize(shading) : geometric;
  hit.geometric = dot(geometric, shading) < 0.0 ? -geometric : geometric;
  hit.shading = shading;
  hit.material = int(p0.w + 0.5);
  return true;
}
