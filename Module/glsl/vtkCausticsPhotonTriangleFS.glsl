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
  vec2 corners[9];
  for (int k = 0; k < 3; ++k)
  {
    corners[k] = cornerPixels[k] - low;
  }
  float covered = CausticsAreaInUnitSquare(corners, 3);
  if (!(covered > 0.0))
  {
    discard;
  }
  outIrradiance = CausticsDeposit(fluxPerPixel * covered, halfSet);
}
