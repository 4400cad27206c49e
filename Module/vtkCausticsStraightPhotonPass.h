/**
 * @class   vtkCausticsStraightPhotonPass
 * @brief   The smallest photon technique: photons go straight on to the receivers.
 *
 * The worked example of docs/architecture.md: shared emission, a trivial transport
 * (a photon that kept its light ray's direction lands on the receiver the light sees
 * in its texel; others are dropped), shared reconstruction. Behind an IOR-1.0 slab:
 * the direct irradiance the slab hides (TestStraightPhotonPass). Not registered.
 */
#ifndef vtkCausticsStraightPhotonPass_h
#define vtkCausticsStraightPhotonPass_h

#include "vtkCausticsRenderPass.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsStraightPhotonPass : public vtkCausticsRenderPass
{
public:
  static vtkCausticsStraightPhotonPass* New();
  vtkTypeMacro(vtkCausticsStraightPhotonPass, vtkCausticsRenderPass);

protected:
  vtkCausticsStraightPhotonPass();
  ~vtkCausticsStraightPhotonPass() override;

  CausticNeeds GetCausticNeeds() override;
  PhotonStorage GetPhotonStorage() override;
  bool RenderCausticIrradiance(const FrameInputs& in) override;
  bool WritesPhotonVariance() override { return true; } // the shared deposit stages
  void ReleaseTechniqueResources(vtkWindow* w) override;

private:
  vtkCausticsStraightPhotonPass(const vtkCausticsStraightPhotonPass&) = delete;
  void operator=(const vtkCausticsStraightPhotonPass&) = delete;

  bool Transport(const FrameInputs& in, int light);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
