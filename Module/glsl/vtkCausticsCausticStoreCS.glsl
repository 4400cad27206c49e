// The caustic store's fill (vtkCausticsDistanceImpostors::StoreCaustic), the shared
// stage of every photon technique: one thread per slot of one light's landed photon
// grid (the photon record layout, vtkCausticsPhotonGrid.h) and per texel of that
// light's view, after the technique's transport:
// 1. a landed photon (position w > 0) adds its flux to the environment-map texel
//    that shows the receiver where it landed (ImpostorDepositCaustic);
// 2. a texel of the light's view whose first surface is specular takes its flux
//    (the shared emitter's light, continued along the light's ray past that
//    surface) off the texel where it would have landed without the specular
//    object: the object's shadow.
// The camera view then shades a receiver it sees only in a mirror or through glass
// (ImpostorCausticIrradiance) with its caustic and its shadow (E-S-D-S-L paths).
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D landedPosition; // xyz m; w: path length, > 0 for a landed photon
uniform sampler2D landedFlux;     // rgb W
uniform ivec2 landedGrid;         // the landed grid's size
uniform sampler2D lightPosition;  // the light's G-buffer: the first surface (w < 0: none)
uniform sampler2D lightNormal;    // w = role of the first surface
uniform sampler2D lightFlux;      // rgb: W through the texel
uniform int lightResolution;      // texels per side of the light's view
uniform int lightType;            // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;         // point and spot lights
uniform vec3 lightAxis;
uniform vec3 boundsMin; // the scene's box (m): searches stay inside it
uniform vec3 boundsMax;
uniform float tolerance; // m: a search starts this far from its surface

// 2. The light that texel `t` of the light's view would have brought past the
// specular surface it meets, taken off where it would have landed.
void DepositShadow(ivec2 t)
{
  vec4 first = texelFetch(lightPosition, t, 0);
  int role = int(texelFetch(lightNormal, t, 0).w + 0.5);
  if (first.w < 0.0 || (role != ROLE_REFLECTOR && role != ROLE_REFRACTOR))
  {
    return;
  }
  vec3 d = lightType == 0 ? normalize(lightAxis) : normalize(first.xyz - lightOrigin);
  float t1;
  ivec3 texel;
  int map = role == ROLE_REFLECTOR ? IMPOSTOR_REFLECTOR_ENVIRONMENT : IMPOSTOR_REFRACTOR_ENVIRONMENT;
  if (ImpostorSearch(map, first.xyz, d, boundsMin, boundsMax, tolerance, t1, texel) &&
    int(texelFetch(impostorNormal, texel, 0).w + 0.5) == ROLE_RECEIVER)
  {
    ImpostorDepositCaustic(first.xyz + t1 * d, -texelFetch(lightFlux, t, 0).rgb);
  }
}

void main()
{
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (all(lessThan(g, landedGrid)))
  {
    vec4 p = texelFetch(landedPosition, g, 0);
    vec3 flux = texelFetch(landedFlux, g, 0).rgb;
    if (p.w > 0.0 && AllFinite(p.xyz) && AllFinite(flux))
    {
      ImpostorDepositCaustic(p.xyz, flux);
    }
  }
  if (all(lessThan(g, ivec2(lightResolution))))
  {
    DepositShadow(g);
  }
}
