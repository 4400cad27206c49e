// Caustic triangles, drawn (vtkCausticsPhotonTriangleCommon.glsl): six vertices per
// triangle of the photon grid, the two triangles of the screen rectangle that
// bounds its landed triangle in the target view (pixel-aligned, so every pixel it
// touches gets a fragment). Triangles the classification rejected collapse.
uniform usampler2D triangleMask; // bit t of a cell: its triangle t is valid
uniform mat4 clipToWorld;        // the target view's inverse

flat out vec2 cornerPixels[3]; // the landed triangle in target pixels
flat out vec3 planePoint;
flat out vec3 planeNormal;
flat out float planeReach;    // largest distance of a receiving point off its plane (m)
flat out vec3 fluxPerPixel;   // W per pixel of screen area it covers, per m^2 there
flat out float halfSet;       // CausticsHalfSet of its cell

uniform float planeTolerance; // in lengths of the triangle's longest edge

void Collapse()
{
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume
  fluxPerPixel = vec3(0.0);
}

// Where the target's ray through `pixel` meets the plane (c, n).
vec3 OnPlane(vec2 pixel, vec3 c, vec3 n)
{
  vec2 ndc = pixel / triangleViewport * 2.0 - 1.0;
  vec4 near = clipToWorld * vec4(ndc, -1.0, 1.0);
  vec4 far = clipToWorld * vec4(ndc, 1.0, 1.0);
  vec3 origin = near.xyz / near.w;
  vec3 direction = far.xyz / far.w - origin;
  return origin + dot(c - origin, n) / dot(direction, n) * direction;
}

void main()
{
  int triangle = gl_VertexID / 6;
  int corner = gl_VertexID % 6;
  int t = triangle % 2;
  ivec2 cell = ivec2((triangle / 2) % hitGrid.x, (triangle / 2) / hitGrid.x);
  CausticTriangle tri;
  if ((texelFetch(triangleMask, cell, 0).r & (1u << uint(t))) == 0u ||
    !LoadCausticTriangle(cell, t, tri))
  {
    Collapse();
    return;
  }
  vec2 e1 = tri.pixel[1] - tri.pixel[0], e2 = tri.pixel[2] - tri.pixel[0];
  float screenArea = 0.5 * abs(e1.x * e2.y - e1.y * e2.x); // pixels
  vec3 middle = (tri.p[0] + tri.p[1] + tri.p[2]) / 3.0;
  vec2 centre = (tri.pixel[0] + tri.pixel[1] + tri.pixel[2]) / 3.0;
  // One pixel's area (m^2) on the triangle's plane, at its middle: a pixel's
  // irradiance is the flux landing in it over that area.
  vec3 stepX = OnPlane(centre + vec2(1.0, 0.0), middle, tri.normal) - OnPlane(centre, middle, tri.normal);
  vec3 stepY = OnPlane(centre + vec2(0.0, 1.0), middle, tri.normal) - OnPlane(centre, middle, tri.normal);
  float pixelArea = length(cross(stepX, stepY));
  if (!(pixelArea > 0.0) || isinf(pixelArea))
  {
    Collapse();
    return;
  }
  float longest = max(max(distance(tri.p[0], tri.p[1]), distance(tri.p[1], tri.p[2])),
    distance(tri.p[2], tri.p[0]));
  cornerPixels = tri.pixel;
  planePoint = middle;
  planeNormal = tri.normal;
  planeReach = planeTolerance * longest;
  fluxPerPixel = tri.flux / (screenArea * pixelArea);
  halfSet = CausticsHalfSet(uint(triangle / 2));
  // The pixel-aligned rectangle around it, within the viewport.
  vec2 low = clamp(floor(min(min(tri.pixel[0], tri.pixel[1]), tri.pixel[2])), vec2(0.0), triangleViewport);
  vec2 high = clamp(ceil(max(max(tri.pixel[0], tri.pixel[1]), tri.pixel[2])), vec2(0.0), triangleViewport);
  vec2 pixel = mix(low, high, vec2(CAUSTICS_TRIANGLE_CORNERS[corner]));
  gl_Position = vec4(pixel / triangleViewport * 2.0 - 1.0, 0.0, 1.0);
}
