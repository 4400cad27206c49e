/**
 * @file   vtkCausticsPhotonGrid.h
 * @brief  The photons of one light, as emission hands them to the later stages (not wrapped).
 *
 * vtkCausticsPhotonEmitter makes one photon per light-buffer texel after its first
 * specular interaction: a grid of N columns and N rows per emission branch, N the
 * light buffers' resolution (the pass's LightBufferResolution), with a second branch
 * of N rows when a refractor's Fresnel-reflected part is emitted separately. Grid
 * texel (x, y) is photon x + y * Width, which keeps neighbouring photons addressable
 * (the hierarchy's mipmap, the splat radii from the neighbours' spacing).
 *
 * Emission produces this value and every later stage takes it as an argument: the
 * photon buffer's trace, the hierarchy, the caustic map, the screen-space transfer
 * and the splatter (which splats one hit per texel of a grid of this layout).
 *
 * Photons are stored in one record layout, caustics::PhotonRecords: three RGBA32F
 * textures of the grid's size, texel (x, y) holding photon x + y * Width. What the
 * channels hold depends on the photon's state (the same table is in
 * glsl/vtkCausticsCommon.glsl, for the shaders):
 *
 * | plane     | emitted (after the first specular event)       | landed on a receiver |
 * |-----------|------------------------------------------------|----------------------------------------------|
 * | Position  | xyz m; w: 0 none, 1 leaving into air, 2 inside a refractor | xyz m; w: path length
 * from the light (m), > 0 | | Direction | xyz unit direction; w: the texel's measure     | xyz
 * receiver normal as modelled; w: abs(N.D) on arrival | | Flux      | rgb W; a: specular events so
 * far (1)           | rgb W; a: the texel's measure                |
 *
 * The measure is what one emission texel covers: m^2 across a directional light's
 * beam, sr from a point or spot light; with the path length and abs(N.D) it gives
 * the photon's unoccluded footprint on the receiver. A directional light's path
 * length is measured from its view's eye plane. Every transport (screen-space
 * transfer, caustic-map trace, straight photons) writes landed photons in this
 * layout and every reconstruction (splatter, caustic-map hierarchy and splats)
 * reads it; the kernel radius a reconstruction gives each photon is its own R32F
 * texture beside the records.
 */
#ifndef vtkCausticsPhotonGrid_h
#define vtkCausticsPhotonGrid_h

#include "vtkCausticsSceneData.h" // For caustics::Light, caustics::LightView

#include <algorithm> // For std::max
#include <cstddef>   // For std::size_t

class vtkTextureObject;

namespace caustics
{
/**
 * The three textures of one grid of photon records (see the file description for
 * their layout). A view: the stage that writes them owns them (caustics::gl::PhotonPlanes).
 */
struct PhotonRecords
{
  vtkTextureObject* Position = nullptr;
  vtkTextureObject* Direction = nullptr; ///< direction in flight, receiver normal once landed
  vtkTextureObject* Flux = nullptr;

  /** True when all three textures are set. */
  bool IsSet() const
  {
    return this->Position != nullptr && this->Direction != nullptr && this->Flux != nullptr;
  }
};

struct PhotonGrid
{
  int Light = -1;     ///< index of the emitting light in SceneData::Lights
  int LightType = 0;  ///< its caustics::Light::Type (0 directional: measures are m^2, else sr)
  int Width = 0;      ///< columns: N, the light buffers' texels per side
  int Height = 0;     ///< rows: N per emission branch (N, or 2N with the reflected branch)
  int BranchRows = 0; ///< N: rows of one branch (grid neighbours never cross a branch)
  /**
   * W summed over RGB: an upper bound of one photon's flux (the light's power through
   * the largest texel of its view). The GPU flux counters count in units of it.
   */
  double MaximumPhotonFlux = 1.0;
  /**
   * The emitted photons, owned by the emitter (see vtkCausticsPhotonEmitter): where
   * each leaves its first specular surface, its direction, its flux.
   */
  PhotonRecords Emitted;

  /** Photon slots (texels) of the grid; the valid photons are fewer. */
  std::size_t Count() const
  {
    return static_cast<std::size_t>(std::max(this->Width, 0)) *
      static_cast<std::size_t>(std::max(this->Height, 0));
  }
  /** True when the grid holds photon slots. */
  bool IsEmpty() const { return this->Width <= 0 || this->Height <= 0; }
};

/**
 * Where the light a trace's photons carried went: counts, and flux in W summed over
 * RGB (GPU counters, glsl/vtkCausticsPhotonStatistics.glsl). The caustic maps' photon
 * buffer and the cascaded trace keep them; vtkCausticsRenderPass::GetLastFramePhotonStatistics
 * sums them over the lights.
 */
struct PhotonStatistics
{
  long long Photons = 0;    ///< photons traced
  long long Hits = 0;       ///< photons that landed on a receiver (valid photons)
  long long HiddenHits = 0; ///< of them, on a hidden receiver (caustic maps)
  long long LostInside = 0; ///< lost: on paths the trace cannot follow to their end
  long long Escaped = 0;    ///< left the views the trace follows
  long long Stored = 0;     ///< no receiver layer landed it; the caustic store did
  double FluxIn = 0.0;      ///< carried by the photons traced
  double FluxHits = 0.0;
  double FluxLostInside = 0.0;
  double FluxEscaped = 0.0;
  double FluxStored = 0.0;
  double FluxInternalReflection = 0.0; ///< reflected back inside at exits, not followed
  double FluxAbsorbed = 0.0;           ///< Beer-Lambert inside refractors

  /**
   * FluxLostInside over the light that landed or was lost: the most of the caustic
   * the lost light could have been (part of it would have landed out of sight). 0
   * when nothing landed or was lost.
   */
  double LostShareBound() const
  {
    const double reached = this->FluxHits + this->FluxStored + this->FluxLostInside;
    return reached > 0.0 ? this->FluxLostInside / reached : 0.0;
  }
  /** Adds another light's statistics. */
  PhotonStatistics& operator+=(const PhotonStatistics& other)
  {
    this->Photons += other.Photons;
    this->Hits += other.Hits;
    this->HiddenHits += other.HiddenHits;
    this->LostInside += other.LostInside;
    this->Escaped += other.Escaped;
    this->Stored += other.Stored;
    this->FluxIn += other.FluxIn;
    this->FluxHits += other.FluxHits;
    this->FluxLostInside += other.FluxLostInside;
    this->FluxEscaped += other.FluxEscaped;
    this->FluxStored += other.FluxStored;
    this->FluxInternalReflection += other.FluxInternalReflection;
    this->FluxAbsorbed += other.FluxAbsorbed;
    return *this;
  }
};

/**
 * Upper bound of the flux (W, summed over RGB) one texel of a light view of the
 * given resolution carries: directional lights, W/m^2 x the texel's area; point and
 * spot lights, W/sr x the largest texel's solid angle, at the frustum's centre
 * (texel^2 on the unit image plane; the spot falloff is at most 1).
 */
inline double MaximumTexelFlux(const Light& light, const LightView& view, int resolution)
{
  const double power = std::max(0.0, light.radiometric[0]) + std::max(0.0, light.radiometric[1]) +
    std::max(0.0, light.radiometric[2]);
  const double bound = power * view.TexelArea(resolution);
  return bound > 0.0 ? bound : 1.0;
}
}

#endif
