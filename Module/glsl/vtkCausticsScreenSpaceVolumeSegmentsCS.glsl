// The traced photon segments of one bounce, handed to the line-based volume caustics
// (vtkCausticsVolumeLines) in their neutral layout: one thread per ray (the tracer's
// indirect dispatch). A ray inside a refractor (origin.w 2: no medium there), without
// a line, or whose line ends before it starts draws nothing; else its line from where
// it starts (clipped to the scene's bounds and the view) to its first hit or where it
// leaves, with the ray's flux.
layout(local_size_x = 64) in;

layout(std430, binding = CAUSTICS_SSP_ARGUMENT_BINDING) readonly buffer SspArguments
{
  uint arguments[]; // word 3: the ray count (vtkCausticsScreenSpaceLineTracerPrepareCS)
};
SSP_RAYS(readonly);
SSP_PAYLOADS(readonly);
SSP_LINES(readonly);
SSP_HITS(readonly);
CAUSTICS_VOLUME_SEGMENTS(writeonly);

void main()
{
  uint ray = gl_GlobalInvocationID.x;
  if (ray >= arguments[3])
  {
    return;
  }
  SspLine line = lines[ray];
  SspRay r = rays[ray];
  float t0 = line.start.w;
  float t1 = line.end.w;
  float hit = hits[ray].position.w;
  if (hit >= 0.0)
  {
    t1 = min(t1, hit);
  }
  if (!(line.info.x > 0.0))
  {
    t1 = t0; // nothing to draw
  }
  // Inside a refractor, direction.w is the material of the surface the photon last
  // entered or reflected in (its absorption: vtkCausticsScreenSpacePhotonPassTransferCS).
  bool inside = r.origin.w > 1.5;
  int absorber = inside && r.direction.w >= 0.0 ? int(r.direction.w + 0.5) : -1;
  volumeSegments[ray] = CausticsMakeVolumeSegment(
    r.origin.xyz, r.direction.xyz, t0, t1, payloads[ray].flux.rgb, inside, absorber);
}
