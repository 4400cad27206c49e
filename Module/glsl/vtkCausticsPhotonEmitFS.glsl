// First specular interaction of every light-buffer texel: the shared start of
// every photon technique (000_54cf099eeccf42d9.txt §2, 001_7c07a484f7a872bb.txt §2).
// Target: width N, height N (one branch) or 2N (rows N..2N-1 hold the reflected
// branch of refractors). Position.w: 0 no photon, 1 travelling in air, 2 inside a
// refractor.
uniform sampler2D lightPosition; // xyz world, w = material index (-1: nothing hit)
uniform sampler2D lightNormal;   // xyz normal as modelled, w = role
uniform sampler2D lightFlux;     // rgb W per texel, a = texel measure (m^2 or sr)
uniform int resolution;
uniform int splitFresnel;
uniform int lightType; // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;
uniform vec3 lightDirection;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outDirection;
layout(location = 2) out vec4 outFlux;

void NoPhoton()
{
  outPosition = vec4(0.0);
  outDirection = vec4(0.0);
  outFlux = vec4(0.0);
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  int branch = pixel.y >= resolution ? 1 : 0;
  ivec2 texel = ivec2(pixel.x, pixel.y - branch * resolution);
  vec4 position = texelFetch(lightPosition, texel, 0);
  vec4 normalRole = texelFetch(lightNormal, texel, 0);
  vec4 flux = texelFetch(lightFlux, texel, 0);
  int role = int(normalRole.w + 0.5);
  if (position.w < 0.0 || (role != ROLE_REFLECTOR && role != ROLE_REFRACTOR) ||
    (branch == 1 && role != ROLE_REFRACTOR) || dot(flux.rgb, vec3(1.0)) <= 0.0)
  {
    NoPhoton();
    return;
  }
  vec3 p = position.xyz;
  vec3 d = lightType == 0 ? lightDirection : normalize(p - lightOrigin);
  CausticsMaterial material = causticsMaterials[int(position.w + 0.5)];
  CausticsInteraction s = CausticsSurfaceInteraction(d, normalRole.xyz, material, role, 1.0);
  // Both Fresnel branches of a refractor are kept, one photon each: branch 0 the
  // refracted one, branch 1 the reflected one. A reflector has only branch 0.
  bool refracts = role == ROLE_REFRACTOR && branch == 0;
  if (refracts && !s.transmits)
  {
    NoPhoton(); // total internal reflection: all flux is in the reflected branch
    return;
  }
  // Inside the refractor after entering it, or after reflecting off its inside.
  bool inside = role == ROLE_REFRACTOR && refracts == s.entering;
  outPosition = vec4(p, inside ? 2.0 : 1.0);
  outDirection = vec4(refracts ? s.refracted : s.reflected, flux.a);
  outFlux = vec4(flux.rgb * (refracts ? s.refractedWeight : s.reflectedWeight), 1.0);
}
