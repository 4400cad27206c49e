#include "vtkCausticsPhotonSplatter.h"

#include "vtkCausticsGBuffer.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsPhotonSplatFS.h"
#include "vtkCausticsPhotonSplatVS.h"

vtkStandardNewMacro(vtkCausticsPhotonSplatter);

vtkCausticsPhotonSplatter::vtkCausticsPhotonSplatter()
{
  this->Program->SetName("photon splat");
  this->Program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->Program->SetVertexSource(vtkCausticsPhotonSplatVS);
  this->Program->SetFragmentSource(vtkCausticsPhotonSplatFS);
}

vtkCausticsPhotonSplatter::~vtkCausticsPhotonSplatter()
{
  if (this->VertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): vertex array leaked");
  }
}

bool vtkCausticsPhotonSplatter::Splat(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
  vtkTextureObject* kernelRadius, vtkCausticsGBuffer* target, const float worldToClip[16])
{
  if (grid.IsEmpty())
  {
    return true; // no photons: nothing to deposit
  }
  if (!landed.IsSet() || !kernelRadius)
  {
    vtkErrorMacro(<< "Splat needs the landed photons' three record textures and their radii");
    return false;
  }
  if (!this->Program->Bind(renWin))
  {
    return false;
  }
  if (!this->VertexArray)
  {
    glCreateVertexArrays(1, &this->VertexArray);
  }
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable pointSize(state, GL_PROGRAM_POINT_SIZE);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglEnable(GL_PROGRAM_POINT_SIZE);

  vtkTextureObject* inputs[] = { landed.Position, landed.Direction, landed.Flux, kernelRadius,
    target->GetPositionTexture(), target->GetNormalTexture() };
  const char* names[] = { "hitPosition", "hitNormal", "hitFlux", "kernelRadius", "targetPosition",
    "targetNormal" };
  for (int i = 0; i < 6; ++i)
  {
    inputs[i]->Activate();
    this->Program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
  }
  const int* size = target->GetSize();
  this->Program->SetUniformi("hitWidth", grid.Width);
  this->Program->SetUniformMatrix4("worldToClip", worldToClip);
  this->Program->SetUniform2f("viewport", static_cast<float>(size[0]), static_cast<float>(size[1]));
  this->Program->SetUniformf("minimumRadiusPixels", static_cast<float>(this->MinimumRadiusPixels));
  this->Program->SetUniformf("maximumRadiusPixels", static_cast<float>(this->MaximumRadiusPixels));
  this->Program->SetUniformf("planeTolerance", static_cast<float>(this->PlaneTolerance));
  this->Program->SetUniformf("normalTolerance", static_cast<float>(this->NormalTolerance));
  glBindVertexArray(this->VertexArray);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(grid.Count()));
  glBindVertexArray(0);
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  this->Program->Unbind(renWin);
  return true;
}

void vtkCausticsPhotonSplatter::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Program->ReleaseGraphicsResources(win);
  if (this->VertexArray)
  {
    glDeleteVertexArrays(1, &this->VertexArray);
    this->VertexArray = 0;
  }
}

void vtkCausticsPhotonSplatter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MinimumRadiusPixels: " << this->MinimumRadiusPixels << "\n";
  os << indent << "MaximumRadiusPixels: " << this->MaximumRadiusPixels << "\n";
  os << indent << "PlaneTolerance: " << this->PlaneTolerance << "\n";
  os << indent << "NormalTolerance: " << this->NormalTolerance << "\n";
}
