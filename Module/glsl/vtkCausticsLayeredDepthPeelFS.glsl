// Depth peeling (000_54cf099eeccf42d9.txt §2.2, after Everitt 2001): layer k keeps,
// per pixel, the nearest fragment strictly behind layer k - 1, and stores its
// world position + material index, normal + role and window depth.
in vec3 worldPosition;
in vec3 worldNormal;
flat in uint materialIndex;

uniform sampler2D previousDepth; // window depth of layer k - 1
uniform int firstLayer;          // 1 for layer 0: nothing to peel away

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out float outDepth;

void main()
{
  if (firstLayer == 0 && gl_FragCoord.z <= texelFetch(previousDepth, ivec2(gl_FragCoord.xy), 0).r)
  {
    discard;
  }
  CausticsMaterial material = causticsMaterials[materialIndex];
  vec3 n = worldNormal;
  float length2 = dot(n, n);
  // As the G-buffer: a vanishing interpolated normal falls back to the face normal.
  if (!(length2 > 1e-12))
  {
    n = cross(dFdx(worldPosition), dFdy(worldPosition));
    length2 = dot(n, n);
  }
  n = length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
  outPosition = vec4(worldPosition, float(materialIndex));
  outNormal = vec4(n, material.albedoRole.a);
  outDepth = gl_FragCoord.z;
}
