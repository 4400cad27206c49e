#include "vtkCausticsAirlight.h"

#include "vtkCausticsAirlightCS.h" // The per-pixel march
#include "vtkCausticsCameraOpticalDepth.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkCausticsAirlight);

struct vtkCausticsAirlight::Internals
{
  vtkNew<vtkCausticsShaderProgram> Program;
};

vtkCausticsAirlight::vtkCausticsAirlight()
  : Internal(new Internals)
{
  this->Internal->Program->SetName("airlight");
  this->Internal->Program->SetComputeSource(vtkCausticsAirlightCS);
  this->Internal->Program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
}

vtkCausticsAirlight::~vtkCausticsAirlight()
{
  if (this->Internal->Program->IsReady())
  {
    vtkErrorMacro(<< "destroyed with its program unreleased (call ReleaseGraphicsResources)");
  }
}

namespace
{
bool HasPower(const caustics::Light& light)
{
  return light.radiometric[0] > 0 || light.radiometric[1] > 0 || light.radiometric[2] > 0;
}

/** sigma_s as the program wants it: per unit density when it follows a grid, else the mean. */
caustics::Vec3 ScatteringFor(vtkCausticsShaderProgram* program, const caustics::Medium& medium)
{
  return program->HasDefine("CAUSTICS_MEDIUM_GRID") ? medium.sigmaS : medium.MeanSigmaS();
}

void SetFloat3(vtkCausticsShaderProgram* program, const char* name, const caustics::Vec3& v)
{
  program->SetUniform3f(
    name, static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}
}

bool vtkCausticsAirlight::IsNeeded(const caustics::SceneData& scene) const
{
  const caustics::Medium& medium = scene.Participating;
  const caustics::Vec3 sigmaS = medium.MeanSigmaS();
  const bool scatters = std::isfinite(sigmaS[0] + sigmaS[1] + sigmaS[2]) &&
    (sigmaS[0] > 0.0 || sigmaS[1] > 0.0 || sigmaS[2] > 0.0);
  return this->Enabled && medium.enabled && scatters && !scene.Lights.empty();
}

bool vtkCausticsAirlight::Render(const Inputs& in, vtkTextureObject* target, bool accumulate)
{
  if (!in.Scene || !in.Shadows || !in.SurfacePositions || !in.RefractorPositions || !target ||
    !this->IsNeeded(*in.Scene))
  {
    return false;
  }
  const caustics::SceneData& scene = *in.Scene;
  vtkCausticsShaderProgram* program = this->Internal->Program;
  caustics::gl::SetMediumDefine(program, in.Grid);
  in.CameraOpticalDepth->SetDefine(program);
  if (!program->Bind(in.Window))
  {
    return false;
  }
  caustics::gl::EnsureTexture(target, in.Window, in.Width, in.Height, GL_RGBA32F);
  float matrix[16];
  caustics::gl::ToColumnMajor(scene.View.clipToWorld, matrix);
  program->SetUniformMatrix4("clipToWorld", matrix);
  program->SetUniform2i("size", in.Width, in.Height);
  program->SetUniformi("steps", this->Steps);
  program->SetUniformi("lightSteps", this->LightSteps);
  SetFloat3(program, "sigmaS", ScatteringFor(program, scene.Participating));
  program->SetUniformf("anisotropy", static_cast<float>(scene.Participating.g));
  caustics::gl::SetMediumUniforms(program, scene, in.Grid);
  in.CameraOpticalDepth->SetUniforms(program);
  in.SurfacePositions->Activate();
  program->SetUniformi("gPosition", in.SurfacePositions->GetTextureUnit());
  in.RefractorPositions->Activate();
  program->SetUniformi("gRefractivePosition", in.RefractorPositions->GetTextureUnit());
  glBindImageTexture(0, target->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  bool wrote = false;
  const int lights =
    std::min(in.Shadows->GetNumberOfLights(), static_cast<int>(scene.Lights.size()));
  for (int i = 0; i < lights; ++i)
  {
    const caustics::LightView& view = in.Shadows->GetView(i);
    if (!HasPower(scene.Lights[i]) || !view.valid)
    {
      continue;
    }
    program->SetUniformi("accumulate", accumulate || wrote ? 1 : 0);
    this->DrawLight(in, i);
    wrote = true;
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  in.SurfacePositions->Deactivate();
  in.RefractorPositions->Deactivate();
  in.CameraOpticalDepth->Deactivate();
  program->Unbind(in.Window);
  return wrote;
}

void vtkCausticsAirlight::DrawLight(const Inputs& in, int i)
{
  vtkCausticsShaderProgram* program = this->Internal->Program;
  const caustics::Light& light = in.Scene->Lights[i];
  const caustics::LightView& view = in.Shadows->GetView(i);
  float matrix[16];
  caustics::gl::ToColumnMajor(view.worldToClip, matrix);
  program->SetUniformMatrix4("lightWorldToClip", matrix);
  program->SetUniformi("lightType", static_cast<int>(light.type));
  // Directional lights measure distance along the axis from the view's eye.
  SetFloat3(program, "lightPosition",
    light.type == caustics::Light::Type::Directional ? view.eye : light.position);
  SetFloat3(program, "lightDirection", light.direction);
  SetFloat3(program, "radiometric", light.radiometric);
  program->SetUniformf("cosOuter", static_cast<float>(light.cosOuter));
  program->SetUniformf("cosInner", static_cast<float>(light.cosInner));
  program->SetUniformf(
    "texelWorldSize", static_cast<float>(view.TexelWidth(in.ShadowMapResolution)));
  vtkTextureObject* shadow = in.Shadows->GetGBuffer(i)->GetPositionTexture();
  vtkTextureObject* shadowNormal = in.Shadows->GetGBuffer(i)->GetNormalTexture();
  shadow->Activate();
  shadowNormal->Activate();
  program->SetUniformi("shadowPosition", shadow->GetTextureUnit());
  program->SetUniformi("shadowNormal", shadowNormal->GetTextureUnit());
  // Each light reads what the one before wrote.
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  program->DispatchCovering2D(in.Width, in.Height, 8, 8);
  shadowNormal->Deactivate();
  shadow->Deactivate();
}

void vtkCausticsAirlight::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->Program->ReleaseGraphicsResources(window);
}

void vtkCausticsAirlight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Enabled: " << (this->Enabled ? "on" : "off") << "\n";
  os << indent << "Steps: " << this->Steps << "\n";
  os << indent << "LightSteps: " << this->LightSteps << "\n";
  os << indent << "Program: " << (this->Internal->Program->IsReady() ? "built" : "not built")
     << "\n";
}
