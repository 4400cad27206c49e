#include "vtkCausticsRenderPass.h"

#include "vtkCamera.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsSceneExtractor.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTimings.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsCompositeFS.h"
#include "vtkCausticsDirectIrradianceFS.h"
#include "vtkCausticsFullScreenVS.h"

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsRenderPass);

namespace
{
/** Binds a framebuffer with one colour attachment and clears it to zero. */
void BindAndClear(vtkOpenGLFramebufferObject* framebuffer, vtkTextureObject* texture,
  vtkOpenGLRenderWindow* renWin, bool attach)
{
  framebuffer->SetContext(renWin);
  framebuffer->Bind();
  if (attach || framebuffer->GetNumberOfColorAttachments() != 1)
  {
    framebuffer->AddColorAttachment(0, texture);
  }
  framebuffer->ActivateDrawBuffers(1);
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glClearBufferfv(GL_COLOR, 0, zero);
}
}

vtkCausticsRenderPass::vtkCausticsRenderPass()
  : Triangle(new caustics::gl::FullScreenTriangle)
{
  this->ShadowBuffers->SetFocus(vtkCausticsLightBuffers::FOCUS_SCENE);
  this->DirectProgram->SetName("direct irradiance");
  this->DirectProgram->SetVertexSource(vtkCausticsFullScreenVS);
  this->DirectProgram->SetFragmentSource(vtkCausticsDirectIrradianceFS);
  this->DirectProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->CompositeProgram->SetName("caustics composite");
  this->CompositeProgram->SetVertexSource(vtkCausticsFullScreenVS);
  this->CompositeProgram->SetFragmentSource(vtkCausticsCompositeFS);
  this->CompositeProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  for (float& v : this->WorldToClip)
  {
    v = 0.0f;
  }
}

vtkCausticsRenderPass::~vtkCausticsRenderPass()
{
  delete this->Triangle;
  if (this->DelegatePass)
  {
    this->DelegatePass->Delete();
    this->DelegatePass = nullptr;
  }
}

void vtkCausticsRenderPass::SetRoughnessCutoff(double cutoff)
{
  this->Extractor->SetRoughnessCutoff(cutoff);
  this->Modified();
}

double vtkCausticsRenderPass::GetRoughnessCutoff()
{
  return this->Extractor->GetRoughnessCutoff();
}

void vtkCausticsRenderPass::StartStage(const char* name)
{
  this->Timings->StartStage(name);
}

void vtkCausticsRenderPass::StopStage(const char* name)
{
  this->Timings->StopStage(name);
}

bool vtkCausticsRenderPass::NeedsCaustics()
{
  const caustics::SceneData& scene = this->Extractor->GetScene();
  if (!scene.HasSpecular || scene.Lights.empty())
  {
    return false;
  }
  bool hasReceiver = false;
  for (const auto& material : scene.Materials)
  {
    hasReceiver = hasReceiver || material.role == caustics::Role::Receiver;
  }
  bool hasPower = false;
  for (const auto& light : scene.Lights)
  {
    hasPower =
      hasPower || light.radiometric[0] > 0 || light.radiometric[1] > 0 || light.radiometric[2] > 0;
  }
  return hasReceiver && hasPower;
}

bool vtkCausticsRenderPass::RenderCausticIrradiance(vtkOpenGLRenderWindow*)
{
  return true; // no technique: the caustic irradiance stays zero
}

void vtkCausticsRenderPass::ReleaseTechniqueResources(vtkWindow*) {}

bool vtkCausticsRenderPass::RenderTechniqueColor(vtkOpenGLRenderWindow*)
{
  return false; // no technique: VTK's colour everywhere
}

bool vtkCausticsRenderPass::PrepareScene(vtkRenderer* renderer, vtkOpenGLRenderWindow*)
{
  if (!this->Extractor->Update(renderer, this->Width, this->Height))
  {
    return false;
  }
  caustics::gl::ToColumnMajor(this->Extractor->GetScene().View.worldToClip, this->WorldToClip);
  return true;
}

