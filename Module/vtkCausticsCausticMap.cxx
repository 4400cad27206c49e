#include "vtkCausticsCausticMap.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsCausticMapSettings.h"
#include "vtkCausticsDistanceImpostors.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsPhotonBufferHierarchy.h"
#include "vtkCausticsPhotonBufferUtilities.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsCausticMapApplyFS.h"
#include "vtkCausticsCausticMapSplatVS.h"
#include "vtkCausticsFullScreenVS.h"
#include "vtkCausticsImpostorCommon.h"
#include "vtkCausticsPhotonBufferCommon.h"
#include "vtkCausticsPhotonSplatFS.h"
#include "vtkCausticsSplatCoverage.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsCausticMap);

struct vtkCausticsCausticMap::Internals
{
  caustics::LightView View;
  bool HasView = false;
};

vtkCausticsCausticMap::vtkCausticsCausticMap()
  : Internal(new Internals)
  , Triangle(new caustics::gl::FullScreenTriangle)
{
  for (int j = 0; j < 4; ++j)
  {
    this->Receivers[j] = vtkSmartPointer<vtkCausticsGBuffer>::New();
    this->Receivers[j]->AlbedoOff(); // the visibility test reads positions and normals
    this->Irradiance[j] = vtkSmartPointer<vtkTextureObject>::New();
    this->Framebuffers[j] = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  }
  const std::string common = vtkCausticsPhotonBufferCommon;
  this->SplatProgram->SetName("caustic map splat");
  this->SplatProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->SplatProgram->SetVertexSource(
    (common + vtkCausticsSplatCoverage + vtkCausticsCausticMapSplatVS).c_str());
  this->SplatProgram->SetFragmentSource(vtkCausticsPhotonSplatFS);
  this->ApplyProgram->SetName("caustic map final render");
  this->ApplyProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->ApplyProgram->SetVertexSource(vtkCausticsFullScreenVS);
  this->ApplyProgram->SetFragmentSource((common + vtkCausticsCausticMapApplyFS).c_str());
  this->StoreProgram->SetName("caustic map final render: the caustic store");
  this->StoreProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->StoreProgram->SetDefine("CAUSTICS_STORE", 1);
  this->StoreProgram->SetVertexSource(vtkCausticsFullScreenVS);
  this->StoreProgram->SetFragmentSource(
    (common + vtkCausticsImpostorCommon + vtkCausticsCausticMapApplyFS).c_str());
}

vtkCausticsCausticMap::~vtkCausticsCausticMap()
{
  delete this->Triangle;
  if (this->VertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): vertex array leaked");
  }
}

int vtkCausticsCausticMap::GetLevelResolution(int j) const
{
  return std::max(1, this->Resolution >> std::max(0, std::min(j, 3)));
}

vtkTextureObject* vtkCausticsCausticMap::GetIrradianceTexture(int j)
{
  return j >= 0 && j < 4 ? this->Irradiance[j].GetPointer() : nullptr;
}

vtkCausticsGBuffer* vtkCausticsCausticMap::GetReceivers(int j)
{
  return j >= 0 && j < 4 ? this->Receivers[j].GetPointer() : nullptr;
}

bool vtkCausticsCausticMap::RenderReceivers(vtkOpenGLRenderWindow* renWin,
  const caustics::CausticMapSettings& settings, vtkCausticsSceneGeometry* geometry,
  const caustics::LightView& view, vtkCausticsCausticMap* front)
{
  this->Resolution = settings.CausticMapResolution;
  this->NumberOfLevels = settings.NumberOfLevels();
  this->Internal->View = view;
  this->Internal->HasView = true;
  float matrix[16];
  caustics::gl::ToColumnMajor(view.worldToClip, matrix);
  // The view's eye, or its direction of sight: which receivers face it.
  const double viewOrigin[4] = { view.perspective ? view.eye[0] : view.axis[0],
    view.perspective ? view.eye[1] : view.axis[1], view.perspective ? view.eye[2] : view.axis[2],
    view.perspective ? 1.0 : 0.0 };
  bool ok = true;
  for (int j = 0; j < this->NumberOfLevels; ++j)
  {
    const int size = this->GetLevelResolution(j);
    if (front)
    {
      this->Receivers[j]->SetPeelBehind(front->Receivers[j], viewOrigin);
    }
    else
    {
      this->Receivers[j]->ClearPeel();
    }
    ok = this->Receivers[j]->Render(
           renWin, geometry, matrix, size, size, vtkCausticsSceneGeometry::RoleBit(1)) &&
      ok;
  }
  return ok;
}

