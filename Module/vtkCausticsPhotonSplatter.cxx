#include "vtkCausticsPhotonSplatter.h"

#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsFullScreenVS.h"
#include "vtkCausticsPhotonSplatEndsFS.h"
#include "vtkCausticsPhotonSplatFS.h"
#include "vtkCausticsPhotonSplatVS.h"
#include "vtkCausticsPhotonTriangleClassifyCS.h"
#include "vtkCausticsPhotonTriangleCommon.h"
#include "vtkCausticsPhotonTriangleFS.h"
#include "vtkCausticsPhotonTriangleVS.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsPhotonSplatter);

vtkCausticsPhotonSplatter::vtkCausticsPhotonSplatter()
  : Triangle(new caustics::gl::FullScreenTriangle)
{
  this->Program->SetName("photon splat");
  this->Program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->Program->SetDefine("CAUSTICS_KERNEL_RADII", 1);
  this->Program->SetVertexSource(vtkCausticsPhotonSplatVS);
  this->Program->SetFragmentSource(vtkCausticsPhotonSplatFS);
  const std::string triangles = vtkCausticsPhotonTriangleCommon;
  const std::string records = "uniform sampler2D hitPosition;\n"
                              "uniform sampler2D hitNormal;\n"
                              "uniform sampler2D hitFlux;\n";
  this->ClassifyProgram->SetName("caustic triangle classification");
  this->ClassifyProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->ClassifyProgram->SetComputeSource(
    (records + triangles + vtkCausticsPhotonTriangleClassifyCS).c_str());
  this->TriangleProgram->SetName("caustic triangles");
  this->TriangleProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->TriangleProgram->SetVertexSource((records + triangles + vtkCausticsPhotonTriangleVS).c_str());
  this->TriangleProgram->SetFragmentSource(vtkCausticsPhotonTriangleFS);
  this->EndsProgram->SetName("photon splat: receivers' ends");
  this->EndsProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->EndsProgram->SetVertexSource(vtkCausticsFullScreenVS);
  this->EndsProgram->SetFragmentSource(vtkCausticsPhotonSplatEndsFS);
}

vtkCausticsPhotonSplatter::~vtkCausticsPhotonSplatter()
{
  if (this->VertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): vertex array leaked");
  }
  delete this->Triangle;
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
  const bool triangles = this->Reconstruction == TRIANGLES;
  if (triangles &&
    (!this->ClassifyTriangles(renWin, grid, landed, target->GetSize(), worldToClip) ||
      !this->DrawTriangles(renWin, grid, landed, target, worldToClip)))
  {
    return false;
  }
  return this->KeepFluxAtReceiverEnds
    ? this->SplatKeepingEnds(renWin, grid, landed, kernelRadius, target, worldToClip)
    : this->DrawSplats(renWin, grid, landed, kernelRadius, target, worldToClip);
}

bool vtkCausticsPhotonSplatter::SplatKeepingEnds(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
  vtkTextureObject* kernelRadius, vtkCausticsGBuffer* target, const float worldToClip[16])
{
  const int* size = target->GetSize();
  const bool resized =
    caustics::gl::EnsureTexture(this->KernelIrradiance, renWin, size[0], size[1], GL_RGBA32F);
  caustics::gl::EnsureTexture(this->KernelRadii, renWin, size[0], size[1], GL_RG32F);
  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLFramebufferObject* framebuffer = this->KernelFramebuffer;
  framebuffer->SetContext(renWin);
  framebuffer->Bind();
  if (resized || framebuffer->GetNumberOfColorAttachments() != 2)
  {
    framebuffer->AddColorAttachment(0, this->KernelIrradiance);
    framebuffer->AddColorAttachment(1, this->KernelRadii);
  }
  framebuffer->ActivateDrawBuffers(2);
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_COLOR, 1, zero);
  const bool drawn = this->DrawSplats(renWin, grid, landed, kernelRadius, target, worldToClip);
  state->PopFramebufferBindings();
  return drawn && this->AddKernels(renWin, target, worldToClip);
}

void vtkCausticsPhotonSplatter::SetReceiverBounds(const double bounds[6])
{
  const bool valid = bounds && std::isfinite(bounds[0]) && std::isfinite(bounds[1]) &&
    std::isfinite(bounds[2]) && std::isfinite(bounds[3]) && std::isfinite(bounds[4]) &&
    std::isfinite(bounds[5]) && bounds[0] <= bounds[1] && bounds[2] <= bounds[3] &&
    bounds[4] <= bounds[5];
  if (valid == this->HasReceiverBounds &&
    (!valid || std::equal(bounds, bounds + 6, this->ReceiverBounds)))
  {
    return;
  }
  this->HasReceiverBounds = valid;
  if (valid)
  {
    std::copy(bounds, bounds + 6, this->ReceiverBounds);
  }
  this->Modified();
}

