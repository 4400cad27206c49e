// Indirect arguments of one trace, from the ray count on the GPU (no read-back):
// words 0-2 a dispatch over the rays (64 per group), 3 the count, 4-7 a draw of
// one line per ray; then per batch b at 8 + 8b: the draw of its rows' lines
// (4 words) and the dispatch of its row reduction (3 words; word 7 = its rows).
layout(local_size_x = 64) in;

SSP_COUNTER(readonly);
layout(std430, binding = CAUSTICS_SSP_ARGUMENT_BINDING) writeonly buffer SspArguments
{
  uint arguments[];
};

uniform int rowsPerBatch;
uniform int batches;
uniform int capacity;

void main()
{
  uint count = min(rayCount, uint(capacity));
  uint local = gl_LocalInvocationIndex;
  if (local == 0u)
  {
    arguments[0] = (count + 63u) / 64u;
    arguments[1] = 1u;
    arguments[2] = 1u;
    arguments[3] = count;
    arguments[4] = 2u * count;
    arguments[5] = 1u;
    arguments[6] = 0u;
    arguments[7] = 0u;
  }
  for (int b = int(local); b < batches; b += 64)
  {
    uint first = uint(b * rowsPerBatch);
    uint rows = count > first ? min(count - first, uint(rowsPerBatch)) : 0u;
    uint base = 8u + 8u * uint(b);
    arguments[base + 0u] = 2u * rows;
    arguments[base + 1u] = 1u;
    arguments[base + 2u] = 2u * first;
    arguments[base + 3u] = 0u;
    arguments[base + 4u] = (rows + 15u) / 16u; // 16 rows per reduction group
    arguments[base + 5u] = 1u;
    arguments[base + 6u] = 1u;
    arguments[base + 7u] = rows;
  }
}
