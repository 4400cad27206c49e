// Line-based volume caustics (vtkCausticsVolumeLines, 003_653219b45420e98f.txt §4-5):
// the neutral layout in which any technique hands its photon segments to the stage,
// and the stage's own buffers. Binding points in vtkCausticsBindings.h.

// One photon segment after a specular event, in air (the medium): the photon leaves
// origin.xyz (m) along direction.xyz (unit) carrying flux.rgb (W) at the origin; the
// part [t0, t1] (m along the direction) is drawn: origin.w = t0, direction.w = t1
// (t1 <= t0: nothing). The light-side extinction from the origin is the stage's.
struct CausticsVolumeSegment
{
  vec4 origin;
  vec4 direction;
  vec4 flux;
};

#define CAUSTICS_VOLUME_SEGMENTS(access) layout(std430, binding = CAUSTICS_VOLUME_SEGMENT_BINDING) access buffer CausticsVolumeSegments { CausticsVolumeSegment volumeSegments[]; }
// The optical depth along each segment's photon from its origin (density x m with a
// grid, m without), at the subSegments + 1 vertices of its pieces.
#define CAUSTICS_VOLUME_DEPTHS(access) layout(std430, binding = CAUSTICS_VOLUME_DEPTH_BINDING) access buffer CausticsVolumeDepths { float volumeDepths[]; }

// The drawn part of segment's piece k of n: t at its two ends (the same split as the
// fragments' in vtkCausticsVolumeLinesFS.glsl).
vec2 CausticsVolumePiece(CausticsVolumeSegment s, int k, int n)
{
  float h = (s.direction.w - s.origin.w) / float(n);
  return vec2(s.origin.w + float(k) * h, k + 1 == n ? s.direction.w : s.origin.w + float(k + 1) * h);
}
