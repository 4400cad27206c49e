// The first transfer map (000_54cf099eeccf42d9.txt §2): the photons that
// vtkCausticsPhotonEmitter left after their first specular interaction, appended
// to a compact list (only texels holding a photon), with the medium's extinction
// along the way from the light into the scene. It counts the photons and their light.
layout(local_size_x = 16, local_size_y = 16) in;

SSP_NEXT_RAYS(writeonly);
SSP_NEXT_PAYLOADS(writeonly);
SSP_NEXT_COUNTER();

uniform sampler2D emitPosition;  // xyz, w = state (0: no photon)
uniform sampler2D emitDirection; // xyz unit, w = the texel's measure (m^2 or sr)
uniform sampler2D emitFlux;      // rgb W, a = specular events (1)
uniform sampler2D lightPosition; // light G-buffer: w = material index of the first hit
uniform ivec2 grid;              // emitter grid: N x N or N x 2N
uniform int resolution;          // N
uniform int lightType;           // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;
uniform vec3 lightDirection;
uniform vec3 viewEye; // a point of the light view's eye plane (directional lights)

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, grid)))
  {
    return;
  }
  vec4 position = texelFetch(emitPosition, texel, 0);
  vec4 flux = texelFetch(emitFlux, texel, 0);
  if (!(position.w > 0.0) || !(dot(flux.rgb, vec3(1.0)) > 0.0))
  {
    return;
  }
  vec3 p = position.xyz;
  // Where its light goes is counted from here (vtkCausticsPhotonStatistics.glsl).
  atomicAdd(statistics[STAT_PHOTONS], 1u);
  AddFlux(STAT_FLUX_IN, CausticsChannelSum(flux.rgb));
  // The medium's extinction from where the light ray enters it (or from a point
  // light inside it) to the first surface.
  vec3 incoming = lightType == 0 ? lightDirection : normalize(p - lightOrigin);
  flux.rgb *= CausticsMediumTransmittance(
    p, -incoming, 0.0, lightType == 0 ? 3.0e38 : distance(p, lightOrigin));
  float material = texelFetch(lightPosition, ivec2(texel.x, texel.y % resolution), 0).w;
  uint index = atomicAdd(nextCount, 1u);
  nextRays[index].origin = position;
  vec4 direction = texelFetch(emitDirection, texel, 0);
  nextRays[index].direction = vec4(direction.xyz, material);
  nextPayloads[index].flux = vec4(flux.rgb, 1.0);
  // Its id is its texel: splats find their neighbours in the grid by it. Its path
  // so far runs from the light (a directional light's view's eye plane).
  float path = lightType == 0 ? dot(p - viewEye, lightDirection) : distance(p, lightOrigin);
  nextPayloads[index].info = uvec4(
    uint(texel.y * grid.x + texel.x), floatBitsToUint(path), floatBitsToUint(direction.w), 0u);
}
