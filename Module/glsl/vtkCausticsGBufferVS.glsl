// Surface attributes for the G-buffer (camera or light view).
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uint material;

uniform mat4 worldToClip;

out vec3 worldPosition;
out vec3 worldNormal;
flat out uint materialIndex;

void main()
{
  worldPosition = position;
  worldNormal = normal;
  materialIndex = material;
  gl_Position = worldToClip * vec4(position, 1.0);
}