void vtkCausticsRenderPass::RenderDelegate(const vtkRenderState* s)
{
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(s->GetRenderer()->GetRenderWindow());
  const int w = this->Width, h = this->Height;
  bool resized = caustics::gl::EnsureTexture(this->DelegateColorTexture, renWin, w, h, GL_RGBA32F);
  resized |=
    caustics::gl::EnsureTexture(this->DelegateDepthTexture, renWin, w, h, GL_DEPTH_COMPONENT32F);

  this->PreRender(s);
  this->DelegateFramebuffer->SetContext(renWin);
  this->DelegateFramebuffer->SaveCurrentBindingsAndBuffers();
  this->DelegateFramebuffer->Bind();
  if (resized || this->DelegateFramebuffer->GetNumberOfColorAttachments() != 1)
  {
    this->DelegateFramebuffer->AddColorAttachment(0, this->DelegateColorTexture);
    this->DelegateFramebuffer->AddDepthAttachment(this->DelegateDepthTexture);
  }
  this->DelegateFramebuffer->ActivateDrawBuffers(1);
  this->DelegateFramebuffer->StartNonOrtho(w, h);
  this->DelegatePass->Render(s);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  this->DelegateFramebuffer->UnBind();
  this->DelegateFramebuffer->RestorePreviousBindingsAndBuffers();
  this->PostRender(s);
}

bool vtkCausticsRenderPass::RenderCameraGBuffers(vtkOpenGLRenderWindow* renWin)
{
  const int opaque = vtkCausticsSceneGeometry::RoleBit(1) | vtkCausticsSceneGeometry::RoleBit(2);
  const int refractive = vtkCausticsSceneGeometry::RoleBit(3);
  bool ok = this->CameraGBuffer->Render(
    renWin, this->Geometry, this->WorldToClip, this->Width, this->Height, opaque);
  ok = this->RefractiveGBuffer->Render(
         renWin, this->Geometry, this->WorldToClip, this->Width, this->Height, refractive) &&
    ok;
  return ok;
}

bool vtkCausticsRenderPass::RenderLightBuffers(vtkOpenGLRenderWindow* renWin)
{
  this->LightBuffers->SetResolution(this->LightBufferResolution);
  return this->LightBuffers->Render(renWin, this->Geometry, this->Extractor->GetScene());
}

bool vtkCausticsRenderPass::RenderCaustics(vtkOpenGLRenderWindow* renWin)
{
  vtkOpenGLState* state = renWin->GetState();
  const bool resized = caustics::gl::EnsureTexture(
    this->CausticTexture, renWin, this->Width, this->Height, GL_RGBA32F);
  state->PushFramebufferBindings();
  BindAndClear(this->CausticFramebuffer, this->CausticTexture, renWin, resized);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, this->Width, this->Height);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_SCISSOR_TEST);
  const bool ok = this->RenderCausticIrradiance(renWin);
  state->PopFramebufferBindings();
  return ok;
}

