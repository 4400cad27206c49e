// Depth complexity count (000_54cf099eeccf42d9.txt §2.2): every fragment of the
// scene adds one to its pixel's counter in its object's slice. No depth test,
// no colour output: the counts are exactly the layers peeling would find.
in vec3 worldPosition;
in vec3 worldNormal;
flat in uint materialIndex;

layout(std430, binding = CAUSTICS_LDI_OBJECT_MAP_BINDING) readonly buffer SspObjectMap
{
  uint objectOfMaterial[];
};
layout(r32ui, binding = 0) uniform coherent uimage2DArray complexity;

void main()
{
  imageAtomicAdd(
    complexity, ivec3(ivec2(gl_FragCoord.xy), int(objectOfMaterial[materialIndex])), 1u);
}
