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
 */
#ifndef vtkCausticsPhotonGrid_h
#define vtkCausticsPhotonGrid_h

#include "vtkCausticsSceneData.h" // For caustics::Light, caustics::LightView

#include <algorithm> // For std::max
#include <cstddef>   // For std::size_t

class vtkTextureObject;

namespace caustics
{
struct PhotonGrid
{
  int Light = -1;     ///< index of the emitting light in SceneData::Lights
  int Width = 0;      ///< columns: N, the light buffers' texels per side
  int Height = 0;     ///< rows: N per emission branch (N, or 2N with the reflected branch)
  int BranchRows = 0; ///< N: rows of one branch (grid neighbours never cross a branch)
  /**
   * W summed over RGB: an upper bound of one photon's flux (the light's power through
   * the largest texel of its view). The GPU flux counters count in units of it.
   */
  double MaximumPhotonFlux = 1.0;
  ///@{
  /**
   * The emitted photons, RGBA32F textures of Width x Height owned by the emitter
   * (see vtkCausticsPhotonEmitter): where each leaves its first specular surface
   * (w = state), its direction (w = the texel's measure), its flux (rgb W).
   */
  vtkTextureObject* Position = nullptr;
  vtkTextureObject* Direction = nullptr;
  vtkTextureObject* Flux = nullptr;
  ///@}

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
 * Upper bound of the flux (W, summed over RGB) one texel of a light view of the
 * given resolution carries: directional lights, W/m^2 x the texel's area; point and
 * spot lights, W/sr x the largest texel's solid angle, at the frustum's centre
 * (texel^2 on the unit image plane; the spot falloff is at most 1).
 */
inline double MaximumTexelFlux(const Light& light, const LightView& view, int resolution)
{
  const double power = std::max(0.0, light.radiometric[0]) + std::max(0.0, light.radiometric[1]) +
    std::max(0.0, light.radiometric[2]);
  const double texel = 2.0 * view.halfExtent / std::max(resolution, 1);
  const double bound = power * texel * texel;
  return bound > 0.0 ? bound : 1.0;
}
}

#endif
