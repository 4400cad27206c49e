// Direct irradiance (W/m^2) of one light at each camera pixel's visible receiver,
// accumulated over lights with additive blending. Visibility comes from the
// light's shadow map (world positions seen from the light, aimed at the whole
// scene): a point is lit when no surface lies between it and the light, tested
// with 2x2 bilinear percentage-closer filtering and a bias of about two texels,
// attenuated by the participating medium, if any.
//
// Its second output is the part of VTK's own diffuse shading (vtkLight's falloff)
// that does not arrive: blocked by reflectors and refractors (specularShadows: the
// light they pass on is the caustic) or taken by the medium on the way from the
// light. The composite takes that much of VTK's colour away.
in vec2 texCoord;

uniform sampler2D gPosition; // camera G-buffer: world position, w = material (-1: none)
uniform sampler2D gNormal;   // world normal, w = role
uniform sampler2D shadowPosition; // light view: world position, w = material (-1: none)
uniform sampler2D shadowNormal;   // light view: world normal, w = role
uniform mat4 lightWorldToClip;
uniform vec3 cameraPosition;
uniform int cameraParallel;
uniform vec3 cameraDirection;

uniform int lightType; // 0 directional, 1 point, 2 spot
uniform vec3 lightPosition;
uniform vec3 lightDirection;
uniform vec3 radiometric;
uniform float cosOuter;
uniform float cosInner;
uniform float texelWorldSize; // size of a shadow texel at unit distance (persp) or absolute (ortho)
// VTK's falloff of this light (Light.shadingAttenuation etc. in vtkCausticsSceneData.h).
uniform vec3 shadingAttenuation;
uniform float shadingExponent;
uniform float shadingConeAngle; // degrees
uniform int specularShadows;    // 1: reflectors and refractors shadow VTK's shading

layout(location = 0) out vec4 outIrradiance;
layout(location = 1) out vec4 outLostShading;

float SpotFactor(vec3 direction)
{
  return lightType != 2 ? 1.0 : CausticsSpotFactor(dot(direction, lightDirection), cosOuter, cosInner);
}

// VTK's Phong falloff (vtkOpenGLPolyDataMapper): 1 / (a0 + a1 d + a2 d^2) for
// positional lights, times cos^exponent inside a spot cone under 90 degrees.
float ShadingFalloff(vec3 p)
{
  if (lightType == 0)
  {
    return 1.0;
  }
  vec3 fromLight = p - lightPosition;
  float distance = length(fromLight);
  float denominator = dot(shadingAttenuation, vec3(1.0, distance, distance * distance));
  float falloff = denominator > 0.0 && denominator < 3.0e38 ? 1.0 / denominator : 0.0;
  if (shadingConeAngle < 90.0)
  {
    float coneDot = dot(fromLight / max(distance, 1e-30), lightDirection);
    falloff = coneDot >= cos(radians(shadingConeAngle))
      ? falloff * pow(max(coneDot, 0.0), shadingExponent)
      : 0.0;
  }
  return falloff;
}

void main()
{
  outIrradiance = vec4(0.0);
  outLostShading = vec4(0.0);
  vec4 position = texture(gPosition, texCoord);
  vec4 normalRole = texture(gNormal, texCoord);
  if (position.w < 0.0 || int(normalRole.w + 0.5) != ROLE_RECEIVER)
  {
    return;
  }
  vec3 p = position.xyz;
  vec3 n = normalRole.xyz;
  // The side the camera sees is the side whose irradiance counts.
  vec3 toCamera = cameraParallel != 0 ? -cameraDirection : cameraPosition - p;
  if (dot(n, toCamera) < 0.0)
  {
    n = -n;
  }
  vec3 toLight;
  float falloff = 1.0;
  if (lightType == 0)
  {
    toLight = -lightDirection;
  }
  else
  {
    vec3 d = lightPosition - p;
    float distance2 = max(dot(d, d), 1e-20);
    toLight = d * inversesqrt(distance2);
    falloff = SpotFactor(-toLight) / distance2;
  }
  float cosine = dot(n, toLight);
  float shading = ShadingFalloff(p);
  if (cosine <= 0.0 || (falloff <= 0.0 && shading <= 0.0))
  {
    return;
  }

  float distance = CausticsLightDistance(p, lightType, lightPosition, lightDirection);
  float bias = CausticsSurfaceShadowBias(texelWorldSize, lightType, distance, cosine);
  float specularShadow; // the part of the light that a reflector or refractor blocks
  float visibility = CausticsShadowVisibility(shadowPosition, shadowNormal,
    lightWorldToClip * vec4(p, 1.0), distance, bias, bias, lightType, lightPosition,
    lightDirection, p, n, specularShadow);
  // A medium attenuates the light on its way to the surface (inside its box; as
  // the reference's DirectIrradiance): to the light, or out of the box for a sun.
  vec3 transmitted = lightType == 0 ? CausticsMediumTransmittance(p, toLight, 0.0, 3.0e38)
                                    : CausticsMediumTransmittance(p, lightPosition - p, 0.0, 1.0);
  outIrradiance = vec4(radiometric * transmitted * (cosine * max(falloff, 0.0) * visibility), 1.0);
  float blocked = specularShadows != 0 ? specularShadow : 0.0;
  vec3 kept = (1.0 - blocked) * transmitted;
  outLostShading = vec4(radiometric * (cosine * shading) * (vec3(1.0) - kept), 1.0);
}
