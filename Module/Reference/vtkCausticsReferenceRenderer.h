/**
 * @class   vtkCausticsReferenceRenderer
 * @brief   CPU ground truth for caustics: photon tracing with Embree, in physical units.
 *
 * Every GPU technique of this module is measured against this renderer. It works on
 * exactly the scene the GPU passes see, a caustics::SceneData made by
 * vtkCausticsSceneExtractor (same world-space triangles, vertex normals, materials,
 * lights, camera and medium), and produces, per pixel of the camera image:
 * - CausticIrradiance (RGB, W/m^2): at the first visible surface when it is a
 *   receiver, light that arrived after at least one specular event, before albedo;
 * - DirectIrradiance (RGB, W/m^2): light arriving with no specular event, shadowed
 *   by every mesh (specular ones included: the light through them is the caustic);
 * - VolumeRadiance (RGB, W/(m^2 sr)): single scattering by the homogeneous medium
 *   along the camera ray, = AirlightRadiance + VolumeCausticRadiance (0 without one);
 * - ReceiverMask (1 where the first visible surface is a receiver), PixelArea (m^2
 *   of receiver surface seen by the pixel: sum E x PixelArea is a flux in W),
 *   Transmittance (medium, surface to camera), Position, Normal, Albedo.
 * Composited, a receiver pixel's radiance is Albedo / pi x (Direct + Caustic) x
 * Transmittance + VolumeRadiance.
 *
 * The algorithm (details, estimators and limits in docs/reference.md):
 * 1. Emit PhotonsPerLight photons per light on a jittered stratified grid aimed at
 *    the specular objects only: directional lights over the smaller of the rectangle
 *    and the disk covering the specular bounds seen along the light, flux per photon
 *    E x area / N; point and spot lights over the smaller of the cap subtending the
 *    specular bounding sphere and the spot cone (the whole sphere from inside it),
 *    flux I x solid angle / N x spot falloff.
 * 2. Follow each photon through up to MaxBounces specular events with Embree:
 *    conductor Fresnel with complex IOR per channel; exact unpolarized dielectric
 *    Fresnel with total internal reflection, Beer-Lambert absorption inside
 *    refractors; interpolated normals bend the rays, face normals decide sides and
 *    take over when the interpolated one would send a ray to the wrong side. At a
 *    dielectric both branches are followed while their weight (flux relative to the
 *    emitted flux) is at least RouletteThreshold, with Russian roulette below it.
 *    Medium extinction attenuates every segment. With a medium, an independent set
 *    of VolumePhotonsPerLight photons is traced the same way, and its path segments
 *    after a specular event are kept as photon beams.
 * 3. Photons reaching a receiver after >= 1 specular event are stored.
 * 4. Per pixel, the first visible surface (Camera::PixelRay, matching OpenGL's
 *    rasterization) gets its direct irradiance with shadow rays and its caustic
 *    irradiance E = sum flux_p K2(|x - x_p|) with the normalized Epanechnikov kernel
 *    K2 (2 / (pi r^2) (1 - d^2 / r^2)) over photons with a similar normal; r is
 *    KernelRadius, or KernelRadiusPixels x sqrt(PixelArea) (or, with
 *    PixelFootprintEstimate, the flux landing in the pixel's footprint over its area).
 * 5. Along each camera ray in the medium: airlight by ray marching (RayMarchStep,
 *    jittered) with shadow rays, and the volume caustic by the beam radiance
 *    estimate (each beam's 2D kernel integrated exactly along the ray).
 *
 * Deterministic: every photon, pixel and beam uses its own random stream keyed by
 * Seed, and partial results are merged in a fixed order, so the output is the same
 * bit for bit for a given seed, whatever NumberOfThreads.
 *
 * Results are cached as EXR files keyed by a hash of every input (geometry,
 * materials, lights, camera, medium, settings and a code version); Update() loads
 * them when present. Photon and beam records are only available after a render
 * that was not loaded from the cache.
 *
 * Physics from 004_4da4b323b51d1415.txt §3 (metal Fresnel with n and k, here exact)
 * and 003_653219b45420e98f.txt §3-4 (single scattering, airlight, volume caustics).
 *
 * @sa vtkCausticsSceneExtractor vtkCausticsErrorMetrics
 */
