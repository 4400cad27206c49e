// Caustic triangles, deposited (vtkCausticsPhotonTriangleCommon.glsl): the pixel
// receives the triangle's flux times the fraction of the triangle's screen area
// inside the pixel, over the pixel's area on the receiver. That is the exact box
// filter of the triangle's irradiance: the pixel-averaged value even where a fold
// squeezes the triangle thinner than a pixel, and the deposits of one triangle
// sum to its flux. The pixel's surface (the target's G-buffer) must be a receiver
// on the triangle's plane with a normal agreeing with it, as for the splats.
uniform sampler2D targetPosition; // xyz world, w = material (-1: no surface)
uniform sampler2D targetNormal;   // xyz normal as modelled, w = role
uniform float normalTolerance;    // minimum cosine between the two normals

flat in vec2 cornerPixels[3];
flat in vec3 planePoint;
flat in vec3 planeNormal;
flat in float planeReach;
flat in vec3 fluxPerPixel;
flat in float halfSet;

layout(location = 0) out vec4 outIrradiance;

// Area of the triangle (a, b, c) inside the unit square [0, 1]^2 (Sutherland-Hodgman).
float AreaInUnitSquare(vec2 a, vec2 b, vec2 c)
{
  vec2 polygon[9];
  polygon[0] = a;
  polygon[1] = b;
  polygon[2] = c;
  int count = 3;
  for (int side = 0; side < 4 && count > 0; ++side)
  {
    int axis = side / 2;
    float sense = side % 2 == 0 ? 1.0 : -1.0; // keep x >= 0, then x <= 1, ...
    float bound = side % 2 == 0 ? 0.0 : 1.0;
    vec2 clipped[9];
    int kept = 0;
    for (int i = 0; i < count; ++i)
    {
      vec2 p = polygon[i];
      vec2 q = polygon[(i + 1) % count];
      float dp = sense * (p[axis] - bound), dq = sense * (q[axis] - bound);
      if (dp >= 0.0)
      {
        clipped[kept++] = p;
      }
      if ((dp >= 0.0) != (dq >= 0.0))
      {
        clipped[kept++] = mix(p, q, dp / (dp - dq));
      }
    }
    for (int i = 0; i < kept; ++i)
    {
      polygon[i] = clipped[i];
    }
    count = kept;
  }
  float twice = 0.0;
  for (int i = 0; i < count; ++i)
  {
    vec2 p = polygon[i], q = polygon[(i + 1) % count];
    twice += p.x * q.y - p.y * q.x;
  }
  return 0.5 * abs(twice);
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position = texelFetch(targetPosition, pixel, 0);
  vec4 normalRole = texelFetch(targetNormal, pixel, 0);
  if (position.w < 0.0 || int(normalRole.w + 0.5) != ROLE_RECEIVER ||
    dot(normalRole.xyz, planeNormal) < normalTolerance ||
    abs(dot(position.xyz - planePoint, planeNormal)) > planeReach)
  {
    discard;
  }
  vec2 low = vec2(pixel);
  float covered =
    AreaInUnitSquare(cornerPixels[0] - low, cornerPixels[1] - low, cornerPixels[2] - low);
  if (!(covered > 0.0))
  {
    discard;
  }
  outIrradiance = CausticsDeposit(fluxPerPixel * covered, halfSet);
}
