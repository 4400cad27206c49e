// Radiance of the distance impostors' texels (vtkCausticsDistanceImpostors), for hits
// the camera does not see: a receiver's albedo x the direct irradiance of one light
// (W/m^2, physical falloff: 1/r^2 and glTF's spot cone), on the side facing the map's
// reference point, in VTK's display units (albedo x E, as the composite adds
// caustics); one dispatch per light, each adding to the last (accumulate). With the
// light's shadow map (shadowed), the light the scene blocks is left out, specular
// objects included: the light they pass on comes as caustic photons (the caustic
// store). Without it, no shadows: the store then takes the specular objects' shadow
// off itself. Other roles (mirrors, glass) get 0: the search continues through them.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

uniform sampler2DArray impostorPosition;
uniform sampler2DArray impostorNormal;
uniform vec3 impostorCentre[4]; // vtkCausticsDistanceImpostors::NUMBER_OF_MAPS
layout(rgba32f, binding = 0) uniform image2DArray impostorRadiance;

uniform int accumulate; // 1: add to what the texel holds (a light after the first)
uniform int lightOn;    // 0: no light, the texels are cleared
uniform int lightType;  // 0 directional, 1 point, 2 spot
uniform vec3 lightOrigin;    // point/spot: the light; directional: its view's eye
uniform vec3 lightDirection; // the way the light travels
uniform vec3 lightRadiometric; // W/m^2 (directional) or W/sr
uniform float lightCosOuter;
uniform float lightCosInner;
uniform int shadowed; // 1: the shadow map below is the light's
uniform sampler2D shadowPosition; // the light's view of the scene (vtkCausticsLightBuffers)
uniform sampler2D shadowNormal;
uniform mat4 lightWorldToClip;
uniform float texelWorldSize; // a shadow texel at unit distance (point) or absolute (sun)

// The light's irradiance at p, normal n, as the direct irradiance stage has it.
vec3 DirectIrradiance(vec3 p, vec3 n)
{
  vec3 toLight = -lightDirection;
  float falloff = 1.0;
  if (lightType != 0)
  {
    vec3 d = lightOrigin - p;
    float distance2 = max(dot(d, d), 1e-20);
    toLight = d * inversesqrt(distance2);
    falloff =
      (lightType == 2
          ? CausticsSpotFactor(dot(-toLight, lightDirection), lightCosOuter, lightCosInner)
          : 1.0) /
      distance2;
  }
  float cosine = dot(n, toLight);
  if (!(cosine > 0.0) || !(falloff > 0.0))
  {
    return vec3(0.0);
  }
  float visibility = 1.0;
  if (shadowed != 0)
  {
    float distance = CausticsLightDistance(p, lightType, lightOrigin, lightDirection);
    float bias = CausticsSurfaceShadowBias(texelWorldSize, lightType, distance, cosine);
    float specular;
    visibility = CausticsShadowVisibility(shadowPosition, shadowNormal,
      lightWorldToClip * vec4(p, 1.0), distance, bias, bias, lightType, lightOrigin,
      lightDirection, p, n, specular);
  }
  return lightRadiometric * (cosine * falloff * visibility);
}

void main()
{
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  ivec3 size = textureSize(impostorPosition, 0);
  if (any(greaterThanEqual(texel, size)))
  {
    return;
  }
  vec4 position = texelFetch(impostorPosition, texel, 0);
  vec4 normalRole = texelFetch(impostorNormal, texel, 0);
  vec3 radiance = accumulate != 0 ? imageLoad(impostorRadiance, texel).rgb : vec3(0.0);
  if (lightOn != 0 && position.w >= 0.0 && int(normalRole.w + 0.5) == ROLE_RECEIVER)
  {
    vec3 p = position.xyz;
    vec3 n = normalize(normalRole.xyz);
    n = dot(n, impostorCentre[texel.z / 6] - p) < 0.0 ? -n : n;
    radiance +=
      causticsMaterials[int(position.w + 0.5)].albedoRole.rgb * DirectIrradiance(p, n);
  }
  imageStore(impostorRadiance, texel, vec4(radiance, 1.0));
}
