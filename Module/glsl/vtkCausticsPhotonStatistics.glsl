// Photon statistics of a trace (the STAT_* words of vtkCausticsPhotonBufferCommon.glsl;
// the host reads them with caustics::hcm::ReadPhotonStatistics): counts, and fluxes as
// 64-bit fixed point in units of `fluxUnit` W, low word first, so that integer atomics
// add them on every GPU (float atomics are an NVIDIA extension).
// Used by the caustic maps' photon buffer and the cascaded trace.

uniform float fluxUnit; // W per statistics unit

layout(std430, binding = CAUSTICS_PHOTON_STATISTICS_BINDING) buffer PhotonStatistics
{
  uint statistics[];
};

float Power(vec3 flux)
{
  return flux.r + flux.g + flux.b;
}

// Adds a flux (W) to the 64-bit fixed-point counter at `slot`, rounded to the unit.
void AddFlux(int slot, float watts)
{
  float units = floor(watts / fluxUnit + 0.5); // rounded: no bias over many photons
  if (units > 0.0 && !isinf(units))
  {
    uint high = uint(units / 4294967296.0);
    uint low = uint(units - float(high) * 4294967296.0);
    uint old = atomicAdd(statistics[slot], low);
    if (high > 0u || old + low < old)
    {
      atomicAdd(statistics[slot + 1], high + (old + low < old ? 1u : 0u));
    }
  }
}

// The counter at `slot` in units (float: for comparisons on the GPU).
float CounterFlux(int slot)
{
  return float(statistics[slot]) + 4294967296.0 * float(statistics[slot + 1]);
}
