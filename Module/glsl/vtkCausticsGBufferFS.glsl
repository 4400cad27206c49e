// G-buffer: world position + material index, normal + role, albedo + IOR.
// Clear values (set by vtkCausticsGBuffer) mark pixels without a surface:
// position.w = -1.
in vec3 worldPosition;
in vec3 worldNormal;
flat in uint materialIndex;

// A second layer (vtkCausticsGBuffer::SetPeelBehind): only surfaces behind the
// front layer's, facing the view.
uniform bool peel;
uniform sampler2D peelFront;  // the front layer's positions (w < 0: no surface)
uniform vec4 peelViewOrigin;  // eye (w = 1) or direction of sight (w = 0)
uniform mat4 worldToClip;

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
  if (peel)
  {
    vec4 front = texelFetch(peelFront, ivec2(gl_FragCoord.xy), 0);
    if (front.w < 0.0)
    {
      discard; // no receiver at all along this ray
    }
    vec4 clip = worldToClip * vec4(front.xyz, 1.0);
    float frontDepth = clip.z / clip.w * 0.5 + 0.5;
    vec3 towardsView =
      peelViewOrigin.w > 0.5 ? peelViewOrigin.xyz - worldPosition : -peelViewOrigin.xyz;
    if (gl_FragCoord.z <= frontDepth + 1e-5 || dot(n, towardsView) <= 0.0)
    {
      discard;
    }
  }
  outPosition = vec4(worldPosition, float(materialIndex));
  outNormal = vec4(n, material.albedoRole.a);
  outAlbedo = vec4(material.albedoRole.rgb, material.params.x);
}