bool vtkCausticsPhotonSplatter::GetReceiverBounds(double bounds[6]) const
{
  if (this->HasReceiverBounds)
  {
    std::copy(this->ReceiverBounds, this->ReceiverBounds + 6, bounds);
  }
  return this->HasReceiverBounds;
}

bool vtkCausticsPhotonSplatter::AddKernels(
  vtkOpenGLRenderWindow* renWin, vtkCausticsGBuffer* target, const float worldToClip[16])
{
  vtkCausticsShaderProgram* program = this->EndsProgram;
  if (!program->Bind(renWin))
  {
    return false;
  }
  vtkTextureObject* inputs[] = { this->KernelIrradiance, this->KernelRadii,
    target->GetPositionTexture(), target->GetNormalTexture() };
  const char* names[] = { "kernelIrradiance", "kernelRadii", "targetPosition", "targetNormal" };
  for (int i = 0; i < 4; ++i)
  {
    inputs[i]->Activate();
    program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
  }
  float clipToWorld[16];
  caustics::gl::InvertColumnMajor(worldToClip, clipToWorld);
  const int* size = target->GetSize();
  program->SetUniformMatrix4("worldToClip", worldToClip);
  program->SetUniformMatrix4("clipToWorld", clipToWorld);
  program->SetUniform2f("viewport", static_cast<float>(size[0]), static_cast<float>(size[1]));
  program->SetUniformf("planeTolerance", static_cast<float>(this->PlaneTolerance));
  program->SetUniformf("normalTolerance", static_cast<float>(this->NormalTolerance));
  const double* b = this->ReceiverBounds;
  program->SetUniformi("hasReceiverBounds", this->HasReceiverBounds ? 1 : 0);
  program->SetUniform3f(
    "receiverMin", static_cast<float>(b[0]), static_cast<float>(b[2]), static_cast<float>(b[4]));
  program->SetUniform3f(
    "receiverMax", static_cast<float>(b[1]), static_cast<float>(b[3]), static_cast<float>(b[5]));
  this->Triangle->Draw(); // blended additively into the caller's target (Splat())
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  program->Unbind(renWin);
  return true;
}

void vtkCausticsPhotonSplatter::SetRecordUniforms(vtkCausticsShaderProgram* program,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed, const int size[2],
  const float worldToClip[16])
{
  vtkTextureObject* inputs[] = { landed.Position, landed.Direction, landed.Flux };
  const char* names[] = { "hitPosition", "hitNormal", "hitFlux" };
  for (int i = 0; i < 3; ++i)
  {
    program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
  }
  program->SetUniform2i("hitGrid", grid.Width, grid.Height);
  program->SetUniformi("hitBranchRows", grid.BranchRows > 0 ? grid.BranchRows : grid.Height);
  program->SetUniformi("hitLightType", grid.LightType);
  program->SetUniformf("triangleStretch", static_cast<float>(this->TriangleStretch));
  program->SetUniformMatrix4("triangleWorldToClip", worldToClip);
  program->SetUniform2f(
    "triangleViewport", static_cast<float>(size[0]), static_cast<float>(size[1]));
}

bool vtkCausticsPhotonSplatter::ClassifyTriangles(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed, const int size[2],
  const float worldToClip[16])
{
  caustics::gl::EnsureTexture(this->TriangleMask, renWin, grid.Width, grid.Height, GL_R32UI);
  vtkCausticsShaderProgram* program = this->ClassifyProgram;
  if (!program->Bind(renWin))
  {
    return false;
  }
  landed.Position->Activate();
  landed.Direction->Activate();
  landed.Flux->Activate();
  this->SetRecordUniforms(program, grid, landed, size, worldToClip);
  glBindImageTexture(0, this->TriangleMask->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
  program->DispatchCovering2D(grid.Width, grid.Height, 16, 16);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
  landed.Position->Deactivate();
  landed.Direction->Deactivate();
  landed.Flux->Deactivate();
  program->Unbind(renWin);
  return true;
}

bool vtkCausticsPhotonSplatter::DrawTriangles(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
  vtkCausticsGBuffer* target, const float worldToClip[16])
{
  vtkCausticsShaderProgram* program = this->TriangleProgram;
  if (!program->Bind(renWin))
  {
    return false;
  }
  vtkTextureObject* inputs[] = { landed.Position, landed.Direction, landed.Flux,
    this->TriangleMask, target->GetPositionTexture(), target->GetNormalTexture() };
  for (vtkTextureObject* input : inputs)
  {
    input->Activate();
  }
  this->SetRecordUniforms(program, grid, landed, target->GetSize(), worldToClip);
  program->SetUniformi("triangleMask", this->TriangleMask->GetTextureUnit());
  program->SetUniformi("targetPosition", target->GetPositionTexture()->GetTextureUnit());
  program->SetUniformi("targetNormal", target->GetNormalTexture()->GetTextureUnit());
  float clipToWorld[16];
  caustics::gl::InvertColumnMajor(worldToClip, clipToWorld);
  program->SetUniformMatrix4("clipToWorld", clipToWorld);
  program->SetUniformf("planeTolerance", static_cast<float>(this->PlaneTolerance));
  program->SetUniformf("normalTolerance", static_cast<float>(this->NormalTolerance));
  glBindVertexArray(this->VertexArray);
  // Six vertices (a screen rectangle) per triangle, two triangles per grid cell.
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(12 * grid.Count()));
  glBindVertexArray(0);
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  program->Unbind(renWin);
  return true;
}

