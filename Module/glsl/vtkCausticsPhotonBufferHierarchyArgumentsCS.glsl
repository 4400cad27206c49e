// Indirect dispatch arguments for one traversal level, from the length of its
// work list (written by the level above): enough 64-wide work groups, folded into
// two dimensions so that no dimension exceeds the 65535 groups GL guarantees.
layout(local_size_x = 1) in;

uniform int level;

layout(std430, binding = CAUSTICS_HIERARCHY_CONTROL_BINDING) buffer Control
{
  uint control[];
};

void main()
{
  uint groups = (control[CONTROL_LIST_COUNT + level] + 63u) / 64u;
  uint x = min(groups, 65535u);
  uint y = x > 0u ? (groups + x - 1u) / x : 0u;
  control[CONTROL_DISPATCH + 3 * level + 0] = x;
  control[CONTROL_DISPATCH + 3 * level + 1] = y;
  control[CONTROL_DISPATCH + 3 * level + 2] = 1u;
}