bool vtkCausticsRenderPass::RenderDirectIrradiance(vtkOpenGLRenderWindow* renWin)
{
  const caustics::SceneData& scene = this->Extractor->GetScene();
  this->ShadowBuffers->SetResolution(this->ShadowMapResolution);
  if (!this->ShadowBuffers->Render(renWin, this->Geometry, scene))
  {
    return false;
  }
  vtkOpenGLState* state = renWin->GetState();
  const bool resized =
    caustics::gl::EnsureTexture(this->DirectTexture, renWin, this->Width, this->Height, GL_RGBA32F);
  state->PushFramebufferBindings();
  BindAndClear(this->DirectFramebuffer, this->DirectTexture, renWin, resized);
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, this->Width, this->Height);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);

  vtkCausticsShaderProgram* program = this->DirectProgram;
  bool ok = program->Bind(renWin);
  if (ok)
  {
    vtkTextureObject* position = this->CameraGBuffer->GetPositionTexture();
    vtkTextureObject* normal = this->CameraGBuffer->GetNormalTexture();
    position->Activate();
    normal->Activate();
    program->SetUniformi("gPosition", position->GetTextureUnit());
    program->SetUniformi("gNormal", normal->GetTextureUnit());
    const caustics::Camera& view = scene.View;
    double direction[3];
    for (int i = 0; i < 3; ++i)
    {
      direction[i] = view.focalPoint[i] - view.position[i];
    }
    const double length = std::sqrt(
      direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    program->SetUniform3f("cameraPosition", static_cast<float>(view.position[0]),
      static_cast<float>(view.position[1]), static_cast<float>(view.position[2]));
    program->SetUniform3f("cameraDirection", static_cast<float>(direction[0] / length),
      static_cast<float>(direction[1] / length), static_cast<float>(direction[2] / length));
    program->SetUniformi("cameraParallel", view.parallel ? 1 : 0);
    for (int i = 0; i < this->ShadowBuffers->GetNumberOfLights(); ++i)
    {
      const caustics::Light& light = scene.Lights[i];
      const caustics::LightView& lightView = this->ShadowBuffers->GetView(i);
      vtkTextureObject* shadow = this->ShadowBuffers->GetGBuffer(i)->GetPositionTexture();
      shadow->Activate();
      program->SetUniformi("shadowPosition", shadow->GetTextureUnit());
      float matrix[16];
      caustics::gl::ToColumnMajor(lightView.worldToClip, matrix);
      program->SetUniformMatrix4("lightWorldToClip", matrix);
      program->SetUniformi("lightType", static_cast<int>(light.type));
      // Directional lights measure distance along the axis from the view's eye.
      const caustics::Vec3& origin =
        light.type == caustics::Light::Type::Directional ? lightView.eye : light.position;
      program->SetUniform3f("lightPosition", static_cast<float>(origin[0]),
        static_cast<float>(origin[1]), static_cast<float>(origin[2]));
      program->SetUniform3f("lightDirection", static_cast<float>(light.direction[0]),
        static_cast<float>(light.direction[1]), static_cast<float>(light.direction[2]));
      program->SetUniform3f("radiometric", static_cast<float>(light.radiometric[0]),
        static_cast<float>(light.radiometric[1]), static_cast<float>(light.radiometric[2]));
      program->SetUniformf("cosOuter", static_cast<float>(light.cosOuter));
      program->SetUniformf("cosInner", static_cast<float>(light.cosInner));
      program->SetUniformf("texelWorldSize",
        static_cast<float>(2.0 * lightView.halfExtent / this->ShadowMapResolution));
      this->Triangle->Draw();
      shadow->Deactivate();
    }
    position->Deactivate();
    normal->Deactivate();
    program->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  return ok;
}

void vtkCausticsRenderPass::Composite(vtkOpenGLRenderWindow* renWin, bool toFinalTexture)
{
  vtkOpenGLState* state = renWin->GetState();
  vtkCausticsShaderProgram* program = this->CompositeProgram;
  if (!program->Bind(renWin))
  {
    return;
  }
  vtkTextureObject* textures[] = { this->DelegateColorTexture, this->DelegateDepthTexture,
    this->CameraGBuffer->GetNormalTexture(), this->CameraGBuffer->GetAlbedoTexture(),
    this->CameraGBuffer->GetDepthTexture(), this->CausticTexture, this->VolumeTexture,
    this->TechniqueColorTexture };
  const char* names[] = { "delegateColor", "delegateDepth", "gNormal", "gAlbedo", "gDepth",
    "causticIrradiance", "volumeRadiance", "techniqueColor" };
  const bool hasCaustics = this->LastFrameHadCaustics;
  const bool hasVolume = hasCaustics && this->TechniqueWroteVolume;
  const bool hasTechniqueColor = hasCaustics && this->LastFrameHadTechniqueColor;
  for (int i = 0; i < 8; ++i)
  {
    const bool used =
      i < 2 || (hasCaustics && i < 6) || (hasVolume && i == 6) || (hasTechniqueColor && i == 7);
    if (used)
    {
      textures[i]->Activate();
      program->SetUniformi(names[i], textures[i]->GetTextureUnit());
    }
  }
  program->SetUniformi("hasCaustics", hasCaustics ? 1 : 0);
  program->SetUniformi("hasVolume", hasVolume ? 1 : 0);
  program->SetUniformi("hasTechniqueColor", hasTechniqueColor ? 1 : 0);
  // The two depth buffers come from the same triangles and matrix; allow float noise.
  program->SetUniformf("depthTolerance", 2e-6f);

  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglDisable(GL_BLEND);
  if (toFinalTexture)
  {
    const bool resized = caustics::gl::EnsureTexture(
      this->FinalTexture, renWin, this->Width, this->Height, GL_RGBA32F);
    state->PushFramebufferBindings();
    BindAndClear(this->FinalFramebuffer, this->FinalTexture, renWin, resized);
    vtkOpenGLState::ScopedglViewport viewport(state);
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglViewport(0, 0, this->Width, this->Height);
    state->vtkglDisable(GL_DEPTH_TEST);
    this->Triangle->Draw();
    state->PopFramebufferBindings();
  }
  else
  {
    // Into the framebuffer the pass was called with, replacing its depth.
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthFunc(GL_ALWAYS);
    vtkOpenGLState::ScopedglDepthMask depthMask(state);
    state->vtkglDepthMask(GL_TRUE);
    this->Triangle->Draw();
  }
  for (int i = 0; i < 8; ++i)
  {
    if (textures[i]->GetHandle() && textures[i]->IsBound())
    {
      textures[i]->Deactivate();
    }
  }
  program->Unbind(renWin);
}

void vtkCausticsRenderPass::Render(const vtkRenderState* s)
{
  vtkOpenGLClearErrorMacro();
  this->NumberOfRenderedProps = 0;
  vtkRenderer* renderer = s->GetRenderer();
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  this->LastWindow = renWin;
  if (!this->DelegatePass)
  {
    vtkRenderStepsPass* steps = vtkRenderStepsPass::New();
    this->SetDelegatePass(steps);
    steps->Delete();
  }
  int x, y;
  renderer->GetTiledSizeAndOrigin(&this->Width, &this->Height, &x, &y);
  this->LastFrameHadCaustics = this->LastFrameHadDirect = this->LastFrameHadBuffers = false;
  this->LastFrameHadTechniqueColor = this->TechniqueWroteVolume = false;
  this->Timings->BeginFrame();

  this->Timings->StartStage("scene snapshot", false); // CPU work: no timer queries
  const bool sceneOk = this->PrepareScene(renderer, renWin);
  this->StopStage("scene snapshot");
  const bool caustics = sceneOk && this->NeedsCaustics();
  const bool buffers = caustics || this->ComputeDirectIrradiance || this->KeepBuffers;

  int major = 0, minor = 0;
  renWin->GetOpenGLVersion(major, minor);
  if (buffers && major * 10 + minor < 45)
  {
    vtkErrorMacro(<< "caustics need OpenGL 4.5 (compute shaders, SSBOs); this context is " << major
                  << "." << minor << ": rendering without caustics");
  }
  if (!sceneOk || !buffers || major * 10 + minor < 45)
  {
    // Nothing to add: VTK renders as if the pass were not there (timed on the CPU
    // only: timer queries would cost more than the rest of the pass here).
    this->Timings->StartStage("vtk delegate", false);
    this->DelegatePass->Render(s);
    this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
    this->StopStage("vtk delegate");
    this->Timings->EndFrame();
    return;
  }

  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blendSaver(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);

  this->StartStage("vtk delegate");
  this->RenderDelegate(s);
  this->StopStage("vtk delegate");

  this->StartStage("geometry upload");
  bool ok = this->Geometry->Upload(this->Extractor->GetScene(), renWin);
  this->StopStage("geometry upload");

  this->StartStage("camera g-buffers");
  ok = this->RenderCameraGBuffers(renWin) && ok;
  this->StopStage("camera g-buffers");
  this->LastFrameHadBuffers = true;

  if (caustics && ok)
  {
    this->StartStage("light buffers");
    ok = this->RenderLightBuffers(renWin);
    this->StopStage("light buffers");
    this->StartStage("caustic irradiance");
    ok = ok && this->RenderCaustics(renWin);
    this->StopStage("caustic irradiance");
    this->LastFrameHadCaustics = ok;
  }
  if (this->ComputeDirectIrradiance)
  {
    this->StartStage("direct irradiance");
    this->LastFrameHadDirect = this->RenderDirectIrradiance(renWin);
    this->StopStage("direct irradiance");
  }
  if (this->LastFrameHadCaustics)
  {
    this->LastFrameHadTechniqueColor = this->RenderTechniqueColor(renWin);
  }

  this->StartStage("composite");
  state->vtkglViewport(x, y, this->Width, this->Height);
  state->vtkglScissor(x, y, this->Width, this->Height);
  this->Composite(renWin, false);
  if (this->KeepBuffers)
  {
    this->Composite(renWin, true);
  }
  this->StopStage("composite");
  this->Timings->EndFrame();
  vtkOpenGLCheckErrorMacro("failed after Render");
}

bool vtkCausticsRenderPass::ReadBuffer(const char* name, vtkImageData* output)
{
  if (!name || !output)
  {
    vtkErrorMacro(<< "ReadBuffer needs a buffer name and an output image");
    return false;
  }
  vtkOpenGLRenderWindow* renWin = this->LastWindow;
  if (!renWin || !this->LastFrameHadBuffers)
  {
    vtkErrorMacro(<< "ReadBuffer('" << name
                  << "'): the last frame made no caustics buffers (nothing needed them; turn "
                     "KeepBuffers on to keep them)");
    return false;
  }
  renWin->MakeCurrent();
  const std::string request = name;
  std::string base = request;
  int light = -1;
  const auto colon = request.find(':');
  if (colon != std::string::npos)
  {
    base = request.substr(0, colon);
    try
    {
      light = std::stoi(request.substr(colon + 1));
    }
    catch (...)
    {
      light = -2;
    }
  }
  vtkTextureObject* texture = nullptr;
  int components = 4;
  if (base == "FinalColor" && this->KeepBuffers)
  {
    texture = this->FinalTexture;
    components = 3;
  }
  else if (base == "CausticIrradiance" && this->LastFrameHadCaustics)
  {
    texture = this->CausticTexture;
    components = 3;
  }
  else if (base == "DirectIrradiance" && this->LastFrameHadDirect)
  {
    texture = this->DirectTexture;
    components = 3;
  }
  else if (base == "VolumeRadiance" && this->LastFrameHadCaustics && this->TechniqueWroteVolume)
  {
    texture = this->VolumeTexture;
    components = 3;
  }
  else if (base == "TechniqueColor" && this->LastFrameHadCaustics &&
    this->LastFrameHadTechniqueColor)
  {
    texture = this->TechniqueColorTexture;
  }
  else if (base == "Position")
  {
    texture = this->CameraGBuffer->GetPositionTexture();
  }
  else if (base == "Normal")
  {
    texture = this->CameraGBuffer->GetNormalTexture();
  }
  else if (base == "Albedo")
  {
    texture = this->CameraGBuffer->GetAlbedoTexture();
  }
  else if (base == "Depth")
  {
    texture = this->CameraGBuffer->GetDepthTexture();
    components = 1;
  }
  else if (base == "RefractivePosition")
  {
    texture = this->RefractiveGBuffer->GetPositionTexture();
  }
  else if (base == "RefractiveNormal")
  {
    texture = this->RefractiveGBuffer->GetNormalTexture();
  }
  else if (base == "RefractiveDepth")
  {
    texture = this->RefractiveGBuffer->GetDepthTexture();
    components = 1;
  }
  else if (base == "ReceiverMask")
  {
    // Receivers not hidden behind a refractor: where caustic irradiance is defined.
    auto normal = caustics::gl::ReadTexture(this->CameraGBuffer->GetNormalTexture(), "n", 4);
    auto depth = caustics::gl::ReadTexture(this->CameraGBuffer->GetDepthTexture(), "d", 1);
    auto refractive = caustics::gl::ReadTexture(this->RefractiveGBuffer->GetDepthTexture(), "r", 1);
    output->Initialize();
    output->SetDimensions(this->Width, this->Height, 1);
    vtkNew<vtkFloatArray> mask;
    mask->SetName(name);
    mask->SetNumberOfTuples(static_cast<vtkIdType>(this->Width) * this->Height);
    vtkDataArray* n = normal->GetPointData()->GetArray(0);
    vtkDataArray* d = depth->GetPointData()->GetArray(0);
    vtkDataArray* r = refractive->GetPointData()->GetArray(0);
    for (vtkIdType i = 0; i < mask->GetNumberOfTuples(); ++i)
    {
      const bool receiver = std::lround(n->GetComponent(i, 3)) == 1;
      mask->SetValue(i, receiver && d->GetComponent(i, 0) <= r->GetComponent(i, 0) ? 1.0f : 0.0f);
    }
    output->GetPointData()->AddArray(mask);
    return true;
  }
  else if (light >= 0 && light < this->LightBuffers->GetNumberOfLights() &&
    this->LastFrameHadCaustics)
  {
    vtkCausticsGBuffer* lightBuffer = this->LightBuffers->GetGBuffer(light);
    if (base == "LightPosition")
    {
      texture = lightBuffer->GetPositionTexture();
    }
    else if (base == "LightNormal")
    {
      texture = lightBuffer->GetNormalTexture();
    }
    else if (base == "LightDepth")
    {
      texture = lightBuffer->GetDepthTexture();
      components = 1;
    }
    else if (base == "LightFlux")
    {
      texture = this->LightBuffers->GetFluxTexture(light);
    }
  }
  if (!texture || !texture->GetHandle())
  {
    vtkErrorMacro(<< "ReadBuffer: no buffer '" << name
                  << "' in the last frame (unknown name, light index out of range, or a stage "
                     "that did not run)");
    return false;
  }
  auto image = caustics::gl::ReadTexture(texture, name, components);
  output->ShallowCopy(image);
  return true;
}

void vtkCausticsRenderPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  this->ReleaseTechniqueResources(w);
  this->Geometry->ReleaseGraphicsResources(w);
  this->CameraGBuffer->ReleaseGraphicsResources(w);
  this->RefractiveGBuffer->ReleaseGraphicsResources(w);
  this->LightBuffers->ReleaseGraphicsResources(w);
  this->ShadowBuffers->ReleaseGraphicsResources(w);
  vtkTextureObject* textures[] = { this->CausticTexture, this->DirectTexture, this->VolumeTexture,
    this->DelegateColorTexture, this->DelegateDepthTexture, this->FinalTexture,
    this->TechniqueColorTexture };
  for (vtkTextureObject* texture : textures)
  {
    texture->ReleaseGraphicsResources(w);
  }
  vtkOpenGLFramebufferObject* framebuffers[] = { this->CausticFramebuffer, this->DirectFramebuffer,
    this->DelegateFramebuffer, this->FinalFramebuffer };
  for (vtkOpenGLFramebufferObject* framebuffer : framebuffers)
  {
    framebuffer->ReleaseGraphicsResources(w);
  }
  this->DirectProgram->ReleaseGraphicsResources(w);
  this->CompositeProgram->ReleaseGraphicsResources(w);
  this->Triangle->Release();
  this->Timings->ReleaseGraphicsResources();
  this->LastFrameHadBuffers = this->LastFrameHadCaustics = this->LastFrameHadDirect = false;
  this->LastFrameHadTechniqueColor = this->TechniqueWroteVolume = false;
}

void vtkCausticsRenderPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LightBufferResolution: " << this->LightBufferResolution << "\n";
  os << indent << "ShadowMapResolution: " << this->ShadowMapResolution << "\n";
  os << indent << "ComputeDirectIrradiance: " << this->ComputeDirectIrradiance << "\n";
  os << indent << "KeepBuffers: " << this->KeepBuffers << "\n";
  os << indent << "RoughnessCutoff: " << this->Extractor->GetRoughnessCutoff() << "\n";
  os << indent << "LastFrameHadCaustics: " << this->LastFrameHadCaustics << "\n";
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n";
  os << indent << "Scene:\n";
  this->Extractor->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Timings:\n" << this->Timings->GetReport();
}
