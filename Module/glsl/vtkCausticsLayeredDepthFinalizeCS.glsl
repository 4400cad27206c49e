// Turns the depth complexities into the number of layers to peel per object
// (capped) and gates the indirect peel and clear commands of every layer: a layer
// beyond its object's depth complexity draws nothing. Runs on the GPU so that
// nothing is read back (vtkCausticsLayeredDepth).
layout(local_size_x = 64) in;

SSP_LDI_TABLE();
// Per peel command: object | layer << 16.
layout(std430, binding = CAUSTICS_LDI_COMMAND_INFO_BINDING) readonly buffer SspCommandInfo
{
  uint commandInfo[];
};
// DrawElementsIndirectCommand: count, instanceCount, firstIndex, baseVertex, baseInstance.
layout(std430, binding = CAUSTICS_LDI_DRAW_COMMAND_BINDING) buffer SspDrawCommands
{
  uint drawCommands[];
};
// DrawArraysIndirectCommand per (object, layer): count, instanceCount, first, baseInstance.
layout(std430, binding = CAUSTICS_LDI_CLEAR_COMMAND_BINDING) buffer SspClearCommands
{
  uint clearCommands[];
};

uniform int objectCount;
uniform int maxLayers;
uniform int commandCount;

void main()
{
  uint local = gl_LocalInvocationIndex;
  if (local == 0u)
  {
    uint complexity = 0u;
    for (int object = 0; object < objectCount; ++object)
    {
      uint count = ldiObjects[object].z;
      complexity = max(complexity, count);
      ldiObjects[object].x = uint(object * maxLayers);
      ldiObjects[object].y = min(count, uint(maxLayers));
    }
    ldiHeader =
      uvec4(uint(objectCount), uint(maxLayers), complexity, uint(objectCount * maxLayers));
  }
  memoryBarrierBuffer();
  barrier();
  for (int i = int(local); i < commandCount; i += 64)
  {
    uint info = commandInfo[i];
    uint object = info & 0xffffu;
    uint layer = info >> 16;
    drawCommands[5 * i + 1] = layer < ldiObjects[object].y ? 1u : 0u;
  }
  for (int i = int(local); i < objectCount * maxLayers; i += 64)
  {
    uint object = uint(i / maxLayers);
    uint layer = uint(i % maxLayers);
    clearCommands[4 * i + 1] = layer < ldiObjects[object].y ? 1u : 0u;
  }
}
