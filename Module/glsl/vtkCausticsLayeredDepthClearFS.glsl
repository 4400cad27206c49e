// Clears one layer of the layered depth image (drawn only for layers that will be
// peeled) and the peel's depth buffer: no surface, depth 1.
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out float outDepth;

void main()
{
  outPosition = vec4(0.0, 0.0, 0.0, -1.0);
  outNormal = vec4(0.0);
  outDepth = 1.0;
  gl_FragDepth = 1.0;
}
