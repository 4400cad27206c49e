/**
 * @file   vtkCausticsCascadedSettings.h
 * @brief  The knobs of cascaded image-space photon tracing, as one value (not wrapped).
 *
 * vtkCausticsCascadedPhotonPass owns one CascadedSettings; its Set/Get methods
 * (documented, with their ranges, on the pass) write into it and the trace takes it
 * by const reference. Section numbers are those of 002_97e66a5090de9b07.txt
 * (Meenrattanakorn and Lambers).
 */
#ifndef vtkCausticsCascadedSettings_h
#define vtkCausticsCascadedSettings_h

#include "vtkCausticsSettingMacros.h" // For vtkCausticsSettingMacro (used with this struct)

namespace caustics
{
struct CascadedSettings
{
  int NumberOfPhotons = 65536; ///< photons sampled per light and frame (§3.1), [0, 16777216]
  bool CameraStage = true;     ///< reproject and march on in the camera view (§3.2, Fig. 5)
  bool MarchHiddenStarts = true; ///< hidden camera-march starts go on (Fig. 7 drops)
  int MarchSteps = 512;        ///< most pixels one march visits in one view, [8, 8192]
  int MaximumEvents = 8;       ///< specular events after emission, [1, 32]
  double KernelSpacings = 2.0; ///< splat radius in photon spacings on the receiver, [0.5, 16]
  double VolumeBlurPixels = 1.5; ///< volume caustics' Gaussian, pixels, [0, 16] (vtkCausticsVolumeLines)
  int VolumeSubSegments = 8;     ///< volume caustics' pieces per segment in a density grid, [0, 64]
};
}

#endif
