// Line-based volume caustics (vtkCausticsVolumeLines, 003_653219b45420e98f.txt §4-5):
// the neutral layout in which any technique hands its photon segments to the stage,
// and the stage's own buffers. Binding points in vtkCausticsBindings.h.

// One photon segment after a specular event, in air (the medium): the photon leaves
// origin.xyz (m) along direction.xyz (unit) carrying flux.rgb (W) at the origin; the
// part [t0, t1] (m along the direction) is drawn: origin.w = t0, direction.w = t1
// (t1 <= t0: nothing). The light-side extinction from the origin is the stage's, and
// so is the Beer-Lambert absorption of the refractor a piece lies in when the medium
// fills the refractors: flux.w = 1 + that refractor's material index (0: none).
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

// A photon's straight piece after a specular event: it leaves `origin` along the unit
// `direction` with `flux` (W); [t0, t1] is drawn. A piece inside a refractor (or under
// an open sheet of water) draws nothing unless the medium fills the refractors
// (CausticsStretchInMedium, as in the reference renderer). `absorber`: the material
// index of the closed refractor the piece lies in, whose own absorption the stage
// applies along it (-1: none, or not followed: an open sheet's water).
CausticsVolumeSegment CausticsMakeVolumeSegment(vec3 origin, vec3 direction, float t0,
  float t1, vec3 flux, bool insideRefractor, int absorber)
{
  CausticsVolumeSegment s;
  s.origin = vec4(origin, t0);
  s.direction =
    vec4(direction, !CausticsStretchInMedium(insideRefractor) || !(t1 > t0) ? t0 : t1);
  s.flux = vec4(flux, insideRefractor && absorber >= 0 ? float(absorber + 1) : 0.0);
  return s;
}

// The same piece cut to the medium's box (causticsMediumLow/High of
// vtkCausticsCommon.glsl: the scene's bounds, or a density grid's within them), for a
// tracer whose pieces run from surface to surface: [0, length] of origin + t direction.
CausticsVolumeSegment CausticsMakeMediumSegment(
  vec3 origin, vec3 direction, float length, vec3 flux, bool insideRefractor, int absorber)
{
  float t0 = 0.0, t1 = length;
  if (causticsMediumOn == 0 ||
    !CausticsClipToBox(origin, direction, causticsMediumLow, causticsMediumHigh, t0, t1))
  {
    t1 = t0;
  }
  return CausticsMakeVolumeSegment(origin, direction, t0, t1, flux, insideRefractor, absorber);
}

#ifdef CAUSTICS_VOLUME_SEGMENT_APPEND
// A tracer's pieces, appended (vtkCausticsVolumeSegmentList binds the two buffers):
// the records, and the count (word 0, which may exceed the capacity: the stage reads
// min(count, capacity)). Empty pieces and pieces without flux are not appended.
layout(std430, binding = CAUSTICS_VOLUME_APPEND_SEGMENT_BINDING) writeonly buffer
  CausticsVolumeAppendSegments
{
  CausticsVolumeSegment appendedVolumeSegments[];
};
layout(std430, binding = CAUSTICS_VOLUME_APPEND_COUNT_BINDING) buffer CausticsVolumeAppendCount
{
  uint appendedVolumeSegmentCount;
};
uniform uint volumeSegmentCapacity;

void CausticsAppendVolumeSegment(CausticsVolumeSegment s)
{
  if (!(s.direction.w > s.origin.w) || !(s.flux.r + s.flux.g + s.flux.b > 0.0))
  {
    return;
  }
  uint slot = atomicAdd(appendedVolumeSegmentCount, 1u);
  if (slot < volumeSegmentCapacity)
  {
    appendedVolumeSegments[slot] = s;
  }
}
#else
// Without a scattering medium the tracers write nothing (the calls compile away).
void CausticsAppendVolumeSegment(CausticsVolumeSegment s)
{
}
#endif

// A photon's straight stretch of `length` m from `origin` along the unit `direction`,
// carrying `flux` (W) at its start, that a tracer follows from surface to surface:
// handed to the volume caustics, and the flux it keeps at the stretch's end after the
// medium's extinction, when the stretch lies in the medium (CausticsStretchInMedium:
// in air, or inside a refractor when the medium fills the refractors). A refractor's own
// Beer-Lambert absorption is the caller's; `absorber` names that refractor's material
// for the stage (CausticsMakeVolumeSegment).
vec3 CausticsMediumStretch(
  vec3 origin, vec3 direction, float length, vec3 flux, bool insideRefractor, int absorber)
{
  CausticsAppendVolumeSegment(
    CausticsMakeMediumSegment(origin, direction, length, flux, insideRefractor, absorber));
  return CausticsStretchInMedium(insideRefractor)
    ? flux * CausticsMediumTransmittance(origin, direction, 0.0, length)
    : flux;
}

// The drawn part of segment's piece k of n: t at its two ends (the same split as the
// fragments' in vtkCausticsVolumeLinesFS.glsl).
vec2 CausticsVolumePiece(CausticsVolumeSegment s, int k, int n)
{
  float h = (s.direction.w - s.origin.w) / float(n);
  return vec2(s.origin.w + float(k) * h, k + 1 == n ? s.direction.w : s.origin.w + float(k + 1) * h);
}
