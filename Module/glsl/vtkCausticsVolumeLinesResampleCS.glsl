// Re-sampling of the photon segments (003 §5.2, vtkCausticsVolumeLines step 2a): one
// thread per segment integrates the optical depth along its photon from the origin to
// the start of the drawn part, then piece after piece, and stores it at every vertex;
// so the density is marched once per segment (a homogeneous medium: closed form),
// never per fragment. Thread 0 writes the indirect draw of the segments' lines.
layout(local_size_x = 64) in;

CAUSTICS_VOLUME_SEGMENTS(readonly);
CAUSTICS_VOLUME_DEPTHS(writeonly);
layout(std430, binding = CAUSTICS_VOLUME_COUNT_BINDING) readonly buffer CausticsVolumeCount
{
  uint countWords[];
};
layout(std430, binding = CAUSTICS_VOLUME_ARGUMENT_BINDING) writeonly buffer CausticsVolumeDraw
{
  uint drawArguments[4];
};

uniform int capacity;
uniform int countWord;
uniform int pieces;

// Optical depth of the medium's box along o + t d, t in [t0, t1].
float OpticalDepth(vec3 o, vec3 d, float t0, float t1)
{
  if (causticsMediumOn == 0 || !(t1 > t0) ||
    !CausticsClipToBox(o, d, causticsMediumLow, causticsMediumHigh, t0, t1))
  {
    return 0.0;
  }
#ifdef CAUSTICS_MEDIUM_GRID
  return CausticsMediumOpticalDepth(o, d, t0, t1);
#else
  return t1 - t0;
#endif
}

void main()
{
  uint count = min(countWords[countWord], uint(capacity));
  uint i = gl_GlobalInvocationID.x;
  if (i == 0u)
  {
    drawArguments[0] = 2u * count;
    drawArguments[1] = 1u;
    drawArguments[2] = 0u;
    drawArguments[3] = 0u;
  }
  if (i >= count)
  {
    return;
  }
  CausticsVolumeSegment s = volumeSegments[i];
  uint base = i * uint(pieces + 1);
  if (!(s.direction.w > s.origin.w))
  {
    return; // the vertex shader draws nothing for it
  }
  vec3 o = s.origin.xyz;
  vec3 d = s.direction.xyz;
  float depth = OpticalDepth(o, d, 0.0, s.origin.w);
  volumeDepths[base] = depth;
  for (int k = 0; k < pieces; ++k)
  {
    vec2 t = CausticsVolumePiece(s, k, pieces);
    depth += OpticalDepth(o, d, t.x, t.y);
    volumeDepths[base + uint(k + 1)] = depth;
  }
}
