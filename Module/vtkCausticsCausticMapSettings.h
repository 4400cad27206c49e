/**
 * @file   vtkCausticsCausticMapSettings.h
 * @brief  The knobs of the hierarchical caustic map technique, as one value (not wrapped).
 *
 * vtkCausticsHierarchicalCausticMapPass owns one CausticMapSettings; its Set/Get
 * methods (documented, with their ranges, on the pass) write into it, and the
 * technique's stages (vtkCausticsPhotonBuffer, vtkCausticsPhotonBufferHierarchy,
 * vtkCausticsCausticMap) take it by const reference when they run, so nothing is
 * copied into them per frame and each knob has one name from the pass to the
 * shaders. Section numbers are those of 001_7c07a484f7a872bb.txt (Wyman 2008).
 */
#ifndef vtkCausticsCausticMapSettings_h
#define vtkCausticsCausticMapSettings_h

#include "vtkCausticsSettingMacros.h" // For vtkCausticsSettingMacro (used with this struct)

namespace caustics
{
struct CausticMapSettings
{
  enum GatherModes
  {
    GATHER_FLAT = 0,        ///< every photon: Wyman & Davis 2006 (with §4's improvements)
    GATHER_HIERARCHICAL = 1 ///< validity mipmap traversal (§3.1)
  };
  enum ClusterModes
  {
    CLUSTER_NONE = 0,       ///< no clustering
    CLUSTER_LAST_LEVEL = 1, ///< convergence tested at mipmap level 1 only (§3.2)
    CLUSTER_ALL_LEVELS = 2  ///< convergence tested at every level (§3.2)
  };
  enum SplatModes
  {
    SPLAT_CONSTANT = 0,        ///< baseline: ConstantSplatRadius pixels, finest map level only
    SPLAT_VARYING_SINGLE = 1,  ///< Eq. 2 radius, finest map level only
    SPLAT_VARYING_MULTIRES = 2 ///< Eq. 2 radius, map level by splat size (§3.3)
  };

  int GatherMode = GATHER_HIERARCHICAL;   ///< GatherModes
  int ClusterMode = CLUSTER_LAST_LEVEL;   ///< ClusterModes (hierarchical gather only)
  int SplatMode = SPLAT_VARYING_MULTIRES; ///< SplatModes
  int CausticMapResolution = 512;         ///< texels per side of the finest level, [16, 8192]
  int TraversalStartResolution = 16;      ///< nodes per side of the first level, [1, 4096]
  double SplatScale = 2.0;                ///< Eq. 2 radius / photon spacing, [0.25, 16]
  /** Eq. 2's spacing: the beam's mean width along the grid's two axes, at least this
   * fraction of its largest neighbour distance (1: the paper's max distance), [0.05, 1] */
  double MaxDistanceFraction = 0.5;
  double ConstantSplatRadius = 1.5;       ///< SPLAT_CONSTANT radius, finest pixels, [0.5, 64]
  double SplatSizeThreshold = 5.0;        ///< diameter, level pixels, before the next, [1, 64]
  double MinimumSplatRadius = 1.5;        ///< level pixels, [1, 16]
  double MinimumCameraSplatRadius = 1.0;  ///< camera pixel footprints, [0, 16]; 0: off
  double MaximumSplatRadius = 32.0;       ///< level pixels, [2, 360]
  bool DropCoarseSplats = false;          ///< drop splats needing level 4+ (else level 3)
  int MaximumInternalEvents = 8;          ///< interfaces met inside a refractor, [1, 32]
  int MaximumReflections = 3;             ///< mirrors met in air after emission, [0, 16]
  int Reconstruction = 0; ///< vtkCausticsPhotonSplatter::Reconstructions: 0 hierarchical splats,
                          ///< 1 caustic triangles into the camera's view
  bool SplitFresnel = true;               ///< emit a refractor's reflected part too
  bool HiddenReceivers = true;            ///< a second map of receivers hidden by nearer ones
  double MinimumMapIncidence = 45.0;      ///< degrees, [0, 90]; the map's view turns to it
  double VolumeBlurPixels = 1.5; ///< volume caustics' Gaussian, pixels, [0, 16] (vtkCausticsVolumeLines)
  int VolumeSubSegments = 8;     ///< volume caustics' pieces per segment in a density grid, [0, 64]
  int MarchSteps = 64; ///< samples of the photon trace's fallback march, [4, 1024] (no setter)

  /** Levels of the caustic map: 4 for the multi-resolution map (§3.3), else 1. */
  int NumberOfLevels() const { return this->SplatMode == SPLAT_VARYING_MULTIRES ? 4 : 1; }

  /** Radius of a cluster's splat, in level pixels: it lands in one texel (§3.2). */
  double ClusterRadius() const
  {
    return this->SplatMode == SPLAT_CONSTANT ? this->ConstantSplatRadius : this->MinimumSplatRadius;
  }
};
}

#endif