bool vtkCausticsCausticMap::Splat(vtkOpenGLRenderWindow* renWin,
  const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
  const caustics::PhotonRecords& landed, vtkCausticsPhotonBufferHierarchy* hierarchy,
  const caustics::Camera* camera, vtkCausticsCausticMap* otherLayer, bool hiddenOnly)
{
  if (!this->Internal->HasView || !landed.IsSet() || !hierarchy)
  {
    vtkErrorMacro(<< "Splat needs RenderReceivers() first, a photon buffer and its hierarchy");
    return false;
  }
  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglEnableDisable pointSize(state, GL_PROGRAM_POINT_SIZE);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_DEPTH_TEST);

  // Clear every level first (levels left out this frame must read zero).
  this->ClearLevels(renWin);

  vtkCausticsShaderProgram* program = this->SplatProgram;
  bool ok = program->Bind(renWin);
  if (ok)
  {
    if (!this->VertexArray)
    {
      glCreateVertexArrays(1, &this->VertexArray);
    }
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    state->vtkglEnable(GL_PROGRAM_POINT_SIZE);
    vtkTextureObject* inputs[] = { landed.Position, landed.Direction, landed.Flux,
      hierarchy->GetSplatRadiusTexture() };
    const char* names[] = { "hitPosition", "hitNormal", "hitFlux", "splatRadiusTexture" };
    for (int i = 0; i < 4; ++i)
    {
      inputs[i]->Activate();
      program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
    }
    this->SetSplatUniforms(program, settings, grid, hierarchy, camera);
    program->SetUniformi("hiddenOnly", hiddenOnly ? 1 : 0);
    hierarchy->GetNodeBuffer().BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_NODES_BINDING);
    hierarchy->GetSplatBuffer().BindBase(
      GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_SPLATS_BINDING);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, hierarchy->GetControlBuffer().Handle());
    glBindVertexArray(this->VertexArray);
    this->DrawLevels(state, program, hierarchy, otherLayer);
    glBindVertexArray(0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    for (vtkTextureObject* input : inputs)
    {
      input->Deactivate();
    }
    program->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  return ok;
}

void vtkCausticsCausticMap::ClearIrradiance(vtkOpenGLRenderWindow* renWin)
{
  vtkTextureObject* finest = this->Irradiance[0];
  if (finest->GetHandle() != 0 && finest->GetContext() == renWin &&
    static_cast<int>(finest->GetWidth()) == this->GetLevelResolution(0))
  {
    return; // allocated and cleared already; nothing draws into it meanwhile
  }
  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  this->ClearLevels(renWin);
  state->PopFramebufferBindings();
}

void vtkCausticsCausticMap::ClearLevels(vtkOpenGLRenderWindow* renWin)
{
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  for (int j = 0; j < 4; ++j)
  {
    const int size = j < this->NumberOfLevels ? this->GetLevelResolution(j) : 1;
    const bool resized =
      caustics::gl::EnsureTexture(this->Irradiance[j], renWin, size, size, GL_RGBA32F);
    vtkOpenGLFramebufferObject* framebuffer = this->Framebuffers[j];
    framebuffer->SetContext(renWin);
    framebuffer->Bind();
    if (resized || framebuffer->GetNumberOfColorAttachments() != 1)
    {
      framebuffer->AddColorAttachment(0, this->Irradiance[j]);
    }
    framebuffer->ActivateDrawBuffers(1);
    glClearBufferfv(GL_COLOR, 0, zero);
  }
}

