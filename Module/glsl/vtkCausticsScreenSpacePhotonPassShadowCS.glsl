// Shadow rays in screen space (000_54cf099eeccf42d9.txt §5, Fig. 11): one ray per
// receiver pixel of the camera G-buffer, towards the light; the line tracer then
// finds whether anything lies between.
layout(local_size_x = 16, local_size_y = 16) in;

SSP_NEXT_RAYS(writeonly);

uniform sampler2D gPosition; // xyz, w = material (-1: none)
uniform sampler2D gNormal;   // w = role
uniform ivec2 size;
uniform int lightType;
uniform vec3 lightOrigin;
uniform vec3 lightDirection;

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size)))
  {
    return;
  }
  uint index = uint(pixel.y * size.x + pixel.x);
  vec4 position = texelFetch(gPosition, pixel, 0);
  int role = int(texelFetch(gNormal, pixel, 0).w + 0.5);
  SspRay ray;
  ray.origin = vec4(0.0);
  ray.direction = vec4(0.0, 0.0, 1.0, -1.0);
  if (position.w >= 0.0 && role == ROLE_RECEIVER)
  {
    vec3 toLight = lightType == 0 ? -lightDirection : normalize(lightOrigin - position.xyz);
    ray.origin = vec4(position.xyz, 1.0);
    ray.direction = vec4(toLight, position.w);
  }
  nextRays[index] = ray;
}
