/**
 * @file   vtkCausticsReferenceCore.h
 * @brief  Plain C++ core of the CPU reference renderer (vtkCausticsReferenceRenderer).
 *
 * Three parts, all outside VTK's wrapping:
 * 1. exact optics used by the reference, exposed so that tests and GPU passes can
 *    check themselves against the same formulas: unpolarized dielectric and
 *    conductor Fresnel reflectance, reflection/refraction directions, the
 *    Henyey-Greenstein phase function, the density-estimation kernels and the
 *    equal-area sampling maps;
 * 2. the records the reference produces: photon deposits on receivers, photon
 *    beams in the medium, flux bookkeeping per light, and the per-pixel images;
 * 3. caustics::ReferenceTracer, which ray-traces a caustics::SceneData with Embree
 *    (the algorithm is described in vtkCausticsReferenceRenderer.h and
 *    docs/reference.md).
 *
 * Units: metres, watts, steradians. Fluxes are per RGB channel.
 */
#ifndef vtkCausticsReferenceCore_h
#define vtkCausticsReferenceCore_h

#include "vtkCausticsSceneData.h" // For caustics::SceneData, caustics::Vec3

#include <cstdint>    // For std::int64_t
#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace caustics
{
///@{
/**
 * Unpolarized Fresnel reflectance of a dielectric interface, exact (average of the
 * s and p amplitudes squared, not Schlick). `cosIncident` is |cos| of the angle
 * between the ray and the normal; `etaIncident`/`etaTransmitted` are the indices on
 * the ray's side and on the far side. Returns 1 for total internal reflection.
 */
double FresnelDielectric(double cosIncident, double etaIncident, double etaTransmitted);
/**
 * Unpolarized Fresnel reflectance of a conductor with complex index n + ik seen
 * from a medium of index 1 (Born and Wolf; 004_4da4b323b51d1415.txt §3 uses an
 * approximation of this). At normal incidence it is ((n-1)^2 + k^2)/((n+1)^2 + k^2).
 */
double FresnelConductor(double cosIncident, double n, double k);
///@}

///@{
/**
 * Mirror direction of unit `d` about unit `n`, and the refracted direction by
 * Snell's law with eta = etaIncident / etaTransmitted. `n` must face the incoming
 * ray (dot(d, n) < 0). Refract returns false on total internal reflection.
 */
Vec3 Reflect(const Vec3& d, const Vec3& n);
bool Refract(const Vec3& d, const Vec3& n, double eta, Vec3& refracted);
///@}

/**
 * Henyey-Greenstein phase function in 1/sr: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5),
 * cos being the cosine between the propagation directions before and after scattering.
 */
double HenyeyGreenstein(double cosTheta, double g);

///@{
/**
 * Normalized Epanechnikov kernels of radius r. 2D (surface photons and beam
 * cross-sections): K2(d) = 2 / (pi r^2) (1 - d^2 / r^2), whose integral over the
 * plane is 1. 1D: its marginal K1(d) = 8 (r^2 - d^2)^1.5 / (3 pi r^4), the integral
 * of K2 along a line at distance d from the centre; its integral over d is 1.
 */
double EpanechnikovKernel2D(double distanceSquared, double radius);
double EpanechnikovKernel1D(double distance, double radius);
///@}

/**
 * Shirley-Chiu concentric map of the unit square (u, v in [0, 1]) to the unit disk,
 * area-preserving up to the factor pi: strata of the square map to strata of equal
 * area on the disk.
 */
void ConcentricSquareToDisk(double u, double v, double& x, double& y);

/** Parameters of a reference render; vtkCausticsReferenceRenderer documents each one. */
struct ReferenceSettings
{
  std::int64_t photonsPerLight = 1000000;
  std::int64_t volumePhotonsPerLight = 100000; ///< separate set traced for beams (medium only)
  int maxBounces = 8;
  std::uint64_t seed = 1;
  int threads = 0;                       ///< 0: vtkSMPTools' own count (all cores)
  double kernelRadius = 0.0;             ///< m; > 0 fixes the surface kernel radius
  double kernelRadiusPixels = 2.0;       ///< else radius = this x sqrt(pixel footprint area)
  double kernelNormalCosine = 0.9;       ///< photons count where n_photon . n_pixel >= this
  bool pixelFootprint = false;           ///< receiver pixels: flux in the footprint / its area
  double rouletteThreshold = 0.1;        ///< branch weight below which Russian roulette is used
  double rayMarchStep = 0.0;             ///< m; 0: scene size / 256
  double volumeKernelRadiusPixels = 1.5; ///< beam kernel radius in pixel footprints
  bool cameraSeesRefractors = true;      ///< false: camera rays pass refractors unbent
  int specularSamples = 0;               ///< camera paths per glass or mirror pixel (0: none)
  Vec3 background{ { 0, 0, 0 } };        ///< what camera paths that leave the scene see
};

/** A photon that reached a receiver after at least one specular event. */
struct ReferencePhoton
{
  float position[3];  ///< on the receiver, m
  float normal[3];    ///< receiver's geometric normal, on the side the photon came from
  float direction[3]; ///< unit propagation direction of its last segment
  float flux[3];      ///< W per channel arriving at the receiver (before albedo)
  float firstHit[3];  ///< where the path met its first specular surface, m
  std::uint32_t mesh; ///< receiver, index into SceneData::Meshes
  std::uint16_t light;
  std::uint8_t events; ///< specular reflections/refractions on the way (>= 1)
};

/** A photon path segment in the medium after at least one specular event. */
struct ReferenceBeam
{
  float start[3];     ///< m, inside the medium
  float direction[3]; ///< unit
  float length;       ///< m, clipped to the medium
  /**
   * W per channel at `start`; decays as exp(-sigma_t s) along it in a homogeneous
   * medium. In a heterogeneous one a beam is a piece between two tentative collisions
   * of ratio tracking, whose flux estimate is constant along it.
   */
  float flux[3];
  /**
   * 1/m per channel: the Beer-Lambert absorption of the refractor the beam lies in
   * (a medium that fills the refractors), by which its flux also decays along it;
   * 0 in air.
   */
  float attenuation[3];
};

/**
 * Where the emitted flux went, per light (W per channel). Exact balance:
 * emitted = direct + deposited + escaped + absorbed + bounceLimit + roulette.
 */
struct ReferenceLightStatistics
{
  std::int64_t photonsEmitted = 0;   ///< emitted paths (strata), after rounding to the grid
  std::int64_t photonsDeposited = 0; ///< ReferencePhoton records from this light
  double emissionMeasure = 0.0;      ///< m^2 (directional) or sr (point, spot) sampled
  Vec3 emitted{ { 0, 0, 0 } };
  Vec3 direct{ { 0, 0, 0 } };      ///< reached a receiver without specular event (not stored)
  Vec3 deposited{ { 0, 0, 0 } };   ///< reached a receiver after >= 1 specular event
  Vec3 escaped{ { 0, 0, 0 } };     ///< left the scene
  Vec3 absorbed{ { 0, 0, 0 } };    ///< conductors, Beer-Lambert in refractors, medium extinction
  Vec3 bounceLimit{ { 0, 0, 0 } }; ///< dropped when meeting specular event MaxBounces + 1
  Vec3 roulette{ { 0, 0, 0 } };    ///< killed minus boosted by Russian roulette (0 on average)
};

struct ReferenceStatistics
{
  std::vector<ReferenceLightStatistics> lights;
  /** Flux deposited by paths with exactly k specular events, k = 0 ... MaxBounces. */
  std::vector<Vec3> depositedByEvents;
  std::int64_t beams = 0;
  double photonSeconds = 0.0; ///< photon tracing
  double viewSeconds = 0.0;   ///< camera rays, direct light, caustic gather, airlight
  double volumeSeconds = 0.0; ///< beam radiance estimate
  double totalSeconds = 0.0;  ///< wall time of the render (0 when loaded from the cache)
};

/** Per-pixel outputs, rows bottom-up, pixel (i, j) at index j * width + i. */
struct ReferenceImage
{
  int width = 0, height = 0;
  std::vector<float> caustic;       ///< 3 per pixel: W/m^2 at the first visible receiver
  std::vector<float> direct;        ///< 3: W/m^2, shadowed, no specular event
  std::vector<float> airlight;      ///< 3: W/(m^2 sr), medium lit straight from the lights
  std::vector<float> volumeCaustic; ///< 3: W/(m^2 sr), medium lit by photon beams
  std::vector<float> transmittance; ///< 3: medium transmittance from the surface to the camera
  std::vector<float> position;      ///< 3: first visible surface point, m (0 when none)
  std::vector<float> normal;        ///< 3: its shading normal, facing the camera
  std::vector<float> albedo;        ///< 3: receiver albedo (0 elsewhere)
  std::vector<float> mask;          ///< 1: 1 where the first visible surface is a receiver
  std::vector<float> pixelArea;     ///< 1: m^2 of that surface seen by the pixel
  std::vector<float> specular;      ///< 3: display colour where the first surface is specular
  std::vector<float> specularMask;  ///< 1: 1 where the first visible surface is glass or mirror

  void Resize(int w, int h);
};

/** Empty when the scene can be rendered, else a message naming what is wrong. */
std::string ValidateReferenceScene(const SceneData& scene);

/** Renders SceneData with Embree ray queries; see vtkCausticsReferenceRenderer. */
class ReferenceTracer
{
public:
  ReferenceTracer();
  ~ReferenceTracer();
  ReferenceTracer(const ReferenceTracer&) = delete;
  ReferenceTracer& operator=(const ReferenceTracer&) = delete;

  /** Called on the calling thread with the fraction done, in [0, 1]. */
  using ProgressFunction = std::function<void(double)>;

  /**
   * Renders `scene` (validated first) at the scene camera's width x height. Returns
   * false with `error` set on bad input or when memory runs out.
   */
  bool Render(const SceneData& scene, const ReferenceSettings& settings, ReferenceImage& image,
    ReferenceStatistics& statistics, const ProgressFunction& progress, std::string& error);

  /** Deposits and beams of the last Render(), in a deterministic order. */
  const std::vector<ReferencePhoton>& GetPhotons() const;
  const std::vector<ReferenceBeam>& GetBeams() const;
  /** Releases the deposits and beams. */
  void ReleasePhotons();

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
};
}

#endif
