#include "vtkCausticsGBuffer.h"

#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsGBufferFS.h"
#include "vtkCausticsGBufferVS.h"

#include <cstdint>
#include <vector>

vtkStandardNewMacro(vtkCausticsGBuffer);

vtkCausticsGBuffer::vtkCausticsGBuffer()
{
  this->Program->SetName("G-buffer");
  this->Program->SetVertexSource(vtkCausticsGBufferVS);
  this->Program->SetFragmentSource(vtkCausticsGBufferFS);
}

vtkCausticsGBuffer::~vtkCausticsGBuffer() = default;

bool vtkCausticsGBuffer::Render(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
  const float worldToClip[16], int width, int height, int roleMask)
{
  // Nothing the targets depend on changed: they are still right (no GL work at all).
  std::vector<std::uint64_t> key{ reinterpret_cast<std::uintptr_t>(renWin),
    reinterpret_cast<std::uintptr_t>(geometry), geometry->GetContentVersion(),
    static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(height),
    static_cast<std::uint64_t>(roleMask), static_cast<std::uint64_t>(this->KeepFarthest),
    static_cast<std::uint64_t>(this->Albedo) };
  caustics::gl::AppendKey(key, worldToClip, 16);
  if (this->PeelFront)
  {
    // The front layer's own key stands for its content.
    key.push_back(reinterpret_cast<std::uintptr_t>(this->PeelFront));
    key.insert(key.end(), this->PeelFront->Key.begin(), this->PeelFront->Key.end());
    caustics::gl::AppendKey(key, this->PeelViewOrigin, 4);
  }
  this->LastRenderReused = this->ReuseUnchanged && key == this->Key;
  if (this->LastRenderReused)
  {
    return true;
  }
  this->Key.clear(); // until this Render() succeeds

  bool resized = false;
  resized |= caustics::gl::EnsureTexture(this->PositionTexture, renWin, width, height, GL_RGBA32F);
  resized |= caustics::gl::EnsureTexture(this->NormalTexture, renWin, width, height, GL_RGBA16F);
  if (this->Albedo)
  {
    resized |= caustics::gl::EnsureTexture(this->AlbedoTexture, renWin, width, height, GL_RGBA16F);
  }
  resized |=
    caustics::gl::EnsureTexture(this->DepthTexture, renWin, width, height, GL_DEPTH_COMPONENT32F);
  this->Size[0] = width;
  this->Size[1] = height;

  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  this->Framebuffer->SetContext(renWin);
  this->Framebuffer->Bind();
  // Without the albedo target the shader's third output has no draw buffer: GL
  // discards it.
  const int targets = this->Albedo ? 3 : 2;
  if (resized || this->Framebuffer->GetNumberOfColorAttachments() != targets)
  {
    this->Framebuffer->AddColorAttachment(0, this->PositionTexture);
    this->Framebuffer->AddColorAttachment(1, this->NormalTexture);
    if (this->Albedo)
    {
      this->Framebuffer->AddColorAttachment(2, this->AlbedoTexture);
    }
    else
    {
      this->Framebuffer->RemoveColorAttachment(2);
    }
    this->Framebuffer->AddDepthAttachment(this->DepthTexture);
  }
  this->Framebuffer->ActivateDrawBuffers(targets);
  if (!this->Albedo)
  {
    this->AlbedoTexture->ReleaseGraphicsResources(renWin); // detached above
  }

  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  // Stages draw whole off-screen targets: VTK may leave a scissor box set.
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglViewport(0, 0, width, height);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglDepthFunc(this->KeepFarthest ? GL_GREATER : GL_LESS);

  const float noSurface[4] = { 0.0f, 0.0f, 0.0f, -1.0f };
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  const float farDepth = this->KeepFarthest ? 0.0f : 1.0f;
  glClearBufferfv(GL_COLOR, 0, noSurface);
  glClearBufferfv(GL_COLOR, 1, zero);
  if (this->Albedo)
  {
    glClearBufferfv(GL_COLOR, 2, zero);
  }
  glClearBufferfv(GL_DEPTH, 0, &farDepth);

  vtkTextureObject* front = this->PeelFront ? this->PeelFront->GetPositionTexture() : nullptr;
  bool ok = !this->PeelFront ||
    (this->PeelFront->Size[0] == width && this->PeelFront->Size[1] == height &&
      !this->PeelFront->Key.empty());
  if (!ok)
  {
    vtkErrorMacro(<< "the layer to peel behind must be rendered first, at " << width << " x "
                  << height);
  }
  ok = ok && this->Program->Bind(renWin);
  if (ok)
  {
    this->Program->SetUniformMatrix4("worldToClip", worldToClip);
    this->Program->SetUniformi("peel", front ? 1 : 0);
    if (front)
    {
      front->Activate();
      this->Program->SetUniformi("peelFront", front->GetTextureUnit());
      const float origin[4] = { static_cast<float>(this->PeelViewOrigin[0]),
        static_cast<float>(this->PeelViewOrigin[1]), static_cast<float>(this->PeelViewOrigin[2]),
        static_cast<float>(this->PeelViewOrigin[3]) };
      this->Program->SetUniform4f("peelViewOrigin", origin);
    }
    geometry->BindMaterials();
    geometry->Draw(roleMask);
    if (front)
    {
      front->Deactivate();
    }
    this->Program->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  if (ok)
  {
    this->Key = std::move(key);
  }
  return ok;
}

void vtkCausticsGBuffer::SetPeelBehind(vtkCausticsGBuffer* front, const double viewOrigin[4])
{
  this->PeelFront = front != this ? front : nullptr;
  for (int i = 0; i < 4; ++i)
  {
    this->PeelViewOrigin[i] = viewOrigin[i];
  }
}

void vtkCausticsGBuffer::ReleaseGraphicsResources(vtkWindow* win)
{
  this->PositionTexture->ReleaseGraphicsResources(win);
  this->NormalTexture->ReleaseGraphicsResources(win);
  this->AlbedoTexture->ReleaseGraphicsResources(win);
  this->DepthTexture->ReleaseGraphicsResources(win);
  this->Framebuffer->ReleaseGraphicsResources(win);
  this->Program->ReleaseGraphicsResources(win);
  this->Size[0] = this->Size[1] = 0;
  this->Key.clear();
  this->LastRenderReused = false;
}

void vtkCausticsGBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Program ready: " << this->Program->IsReady() << "\n";
  os << indent << "KeepFarthest: " << this->KeepFarthest << "\n";
  os << indent << "Albedo: " << this->Albedo << "\n";
  os << indent << "PeelFront: " << this->PeelFront << "\n";
  os << indent << "ReuseUnchanged: " << this->ReuseUnchanged << "\n";
  os << indent << "LastRenderReused: " << this->LastRenderReused << "\n";
}
