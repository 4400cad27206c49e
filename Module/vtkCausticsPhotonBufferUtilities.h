/**
 * @file   vtkCausticsPhotonBufferUtilities.h
 * @brief  Host-side helpers of the hierarchical caustic map stages (not wrapped).
 *
 * The buffer layouts of glsl/vtkCausticsPhotonBufferCommon.glsl and
 * glsl/vtkCausticsPhotonStatistics.glsl mirrored for the
 * host, a light view's shader uniforms, and the flux unit of the GPU statistics.
 * Used by vtkCausticsPhotonBuffer, vtkCausticsPhotonBufferHierarchy,
 * vtkCausticsCausticMap and vtkCausticsHierarchicalCausticMapPass; the statistics
 * also by the cascaded and screen-space passes.
 */
#ifndef vtkCausticsPhotonBufferUtilities_h
#define vtkCausticsPhotonBufferUtilities_h

#include "vtkCausticsGLUtilities.h" // For caustics::gl::StorageBuffer
#include "vtkCausticsPhotonGrid.h"  // For caustics::PhotonStatistics
#include "vtkCausticsSceneData.h" // For caustics::LightView

#include <cstdint> // For std::uint32_t
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkCausticsLightBuffers;
class vtkCausticsShaderProgram;

namespace caustics
{

namespace hcm
{
// Shader storage binding points: CAUSTICS_PHOTON_STATISTICS_BINDING and
// CAUSTICS_HIERARCHY_*_BINDING in vtkCausticsBindings.h.

// Photon statistics words (STAT_*, glsl/vtkCausticsPhotonStatistics.glsl).
constexpr int StatPhotons = 0;
constexpr int StatHits = 1;
constexpr int StatLostInside = 2;
constexpr int StatEscaped = 3;
constexpr int StatFluxIn = 4;
constexpr int StatFluxHits = 6;
constexpr int StatFluxLostInside = 8;
constexpr int StatFluxEscaped = 10;
constexpr int StatFluxInternalReflection = 12;
constexpr int StatFluxAbsorbed = 14;
constexpr int StatHiddenHits = 16;
constexpr int StatHiddenDraw = 17; // 4 words: { 3, any hidden hit ? 1 : 0, 0, 0 }
constexpr int StatStored = 21;
constexpr int StatFluxStored = 22;
constexpr int StatStoreDraw = 24; // 4 words: { 3, stored flux > 1e-3 x landed ? 1 : 0, 0, 0 }
constexpr int StatSize = 28;

// Hierarchy control block words (CONTROL_*).
constexpr int ControlDispatch = 0;
constexpr int ControlDraw = 48;
constexpr int ControlListCount = 64;
constexpr int ControlValid = 80;
constexpr int ControlClusters = 81;
constexpr int ControlClusteredPhotons = 82;
constexpr int ControlCoarseSplats = 83;
constexpr int ControlSplatFlux = 84;
constexpr int ControlCoarseFlux = 92;
constexpr int ControlSize = 96;
constexpr int MaxTraversalLevels = 16;
constexpr int MapLevels = 4;

/**
 * Sets the CausticsView uniform struct `name` (e.g. "mapView" or "mapViews[2]") of
 * the bound program: the view's matrices, eye, axis, pixel size and texel width.
 */
void SetViewUniforms(vtkCausticsShaderProgram* program, const std::string& name,
  const caustics::LightView& view, int width, int height);

/**
 * Sets the CausticsView uniform struct `name` to the camera's view: its matrices,
 * eye, viewing direction, image size, and the width of one pixel (at unit depth when
 * perspective), so that ViewTexelSize(name, x) is a camera pixel's width at x.
 */
void SetCameraViewUniforms(
  vtkCausticsShaderProgram* program, const std::string& name, const caustics::Camera& camera);

/**
 * W per unit of the GPU flux statistics for the photons of `grid`: its
 * MaximumPhotonFlux / 2^20, so a photon is rounded to within 5e-7 of that bound (a
 * float holds its units exactly) and 64-bit sums never overflow (2^23 photons x
 * 2^20 units x 4^9 for the largest clusters < 2^64).
 */
double FluxUnit(const caustics::PhotonGrid& grid);

/**
 * Axis-aligned bounds of the meshes whose role is receiver (xmin, xmax, ymin, ...),
 * with a cache of each mesh's bounds keyed by its actor and version, so that an
 * unchanged scene costs no pass over its vertices. False (bounds untouched) when
 * there is no receiver vertex.
 */
class ReceiverBoundsCache
{
public:
  bool Compute(const caustics::SceneData& scene, double bounds[6]);

private:
  struct Entry
  {
    const void* Actor = nullptr;
    unsigned long Version = 0;
    bool Valid = false;
    double Bounds[6];
  };
  std::vector<Entry> Entries;
};

/** Units per maximum photon flux in the statistics (see FluxUnit). */
constexpr double UnitsPerTexelFlux = 1048576.0;

/**
 * Reads the statistics words of `buffer` (StatSize words, fluxes in units of `unit`
 * W) into `statistics`. Stalls the GPU: tests, tools and requested reports only.
 */
void ReadPhotonStatistics(
  const caustics::gl::StorageBuffer& buffer, double unit, caustics::PhotonStatistics& statistics);

/**
 * A technique's photon statistics of one frame (glsl/vtkCausticsPhotonStatistics.glsl):
 * one buffer and one flux unit for every light of the frame, so that their counts add
 * up. Begin() once per frame before the first trace, Bind() before every program
 * that counts, Read() on request (it stalls; vtkCausticsRenderPass's
 * GetLastFramePhotonStatistics), Release() with the technique's GL objects.
 */
class StatisticsBuffer
{
public:
  /**
   * Clears the counters; each traced photon stands for `texelsPerPhoton` emitter
   * texels. The flux unit is FluxUnit's rule for the largest photon of all the
   * frame's lights (their MaximumTexelFlux at the light buffers' resolution).
   */
  void Begin(
    const caustics::SceneData& scene, vtkCausticsLightBuffers* lights, double texelsPerPhoton);
  /** Binds the counters and sets the bound program's `fluxUnit`. */
  void Bind(vtkCausticsShaderProgram* program) const;
  /** The counts of the frame begun last; false when none was begun or none traced. */
  bool Read(caustics::PhotonStatistics& statistics) const;
  void Release();

private:
  caustics::gl::StorageBuffer Buffer;
  double Unit = 1.0; // W per unit of the flux counters
};

/** 64-bit fixed-point flux (two words, low first) in W, given the unit in W. */
inline double FluxFromWords(const std::uint32_t* words, double unit)
{
  return (static_cast<double>(words[0]) + 4294967296.0 * static_cast<double>(words[1])) * unit;
}
}
}

#endif