void vtkCausticsCausticMap::SetSplatUniforms(vtkCausticsShaderProgram* program,
  const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
  vtkCausticsPhotonBufferHierarchy* hierarchy, const caustics::Camera* camera)
{
  program->SetUniformi("gridWidth", grid.Width);
  for (int k = 0; k < caustics::hcm::MaxTraversalLevels; ++k)
  {
    const std::string index = "[" + std::to_string(k) + "]";
    program->SetUniformu(("nodeOffsets" + index).c_str(), hierarchy->GetNodeOffset(k));
    program->SetUniformi(("nodeRowLength" + index).c_str(), hierarchy->GetNodeRowLength(k));
  }
  // Clusters get the hierarchy's camera floor too (its photons' kernels have it).
  const bool cameraFloor =
    camera && settings.SplatMode != caustics::CausticMapSettings::SPLAT_CONSTANT;
  if (camera)
  {
    caustics::hcm::SetCameraViewUniforms(program, "cameraView", *camera);
  }
  program->SetUniformf("minimumCameraRadiusPixels",
    cameraFloor ? static_cast<float>(settings.MinimumCameraSplatRadius) : 0.0f);
  program->SetUniformf("minimumRadiusPixels", static_cast<float>(settings.MinimumSplatRadius));
  program->SetUniformf("maximumRadiusPixels", static_cast<float>(settings.MaximumSplatRadius));
  program->SetUniformf("clusterRadiusPixels",
    static_cast<float>(std::max(settings.ClusterRadius(), settings.MinimumSplatRadius)));
  program->SetUniformf("planeTolerance", static_cast<float>(this->PlaneTolerance));
  program->SetUniformf("normalTolerance", static_cast<float>(this->NormalTolerance));
}

void vtkCausticsCausticMap::DrawLevels(vtkOpenGLState* state, vtkCausticsShaderProgram* program,
  vtkCausticsPhotonBufferHierarchy* hierarchy, vtkCausticsCausticMap* otherLayer)
{
  for (int j = 0; j < this->NumberOfLevels; ++j)
  {
    const int size = this->GetLevelResolution(j);
    vtkCausticsGBuffer* target = this->Receivers[j];
    vtkTextureObject* targetPosition = target->GetPositionTexture();
    vtkTextureObject* targetNormal = target->GetNormalTexture();
    targetPosition->Activate();
    targetNormal->Activate();
    program->SetUniformi("targetPosition", targetPosition->GetTextureUnit());
    program->SetUniformi("targetNormal", targetNormal->GetTextureUnit());
    // The other layer's receivers of this level, where it has them (the same view and
    // size: rendered with the same settings).
    vtkCausticsGBuffer* other = otherLayer && j < otherLayer->NumberOfLevels &&
        otherLayer->GetLevelResolution(j) == size
      ? otherLayer->Receivers[j].GetPointer()
      : nullptr;
    vtkTextureObject* otherPosition = other ? other->GetPositionTexture() : nullptr;
    vtkTextureObject* otherNormal = other ? other->GetNormalTexture() : nullptr;
    const bool hasOther = otherPosition && otherNormal;
    program->SetUniformi("hasOtherLayer", hasOther ? 1 : 0);
    if (hasOther)
    {
      otherPosition->Activate();
      otherNormal->Activate();
    }
    // Unused when there is none, but a sampler must name a unit of its type.
    program->SetUniformi(
      "otherPosition", (hasOther ? otherPosition : targetPosition)->GetTextureUnit());
    program->SetUniformi("otherNormal", (hasOther ? otherNormal : targetNormal)->GetTextureUnit());
    caustics::hcm::SetViewUniforms(program, "targetView", this->Internal->View, size, size);
    program->SetUniformu("listOffset", static_cast<unsigned int>(j) * hierarchy->GetSplatRegion());
    this->Framebuffers[j]->Bind();
    this->Framebuffers[j]->ActivateDrawBuffers(1);
    state->vtkglViewport(0, 0, size, size);
    glDrawArraysIndirect(GL_POINTS,
      reinterpret_cast<const void*>(
        static_cast<std::size_t>(vtkCausticsPhotonBufferHierarchy::GetDrawArgumentsOffset(j))));
    if (hasOther)
    {
      otherPosition->Deactivate();
      otherNormal->Deactivate();
    }
    targetPosition->Deactivate();
    targetNormal->Deactivate();
  }
}

bool vtkCausticsCausticMap::Apply(vtkOpenGLRenderWindow* renWin, vtkCausticsGBuffer* camera,
  const caustics::Camera& view, vtkCausticsCausticMap* front,
  const caustics::gl::StorageBuffer* drawArguments, std::size_t drawOffset)
{
  return this->DrawFinal(
    renWin, this->ApplyProgram, camera, view, front, nullptr, drawArguments, drawOffset);
}

