/**
 * @file   vtkCausticsImpostorPhotonSettings.h
 * @brief  The knobs of caustics via distance impostors, as one value (not wrapped).
 *
 * vtkCausticsImpostorPhotonPass owns one ImpostorPhotonSettings; its Set/Get methods
 * (documented, with their ranges, on the pass) write into it and the trace takes it
 * by const reference. Section numbers are those of 004_4da4b323b51d1415.txt
 * (Szirmay-Kalos et al., distance impostors). The maps' own knobs (Resolution,
 * LinearSteps, SecantSteps) are vtkCausticsDistanceImpostors', shared with the
 * camera view.
 */
#ifndef vtkCausticsImpostorPhotonSettings_h
#define vtkCausticsImpostorPhotonSettings_h

#include "vtkCausticsSettingMacros.h" // For vtkCausticsSettingMacro (used with this struct)

namespace caustics
{
struct ImpostorPhotonSettings
{
  int MaximumEvents = 8;       ///< specular events after emission (§4-5), [1, 32]
  double KernelSpacings = 2.0; ///< splat radius in photon spacings on the receiver, [0.5, 16]
  double SpreadStretch = 64.0; ///< farthest widening neighbour, unoccluded spacings, [0, 1e6]
};
}

#endif