bool vtkCausticsPhotonSplatter::DrawSplats(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonGrid& grid, const caustics::PhotonRecords& landed,
  vtkTextureObject* kernelRadius, vtkCausticsGBuffer* target, const float worldToClip[16])
{
  if (!this->Program->Bind(renWin))
  {
    return false;
  }
  const bool triangles = this->Reconstruction == TRIANGLES;
  if (!triangles && !this->TriangleMask->GetHandle())
  {
    // Unread without triangles, but its unsigned sampler must not share a unit with
    // a float one (an invalid draw for the GL): a texel of its own.
    caustics::gl::EnsureTexture(this->TriangleMask, renWin, 1, 1, GL_R32UI);
  }
  vtkTextureObject* inputs[] = { landed.Position, landed.Direction, landed.Flux, kernelRadius,
    target->GetPositionTexture(), target->GetNormalTexture(), this->TriangleMask };
  const char* names[] = { "hitPosition", "hitNormal", "hitFlux", "kernelRadius", "targetPosition",
    "targetNormal", "triangleMask" };
  for (int i = 0; i < 7; ++i)
  {
    inputs[i]->Activate();
    this->Program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
  }
  const int* size = target->GetSize();
  this->Program->SetUniformi("hitWidth", grid.Width);
  this->Program->SetUniformi("triangles", triangles ? 1 : 0);
  this->Program->SetUniform2i("hitGridSize", grid.Width, grid.Height);
  this->Program->SetUniformMatrix4("worldToClip", worldToClip);
  this->Program->SetUniform2f("viewport", static_cast<float>(size[0]), static_cast<float>(size[1]));
  this->Program->SetUniformf("minimumRadiusPixels", static_cast<float>(this->MinimumRadiusPixels));
  this->Program->SetUniformf("maximumRadiusPixels", static_cast<float>(this->MaximumRadiusPixels));
  this->Program->SetUniformf("planeTolerance", static_cast<float>(this->PlaneTolerance));
  this->Program->SetUniformf("normalTolerance", static_cast<float>(this->NormalTolerance));
  // The GL discards a point whose centre is outside the clip volume, sprite and all:
  // a photon that landed just outside the view would not light the pixels its kernel
  // covers inside it, and every image read low along its borders (0.6 of the
  // reference in the outermost pixels). The points are drawn into a viewport wider by
  // the largest sprite's reach on each side, their positions shrunk to match, so that
  // each keeps its pixel; what falls outside the framebuffer is discarded as before.
  const int guard = static_cast<int>(std::ceil(1.4143 * this->MaximumRadiusPixels)) + 2;
  this->Program->SetUniform2f("guardScale",
    static_cast<float>(size[0]) / static_cast<float>(size[0] + 2 * guard),
    static_cast<float>(size[1]) / static_cast<float>(size[1] + 2 * guard));
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglViewport viewport(state);
  state->vtkglViewport(-guard, -guard, size[0] + 2 * guard, size[1] + 2 * guard);
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
  this->ClassifyProgram->ReleaseGraphicsResources(win);
  this->TriangleProgram->ReleaseGraphicsResources(win);
  this->TriangleMask->ReleaseGraphicsResources(win);
  this->EndsProgram->ReleaseGraphicsResources(win);
  this->KernelFramebuffer->ReleaseGraphicsResources(win);
  this->KernelIrradiance->ReleaseGraphicsResources(win);
  this->KernelRadii->ReleaseGraphicsResources(win);
  this->Triangle->Release();
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
  os << indent << "Reconstruction: " << (this->Reconstruction == TRIANGLES ? "triangles" : "splats")
     << "\n";
  os << indent << "TriangleStretch: " << this->TriangleStretch << "\n";
  os << indent << "KeepFluxAtReceiverEnds: " << (this->KeepFluxAtReceiverEnds ? "on" : "off")
     << "\n";
  os << indent << "ReceiverBounds: ";
  if (this->HasReceiverBounds)
  {
    const double* b = this->ReceiverBounds;
    os << "(" << b[0] << ", " << b[1] << ", " << b[2] << ", " << b[3] << ", " << b[4] << ", "
       << b[5] << ")\n";
  }
  else
  {
    os << "(none)\n";
  }
}
