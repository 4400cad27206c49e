// Radiance of the distance impostors' texels (vtkCausticsDistanceImpostors), for hits
// the camera does not see: a receiver's albedo x the direct irradiance of the
// scene's lights (W/m^2, physical falloff: 1/r^2 and glTF's spot cone), on the side
// facing the map's reference point, in VTK's display units (albedo x E, as the
// composite adds caustics). No shadows and no caustic: the maps hold no visibility
// of the lights. Other roles (mirrors, glass) get 0: the search continues through them.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

uniform sampler2DArray impostorPosition;
uniform sampler2DArray impostorNormal;
uniform vec3 impostorCentre[4]; // vtkCausticsDistanceImpostors::NUMBER_OF_MAPS
layout(rgba32f, binding = 0) uniform writeonly image2DArray impostorRadiance;

const int MAX_LIGHTS = 8;
uniform int lightCount;
uniform int lightType[MAX_LIGHTS]; // 0 directional, 1 point, 2 spot
uniform vec3 lightPosition[MAX_LIGHTS];
uniform vec3 lightDirection[MAX_LIGHTS]; // the way the light travels
uniform vec3 lightRadiometric[MAX_LIGHTS]; // W/m^2 (directional) or W/sr
uniform float lightCosOuter[MAX_LIGHTS];
uniform float lightCosInner[MAX_LIGHTS];

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
  vec3 radiance = vec3(0.0);
  if (position.w >= 0.0 && int(normalRole.w + 0.5) == ROLE_RECEIVER)
  {
    vec3 p = position.xyz;
    vec3 n = normalize(normalRole.xyz);
    n = dot(n, impostorCentre[texel.z / 6] - p) < 0.0 ? -n : n;
    vec3 irradiance = vec3(0.0);
    for (int i = 0; i < lightCount; ++i)
    {
      vec3 toLight = -lightDirection[i];
      float falloff = 1.0;
      if (lightType[i] != 0)
      {
        vec3 d = lightPosition[i] - p;
        float distance2 = max(dot(d, d), 1e-20);
        toLight = d * inversesqrt(distance2);
        falloff = (lightType[i] == 2
                      ? CausticsSpotFactor(dot(-toLight, lightDirection[i]), lightCosOuter[i],
                          lightCosInner[i])
                      : 1.0) /
          distance2;
      }
      irradiance += lightRadiometric[i] * max(dot(n, toLight), 0.0) * falloff;
    }
    radiance = causticsMaterials[int(position.w + 0.5)].albedoRole.rgb * irradiance;
  }
  imageStore(impostorRadiance, texel, vec4(radiance, 1.0));
}
