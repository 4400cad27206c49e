// G-buffer: world position + material index, normal + role, albedo + IOR.
// Clear values (set by vtkCausticsGBuffer) mark pixels without a surface:
// position.w = -1.
in vec3 worldPosition;
in vec3 worldNormal;
flat in uint materialIndex;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;

void main()
{
  CausticsMaterial material = causticsMaterials[materialIndex];
  vec3 n = worldNormal;
  float length2 = dot(n, n);
  // Interpolated normals can vanish between opposite vertex normals; fall back
  // to the face normal from screen-space derivatives.
  if (!(length2 > 1e-12))
  {
    n = cross(dFdx(worldPosition), dFdy(worldPosition));
    length2 = dot(n, n);
  }
  n = length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
  outPosition = vec4(worldPosition, float(materialIndex));
  outNormal = vec4(n, material.albedoRole.a);
  outAlbedo = vec4(material.albedoRole.rgb, material.params.x);
}
