/**
 * @file   vtkCausticsScreenSpaceSettings.h
 * @brief  The knobs of the screen-space photon tracing technique, as one value (not wrapped).
 *
 * vtkCausticsScreenSpacePhotonPass owns one ScreenSpaceSettings; its Set/Get
 * methods (documented, with their ranges, on the pass) write into it, and the
 * stages that need a knob take the value by const reference when they run
 * (vtkCausticsScreenSpaceLineTracer, vtkCausticsVolumeLines), so nothing is
 * copied into them per frame. Section numbers are those of 000_54cf099eeccf42d9.txt
 * (Krüger, Bürger and Westermann 2006).
 */
#ifndef vtkCausticsScreenSpaceSettings_h
#define vtkCausticsScreenSpaceSettings_h

#include "vtkCausticsSettingMacros.h" // For vtkCausticsSettingMacro (used with this struct)

namespace caustics
{
struct ScreenSpaceSettings
{
  int MaximumNumberOfLayers = 8;               ///< depth layers peeled from the camera, [1, 16]
  bool PerObjectLayers = false;                ///< one layered depth image per object (§2.2)
  int MaximumBounces = 3;                      ///< specular events of a photon path, [1, 8]
  double IntersectionTolerance = 0.0;          ///< m, [0, 1e6]; 0: relative to the scene
  double RelativeIntersectionTolerance = 1e-3; ///< x caustics::VisibleScale, [1e-6, 0.1]
  int MinimumLineLength = 8;                   ///< fragments of the shortest traced line, [1, 256]
  int RowsPerBatch = 8192;                     ///< line rows traced per batch, [16, 16384]
  double SplatRadius = 0.0;                    ///< m, [0, 1e6]; 0: the pixel and spacing rules
  double SplatRadiusPixels = 2.0;              ///< pixel footprints, [0.5, 64]
  double SplatRadiusSpacings = 2.0;            ///< photon spacings, [0, 16]; 0: pixel rule only
  int Reconstruction = 0; ///< vtkCausticsPhotonSplatter::Reconstructions: 0 splats, 1 triangles
  bool GodRays = true;                         ///< volume caustics in a medium (§3.2)
  double GodRayBlurPixels = 1.5;               ///< Gaussian standard deviation, pixels, [0, 16]
  int VolumeSubSegments = 8; ///< god-ray pieces in a heterogeneous medium (003 §5.2), [0, 64]; 0 marches per fragment
  bool SkipOffscreenSpecular = false;          ///< plain VTK when no specular actor is in view
  int TraceView = 0; ///< caustics::TraceViewMode: 0 automatic, 1 camera, 2 fitted

  /** The hit tolerance (m) in a scene of the given size (m). */
  double Tolerance(double sceneScale) const
  {
    return this->IntersectionTolerance > 0.0 ? this->IntersectionTolerance
                                             : this->RelativeIntersectionTolerance * sceneScale;
  }
};
}

#endif
