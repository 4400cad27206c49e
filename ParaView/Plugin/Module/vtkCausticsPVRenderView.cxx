#include "vtkCausticsPVRenderView.h"

#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkObjectFactory.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkRenderWindow.h"

#include <algorithm>

vtkStandardNewMacro(vtkCausticsPVRenderView);

namespace
{
/** The name that leaves ParaView's own pass in place. */
const char* const OffName = "off";
}

vtkCausticsPVRenderView::vtkCausticsPVRenderView() = default;

// The pass's GPU resources go with the window's: vtkRenderer::ReleaseGraphicsResources
// reaches it through ParaView's camera pass. By the time the view is deleted, the
// context may be gone already, so nothing is released here.
vtkCausticsPVRenderView::~vtkCausticsPVRenderView() = default;

void vtkCausticsPVRenderView::SetCausticsTechnique(const char* name)
{
  const std::string technique = name ? name : OffName;
  if (technique != this->Technique)
  {
    this->Technique = technique;
    this->Modified();
  }
}

void vtkCausticsPVRenderView::SetPhotonGridSide(int side)
{
  side = std::min(8192, std::max(1, side));
  if (side != this->PhotonGridSide)
  {
    this->PhotonGridSide = side;
    this->Modified();
  }
}

vtkCausticsRenderPass* vtkCausticsPVRenderView::GetCausticsPass()
{
  return this->Pass;
}

void vtkCausticsPVRenderView::Render(bool interactive, bool skip_rendering)
{
  this->UpdateCausticsPass();
  this->Superclass::Render(interactive, skip_rendering);
}

/** Steps 2 and 3 of the class description: the pass the next render uses. */
void vtkCausticsPVRenderView::UpdateCausticsPass()
{
  if (this->Technique != this->InstalledTechnique)
  {
    if (this->Pass && this->GetRenderWindow())
    {
      this->Pass->ReleaseGraphicsResources(this->GetRenderWindow());
    }
    this->Pass = nullptr;
    if (this->Technique != OffName)
    {
      this->Pass = vtkCausticsTechniques::Create(this->Technique);
      if (!this->Pass)
      {
        std::string known = "off, best";
        for (const std::string& name : vtkCausticsTechniques::GetNames())
        {
          known += ", " + name;
        }
        vtkErrorMacro("unknown caustics technique '" << this->Technique << "' (known: " << known
                                                     << "); ParaView's own pass renders");
      }
    }
    this->SynchronizedRenderers->SetRenderPass(this->Pass);
    this->InstalledTechnique = this->Technique;
  }
  if (this->Pass)
  {
    this->Pass->SetLightBufferResolution(this->PhotonGridSide);
  }
}

void vtkCausticsPVRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CausticsTechnique: " << this->Technique << "\n";
  os << indent << "PhotonGridSide: " << this->PhotonGridSide << "\n";
  os << indent << "CausticsPass: " << this->Pass.GetPointer() << "\n";
}
