#include "vtkCausticsPhotonEmitter.h"

#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsFullScreenVS.h"
#include "vtkCausticsOptics.h"
#include "vtkCausticsPhotonEmitFS.h"

#include <string>

vtkStandardNewMacro(vtkCausticsPhotonEmitter);

vtkCausticsPhotonEmitter::vtkCausticsPhotonEmitter()
  : Triangle(new caustics::gl::FullScreenTriangle)
  , Planes(new caustics::gl::PhotonPlanes)
{
  this->Program->SetName("photon emission");
  this->Program->SetVertexSource(vtkCausticsFullScreenVS);
  this->Program->SetFragmentSource(
    (std::string(vtkCausticsOptics) + vtkCausticsPhotonEmitFS).c_str());
}

vtkCausticsPhotonEmitter::~vtkCausticsPhotonEmitter()
{
  delete this->Triangle;
  delete this->Planes;
}

bool vtkCausticsPhotonEmitter::Emit(vtkOpenGLRenderWindow* renWin, vtkCausticsLightBuffers* lights,
  int light, vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene)
{
  vtkCausticsGBuffer* buffer = lights->GetGBuffer(light);
  vtkTextureObject* flux = lights->GetFluxTexture(light);
  if (!buffer || !flux || light >= static_cast<int>(scene.Lights.size()))
  {
    vtkErrorMacro(<< "no light buffers for light " << light);
    return false;
  }
  const int n = lights->GetResolution();
  const int width = n, height = this->SplitFresnel ? 2 * n : n;
  const bool resized = this->Planes->Ensure(renWin, width, height);
  this->DescribeGrid(scene.Lights[light], lights->GetView(light), light, n);

  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  this->Framebuffer->SetContext(renWin);
  this->Framebuffer->Bind();
  if (resized || this->Framebuffer->GetNumberOfColorAttachments() != 3)
  {
    const caustics::PhotonRecords records = this->Planes->Records();
    this->Framebuffer->AddColorAttachment(0, records.Position);
    this->Framebuffer->AddColorAttachment(1, records.Direction);
    this->Framebuffer->AddColorAttachment(2, records.Flux);
  }
  this->Framebuffer->ActivateDrawBuffers(3);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, width, height);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_SCISSOR_TEST);

  bool ok = this->Program->Bind(renWin);
  if (ok)
  {
    vtkTextureObject* inputs[] = { buffer->GetPositionTexture(), buffer->GetNormalTexture(), flux };
    const char* names[] = { "lightPosition", "lightNormal", "lightFlux" };
    for (int i = 0; i < 3; ++i)
    {
      inputs[i]->Activate();
      this->Program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
    }
    const caustics::Light& source = scene.Lights[light];
    const caustics::Vec3& origin = source.position;
    this->Program->SetUniformi("resolution", n);
    this->Program->SetUniformi("splitFresnel", this->SplitFresnel ? 1 : 0);
    this->Program->SetUniformi("lightType", static_cast<int>(source.type));
    this->Program->SetUniform3f("lightOrigin", static_cast<float>(origin[0]),
      static_cast<float>(origin[1]), static_cast<float>(origin[2]));
    this->Program->SetUniform3f("lightDirection", static_cast<float>(source.direction[0]),
      static_cast<float>(source.direction[1]), static_cast<float>(source.direction[2]));
    geometry->BindMaterials();
    this->Triangle->Draw();
    for (vtkTextureObject* input : inputs)
    {
      input->Deactivate();
    }
    this->Program->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  return ok;
}

void vtkCausticsPhotonEmitter::DescribeGrid(
  const caustics::Light& source, const caustics::LightView& view, int light, int resolution)
{
  caustics::PhotonGrid& grid = this->Grid;
  grid.Light = light;
  grid.LightType = static_cast<int>(source.type);
  grid.Width = resolution;
  grid.BranchRows = resolution;
  grid.Height = this->SplitFresnel ? 2 * resolution : resolution;
  grid.MaximumPhotonFlux = caustics::MaximumTexelFlux(source, view, resolution);
  grid.Emitted = this->Planes->Records();
}

void vtkCausticsPhotonEmitter::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Planes->Release(win);
  this->Framebuffer->ReleaseGraphicsResources(win);
  this->Program->ReleaseGraphicsResources(win);
  this->Triangle->Release();
  this->Grid = caustics::PhotonGrid();
}

void vtkCausticsPhotonEmitter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SplitFresnel: " << this->SplitFresnel << "\n";
  os << indent << "Grid: " << this->Grid.Width << " x " << this->Grid.Height << " (light "
     << this->Grid.Light << ")\n";
}
