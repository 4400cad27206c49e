// Photon statistics of a trace (the STAT_* words below; the host reads them with
// caustics::hcm::ReadPhotonStatistics): counts, and fluxes as
// 64-bit fixed point in units of `fluxUnit` W, low word first, so that integer atomics
// add them on every GPU (float atomics are an NVIDIA extension).
// Used by the caustic maps' photon buffer, the cascaded trace and the screen-space
// transfer. The words (caustics::hcm::Stat* mirror them on the host; the draw words
// are the caustic maps'):
#define STAT_PHOTONS 0
#define STAT_HITS 1
#define STAT_LOST_INSIDE 2
#define STAT_ESCAPED 3
#define STAT_FLUX_IN 4
#define STAT_FLUX_HITS 6
#define STAT_FLUX_LOST_INSIDE 8
#define STAT_FLUX_ESCAPED 10
#define STAT_FLUX_INTERNAL_REFLECTION 12
#define STAT_FLUX_ABSORBED 14
#define STAT_HIDDEN_HITS 16 // of STAT_HITS, on the hidden receivers' layer
#define STAT_HIDDEN_DRAW 17 // the hidden map's final-render draw: 3, 1 if any such hit, 0, 0
#define STAT_STORED 21      // photons no receiver layer lands, taken by the caustic store
#define STAT_FLUX_STORED 22
#define STAT_STORE_DRAW 24 // the caustic store's final-render draw: 3, 1 if worth it (phase 3), 0, 0
#define STAT_SIZE 28

uniform float fluxUnit; // W per statistics unit

layout(std430, binding = CAUSTICS_PHOTON_STATISTICS_BINDING) buffer PhotonStatistics
{
  uint statistics[];
};

// Adds a flux (W) to the 64-bit fixed-point counter at `slot`, rounded to the unit.
void AddFlux(int slot, float watts)
{
  CAUSTICS_ADD_FIXED_POINT(statistics, slot, watts, fluxUnit)
}

// The counter at `slot` in units (float: for comparisons on the GPU).
float CounterFlux(int slot)
{
  return float(statistics[slot]) + 4294967296.0 * float(statistics[slot + 1]);
}