bool vtkCausticsCausticMap::ApplyStore(vtkOpenGLRenderWindow* renWin, vtkCausticsGBuffer* camera,
  const caustics::Camera& view, vtkCausticsCausticMap* hidden, vtkCausticsDistanceImpostors* store,
  const caustics::gl::StorageBuffer& drawArguments, std::size_t drawOffset)
{
  if (!store)
  {
    vtkErrorMacro(<< "ApplyStore needs the distance impostors whose store took the photons");
    return false;
  }
  // The hidden receivers' map stands where Apply() takes its front map: a pixel it sees
  // is its own.
  return this->DrawFinal(
    renWin, this->StoreProgram, camera, view, hidden, store, &drawArguments, drawOffset);
}

bool vtkCausticsCausticMap::DrawFinal(vtkOpenGLRenderWindow* renWin,
  vtkCausticsShaderProgram* program, vtkCausticsGBuffer* camera, const caustics::Camera& view,
  vtkCausticsCausticMap* front, vtkCausticsDistanceImpostors* store,
  const caustics::gl::StorageBuffer* drawArguments, std::size_t drawOffset)
{
  if (!this->Internal->HasView || !camera)
  {
    vtkErrorMacro(<< "Apply needs RenderReceivers() and Splat() first, and a camera G-buffer");
    return false;
  }
  if (!program->Bind(renWin))
  {
    return false;
  }
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);

  std::vector<vtkTextureObject*> bound;
  auto bind = [&](vtkTextureObject* texture, const std::string& name)
  {
    texture->Activate();
    program->SetUniformi(name.c_str(), texture->GetTextureUnit());
    bound.push_back(texture);
  };
  bind(camera->GetPositionTexture(), "gPosition");
  bind(camera->GetNormalTexture(), "gNormal");
  for (int j = 0; j < this->NumberOfLevels; ++j)
  {
    const std::string index = "[" + std::to_string(j) + "]";
    bind(this->Irradiance[j], "irradiance" + index);
    bind(this->Receivers[j]->GetPositionTexture(), "receiverPosition" + index);
    bind(this->Receivers[j]->GetNormalTexture(), "receiverNormal" + index);
    const int size = this->GetLevelResolution(j);
    caustics::hcm::SetViewUniforms(program, "mapViews" + index, this->Internal->View, size, size);
  }
  program->SetUniformi("levels", this->NumberOfLevels);
  caustics::hcm::SetCameraViewUniforms(program, "cameraView", view);
  // Without a front map its samplers still need textures: the map's own stand in.
  vtkCausticsGBuffer* frontReceivers = front ? front->Receivers[0] : this->Receivers[0];
  bind(frontReceivers->GetPositionTexture(), "frontPosition");
  bind(frontReceivers->GetNormalTexture(), "frontNormal");
  program->SetUniformi("hasFront", front ? 1 : 0);
  caustics::ssp::TextureUnits units(renWin); // the store's, held through the draw
  if (store)
  {
    store->SetUniforms(program, units);
  }
  if (drawArguments)
  {
    this->Triangle->DrawIndirect(*drawArguments, drawOffset);
  }
  else
  {
    this->Triangle->Draw();
  }
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
  program->Unbind(renWin);
  if (store)
  {
    glBindImageTexture(CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
  }
  return true;
}

void vtkCausticsCausticMap::ReleaseGraphicsResources(vtkWindow* win)
{
  for (int j = 0; j < 4; ++j)
  {
    this->Receivers[j]->ReleaseGraphicsResources(win);
    this->Irradiance[j]->ReleaseGraphicsResources(win);
    this->Framebuffers[j]->ReleaseGraphicsResources(win);
  }
  this->SplatProgram->ReleaseGraphicsResources(win);
  this->ApplyProgram->ReleaseGraphicsResources(win);
  this->StoreProgram->ReleaseGraphicsResources(win);
  this->Triangle->Release();
  if (this->VertexArray)
  {
    glDeleteVertexArrays(1, &this->VertexArray);
    this->VertexArray = 0;
  }
  this->Internal->HasView = false;
}

void vtkCausticsCausticMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "PlaneTolerance: " << this->PlaneTolerance << " radii\n";
  os << indent << "NormalTolerance: " << this->NormalTolerance << "\n";
  os << indent << "HasView: " << this->Internal->HasView << "\n";
}
