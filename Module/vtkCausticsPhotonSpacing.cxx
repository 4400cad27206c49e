#include "vtkCausticsPhotonSpacing.h"

#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsPhotonSpacingCS.h" // The stage's compute shader
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

vtkStandardNewMacro(vtkCausticsPhotonSpacing);

vtkCausticsPhotonSpacing::vtkCausticsPhotonSpacing()
{
  this->Program->SetName("photon spacing radii");
  this->Program->SetComputeSource(vtkCausticsPhotonSpacingCS);
  this->Program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
}

vtkCausticsPhotonSpacing::~vtkCausticsPhotonSpacing() = default;

bool vtkCausticsPhotonSpacing::Widen(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed, vtkTextureObject* radius,
  double spacings, int estimate, double stretch)
{
  if (!landed.IsSet() || !radius || !radius->GetHandle())
  {
    vtkErrorMacro(<< "Widen needs the landed photon records and their radius texture");
    return false;
  }
  if (grid.Width <= 0 || grid.Height <= 0 || !(spacings > 0.0))
  {
    return true; // no photons, or no widening asked for
  }
  vtkCausticsShaderProgram* p = this->Program;
  if (!p->Bind(renWin))
  {
    return false;
  }
  glBindImageTexture(0, landed.Position->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(1, landed.Direction->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(2, landed.Flux->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(3, radius->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  p->SetUniform2i("grid", grid.Width, grid.Height);
  p->SetUniformi("branchRows", std::max(grid.BranchRows, 1));
  p->SetUniformi("directional", grid.LightType == 0 ? 1 : 0);
  p->SetUniformf("spacings", static_cast<float>(spacings));
  p->SetUniformf("stretch", static_cast<float>(std::max(stretch, 0.0)));
  p->SetUniformi("estimate", estimate == MEAN_DISTANCE ? MEAN_DISTANCE : AREA);
  p->DispatchCovering2D(grid.Width, grid.Height, 16, 16);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  for (unsigned int unit = 0; unit < 3; ++unit)
  {
    glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  }
  glBindImageTexture(3, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  p->Unbind(renWin);
  return true;
}

void vtkCausticsPhotonSpacing::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Program->ReleaseGraphicsResources(win);
}

void vtkCausticsPhotonSpacing::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Program: " << this->Program << "\n";
}