#ifndef vtkCausticsReferenceRenderer_h
#define vtkCausticsReferenceRenderer_h

#include "vtkObject.h"
#include "vtkCausticsReferenceModule.h" // For export macro
#include "vtkSmartPointer.h"            // For members

#include "vtkCausticsReferenceCore.h" // For caustics::ReferencePhoton and friends

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkCausticsSceneExtractor;
class vtkImageData;
class vtkRenderer;

class VTKCAUSTICSREFERENCE_EXPORT vtkCausticsReferenceRenderer : public vtkObject
{
public:
  static vtkCausticsReferenceRenderer* New();
  vtkTypeMacro(vtkCausticsReferenceRenderer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Renders this renderer's scene (through a vtkCausticsSceneExtractor) at
   * ImageSize. Replaces any scene given with SetScene().
   */
  virtual void SetInputRenderer(vtkRenderer* renderer);
  vtkRenderer* GetInputRenderer();

#ifndef __VTK_WRAP__
  /**
   * Renders a scene snapshot instead of a renderer (replaces SetInputRenderer).
   * ImageSize becomes the scene camera's size; it may then be changed to another
   * size of the same aspect ratio.
   */
  void SetScene(const caustics::SceneData& scene);
  /** The scene of the last Update(). */
  const caustics::SceneData& GetScene() const;
#endif

  ///@{
  /** Output image size in pixels, each in [1, 16384]. Default 256 x 256. */
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /**
   * Photons emitted per light, rounded down to a full grid of strata (at most about
   * 2 sqrt(N) fewer; GetNumberOfPhotonsEmitted() tells). Default 1,000,000. Zero is
   * an error when the scene has lights and specular objects.
   */
  vtkSetClampMacro(PhotonsPerLight, vtkIdType, 0, 10000000000LL);
  vtkGetMacro(PhotonsPerLight, vtkIdType);
  ///@}

  ///@{
  /**
   * Photons per light traced, independently of the others, for the beam estimate
   * of volume caustics (only with a medium). A beam lights every pixel along it, so
   * far fewer are needed than for surfaces, and each costs in proportion to its
   * length on screen. Rounded like PhotonsPerLight. Default 100,000.
   */
  vtkSetClampMacro(VolumePhotonsPerLight, vtkIdType, 0, 10000000000LL);
  vtkGetMacro(VolumePhotonsPerLight, vtkIdType);
  ///@}

  ///@{
  /** Specular events (reflections, refractions) a path may have. Default 8. */
  vtkSetClampMacro(MaxBounces, int, 1, 64);
  vtkGetMacro(MaxBounces, int);
  ///@}

  ///@{
  /** Seed of every random stream (jitter, roulette). Default 1. */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * Worker threads, run by vtkSMPTools. 0 (default) keeps vtkSMPTools' own count: every
   * core unless VTK_SMP_MAX_THREADS or vtkSMPTools::Initialize() says otherwise. A
   * count > 0 applies through vtkSMPTools::LocalScope, which sets vtkSMPTools' global
   * count for the duration of Update(): do not run renders with different counts
   * concurrently. Results do not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 4096);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Radius of the surface kernel in metres. 0 (default) uses KernelRadiusPixels
   * instead, so the radius follows the pixel footprint.
   */
  vtkSetClampMacro(KernelRadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(KernelRadius, double);
  ///@}

  ///@{
  /**
   * Surface kernel radius in pixel footprints when KernelRadius is 0: r = this x
   * sqrt(PixelArea) at the shaded point. Default 2.
   */
  vtkSetClampMacro(KernelRadiusPixels, double, 0.25, 64.0);
  vtkGetMacro(KernelRadiusPixels, double);
  ///@}

  ///@{
  /**
   * Estimate each receiver pixel's caustic irradiance as the flux of the photons that
   * land in its footprint (its corner rays on the receiver's tangent plane at the
   * pixel's point) over the footprint's area, instead of with the kernel: the mean
   * irradiance over the pixel, with no blur, what a camera pixel shows and what a box
   * filter of the exact irradiance gives. Needs more photons than the kernel for the
   * same noise (about 9 times those of a kernel of 2 footprints), and pins down
   * detail finer than a kernel (a line one pixel wide; the kernel's estimate of it
   * depends on the radius). Glass and mirror pixels' camera paths keep the kernel.
   * Default off.
   */
  vtkSetMacro(PixelFootprintEstimate, bool);
  vtkGetMacro(PixelFootprintEstimate, bool);
  vtkBooleanMacro(PixelFootprintEstimate, bool);
  ///@}

  ///@{
  /**
   * A photon counts for a pixel only where the cosine between its receiver normal
   * and the pixel's is at least this (same surface, same side). Default 0.9.
   */
  vtkSetClampMacro(KernelNormalCosine, double, -1.0, 1.0);
  vtkGetMacro(KernelNormalCosine, double);
  ///@}

  ///@{
  /**
   * Branch weight (flux / emitted flux, largest channel) below which a branch is
   * followed by Russian roulette instead of deterministically. Default 0.1.
   */
  vtkSetClampMacro(RouletteThreshold, double, 1e-4, 1.0);
  vtkGetMacro(RouletteThreshold, double);
  ///@}

  ///@{
  /** Airlight ray-march step in metres; 0 (default) is the scene's diagonal / 256. */
  vtkSetClampMacro(RayMarchStep, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RayMarchStep, double);
  ///@}

  ///@{
  /** Photon beam kernel radius in pixel footprints at the beam's distance. Default 1.5. */
  vtkSetClampMacro(VolumeKernelRadiusPixels, double, 0.5, 64.0);
  vtkGetMacro(VolumeKernelRadiusPixels, double);
  ///@}

  ///@{
  /**
   * Whether camera rays stop at refractors (default on: the first visible surface).
   * Off, they pass through refractors in a straight line to the first reflector or
   * receiver, the surface the GPU passes' opaque G-buffer holds: the caustic
   * irradiance under a water surface (the pool's floor) can then be compared.
   * Photons are unaffected.
   */
  vtkSetMacro(CameraSeesRefractors, bool);
  vtkGetMacro(CameraSeesRefractors, bool);
  vtkBooleanMacro(CameraSeesRefractors, bool);
  ///@}

  ///@{
  /**
   * Camera paths per pixel whose first visible surface is glass or a mirror, for the
   * output arrays "SpecularColor" (display units: albedo x irradiance where the path
   * ends on a receiver, the background where it leaves the scene; what the GPU passes'
   * camera-view stage shows there) and "SpecularMask", in [0, 4096]; 0: none (zero
   * arrays). Default 0: each path gathers the photons, which costs as much as a
   * pixel's caustic per sample.
   * The background is the input renderer's (black with SetScene()).
   */
  vtkSetClampMacro(SpecularSamples, int, 0, 4096);
  vtkGetMacro(SpecularSamples, int);
  ///@}

  ///@{
  /** Load and store results in CacheDirectory. Default on. */
  vtkSetMacro(UseCache, bool);
  vtkGetMacro(UseCache, bool);
  vtkBooleanMacro(UseCache, bool);
  ///@}

  ///@{
  /**
   * Folder of cached results. Default: the environment variable
   * CAUSTICS_REFERENCE_CACHE as it is when the renderer is constructed, else
   * $XDG_CACHE_HOME/vtkcaustics/reference, else ~/.cache/vtkcaustics/reference
   * (empty, no cache, without a home). The tests set it to <build>/reference-cache.
   */
  vtkSetStdStringFromCharMacro(CacheDirectory);
  vtkGetCharFromStdStringMacro(CacheDirectory);
  ///@}

  /**
   * Renders (or loads from the cache). Returns false with GetLastError() set and an
   * empty output on bad input; never leaves a stale image in the output.
   */
  bool Update();

  /** The image of the last Update(): ImageSize, float point-data arrays (see above). */
  vtkImageData* GetOutput();

  /** Message of the last failure, empty after a success. */
  const char* GetLastError() const
  {
    return this->LastError.c_str();
  }

  /** True when the last Update() read its result from the cache. */
  bool GetLoadedFromCache() const
  {
    return this->LoadedFromCache;
  }
  /** Cache file (.exr) of the last Update(), empty when the cache is off. */
  const char* GetCacheFile() const
  {
    return this->CacheFile.c_str();
  }

  ///@{
  /** Statistics of the last Update() (also restored from the cache). */
  vtkIdType GetNumberOfPhotonsEmitted() const;
  vtkIdType GetNumberOfPhotonsDeposited() const;
  vtkIdType GetNumberOfBeams() const;
  /** Flux (W, RGB) a light emitted / deposited on receivers after specular events. */
  void GetEmittedFlux(int light, double rgb[3]) const;
  void GetDepositedFlux(int light, double rgb[3]) const;
  /** Wall time of the last Update() in seconds, extraction and cache included. */
  double GetWallTime() const
  {
    return this->WallTime;
  }
  ///@}

#ifndef __VTK_WRAP__
  /** Full statistics: flux balance per light, deposits by event count, stage times. */
  const caustics::ReferenceStatistics& GetStatistics() const;
  /** Photons stored on receivers by the last render (empty after a cache hit). */
  const std::vector<caustics::ReferencePhoton>& GetPhotons() const;
  /** Photon beams of the last render (empty after a cache hit or without a medium). */
  const std::vector<caustics::ReferenceBeam>& GetBeams() const;
  /** The settings Update() passes to the tracer. */
  caustics::ReferenceSettings GetSettings() const;
  /** Hash of a scene and settings at a size, as used for the cache file name. */
  static std::string ComputeCacheKey(
    const caustics::SceneData& scene, const caustics::ReferenceSettings& settings);
#endif

  /** Version of the reference's results; part of every cache key. */
  static const char* GetVersion();

protected:
  vtkCausticsReferenceRenderer();
  ~vtkCausticsReferenceRenderer() override;

  int ImageSize[2] = { 256, 256 };
  vtkIdType PhotonsPerLight = 1000000;
  vtkIdType VolumePhotonsPerLight = 100000;
  int MaxBounces = 8;
  unsigned int Seed = 1;
  int NumberOfThreads = 0;
  double KernelRadius = 0.0;
  double KernelRadiusPixels = 2.0;
  bool PixelFootprintEstimate = false;
  double KernelNormalCosine = 0.9;
  double RouletteThreshold = 0.1;
  double RayMarchStep = 0.0;
  double VolumeKernelRadiusPixels = 1.5;
  bool CameraSeesRefractors = true;
  int SpecularSamples = 0;
  bool UseCache = true;
  std::string CacheDirectory;

private:
  vtkCausticsReferenceRenderer(const vtkCausticsReferenceRenderer&) = delete;
  void operator=(const vtkCausticsReferenceRenderer&) = delete;

  bool Fail(const std::string& message);
  bool CheckSettings();
  bool AcquireScene();
  bool CheckWorkload(const caustics::SceneData& scene, const caustics::ReferenceSettings& settings);
  bool Render(const caustics::SceneData& scene, const caustics::ReferenceSettings& settings);
  bool LoadFromCache(const std::string& key);
  void StoreInCache(const std::string& key);
  void MakeOutput(const caustics::ReferenceImage& image);

  vtkSmartPointer<vtkRenderer> InputRenderer;
  vtkSmartPointer<vtkCausticsSceneExtractor> Extractor;
  vtkSmartPointer<vtkImageData> Output;
  std::string LastError;
  std::string CacheFile;
  bool LoadedFromCache = false;
  double WallTime = 0.0;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
