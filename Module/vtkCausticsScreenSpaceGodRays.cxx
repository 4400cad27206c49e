#include "vtkCausticsScreenSpaceGodRays.h"

#include "vtkCausticsCameraOpticalDepth.h"

#include "vtkCausticsScreenSpaceSettings.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsCameraOpticalDepth.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsScreenSpaceCommon.h"
#include "vtkCausticsScreenSpaceGodRaysBlurCS.h"
#include "vtkCausticsScreenSpaceGodRaysFS.h"
#include "vtkCausticsScreenSpaceGodRaysVS.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsScreenSpaceGodRays);

struct vtkCausticsScreenSpaceGodRays::Internals
{
  caustics::ssp::Texture Accumulation; // RGBA32F, W/(m^2 sr)
  caustics::ssp::Texture Blurred;      // RGBA32F, after the horizontal pass
  caustics::ssp::Framebuffer Framebuffer;
  unsigned int EmptyVertexArray = 0;
  vtkNew<vtkCausticsShaderProgram> LineProgram;
  vtkNew<vtkCausticsShaderProgram> BlurProgram;
  int Width = 0, Height = 0;
};

vtkCausticsScreenSpaceGodRays::vtkCausticsScreenSpaceGodRays()
  : Internal(new Internals)
{
  auto& in = *this->Internal;
  const std::string common = vtkCausticsScreenSpaceCommon;
  in.LineProgram->SetName("god-rays");
  in.LineProgram->SetVertexSource((common + vtkCausticsScreenSpaceGodRaysVS).c_str());
  in.LineProgram->SetFragmentSource((common + vtkCausticsScreenSpaceGodRaysFS).c_str());
  in.LineProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.BlurProgram->SetName("god-ray blur");
  in.BlurProgram->SetComputeSource(vtkCausticsScreenSpaceGodRaysBlurCS);
  in.BlurProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
}

vtkCausticsScreenSpaceGodRays::~vtkCausticsScreenSpaceGodRays()
{
  if (this->Internal->Accumulation.Handle || this->Internal->EmptyVertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

bool vtkCausticsScreenSpaceGodRays::Begin(vtkOpenGLRenderWindow*, int width, int height)
{
  auto& in = *this->Internal;
  in.Accumulation.Ensure(width, height, 0, GL_RGBA32F);
  in.Blurred.Ensure(width, height, 0, GL_RGBA32F);
  in.Width = width;
  in.Height = height;
  const float zero[4] = { 0, 0, 0, 0 };
  glClearTexImage(in.Accumulation.Handle, 0, GL_RGBA, GL_FLOAT, zero);
  if (!in.EmptyVertexArray)
  {
    glCreateVertexArrays(1, &in.EmptyVertexArray);
  }
  return true;
}

bool vtkCausticsScreenSpaceGodRays::Draw(vtkOpenGLRenderWindow* renWin, const View& view,
  unsigned int rayBuffer, unsigned int payloadBuffer, unsigned int lineBuffer,
  unsigned int hitBuffer, unsigned int argumentBuffer)
{
  auto& in = *this->Internal;
  if (!view.Medium || !view.WorldToClip || !view.ClipToWorld || !view.OpaqueDepth ||
    !view.RefractiveDepth || !in.Accumulation.Handle)
  {
    vtkErrorMacro(<< "god-rays need Begin(), a medium, the camera matrices and depth buffers");
    return false;
  }
  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  const GLuint framebuffer = in.Framebuffer.Get();
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, in.Accumulation.Handle, 0);
  glNamedFramebufferDrawBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  state->vtkglViewport(0, 0, in.Width, in.Height);
  caustics::gl::SetMediumDefine(in.LineProgram, view.MediumGrid);
  if (view.CameraOpticalDepth)
  {
    view.CameraOpticalDepth->SetDefine(in.LineProgram);
  }
  bool ok = in.LineProgram->Bind(renWin);
  if (ok)
  {
    vtkCausticsShaderProgram* p = in.LineProgram;
    caustics::ssp::TextureUnits units(renWin);
    p->SetUniformi("opaqueDepth", units.Bind(view.OpaqueDepth));
    p->SetUniformi("refractiveDepth", units.Bind(view.RefractiveDepth));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, rayBuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_PAYLOAD_BINDING, payloadBuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_LINE_BINDING, lineBuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_HIT_BINDING, hitBuffer);
    p->SetUniformMatrix4("worldToClip", view.WorldToClip);
    p->SetUniformMatrix4("clipToWorld", view.ClipToWorld);
    p->SetUniform2f("viewport", static_cast<float>(in.Width), static_cast<float>(in.Height));
    const float origin[4] = { static_cast<float>(view.ViewOrigin[0]),
      static_cast<float>(view.ViewOrigin[1]), static_cast<float>(view.ViewOrigin[2]),
      static_cast<float>(view.ViewOrigin[3]) };
    p->SetUniform4f("viewOrigin", origin);
    const caustics::Medium& medium = *view.Medium;
    // With a grid the coefficients are per unit density (the shader samples the density
    // and marches the transmittance); else the homogeneous ones.
    const bool grid = p->HasDefine("CAUSTICS_MEDIUM_GRID");
    if (grid)
    {
      caustics::gl::SetMediumUniforms(p, medium, view.Bounds, view.MediumGrid);
      if (view.CameraOpticalDepth)
      {
        view.CameraOpticalDepth->SetUniforms(p);
      }
    }
    const caustics::Vec3 sigmaS = grid ? medium.sigmaS : medium.MeanSigmaS();
    const caustics::Vec3 sigmaT = medium.MeanSigmaT();
    p->SetUniform3f("sigmaS", static_cast<float>(sigmaS[0]), static_cast<float>(sigmaS[1]),
      static_cast<float>(sigmaS[2]));
    p->SetUniform3f("sigmaT", static_cast<float>(sigmaT[0]), static_cast<float>(sigmaT[1]),
      static_cast<float>(sigmaT[2]));
    p->SetUniformf("anisotropy", static_cast<float>(medium.g));
    p->SetUniform3f("boundsMin", static_cast<float>(view.Bounds[0]),
      static_cast<float>(view.Bounds[2]), static_cast<float>(view.Bounds[4]));
    p->SetUniform3f("boundsMax", static_cast<float>(view.Bounds[1]),
      static_cast<float>(view.Bounds[3]), static_cast<float>(view.Bounds[5]));
    glBindVertexArray(in.EmptyVertexArray);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, argumentBuffer);
    glDrawArraysIndirect(GL_LINES, reinterpret_cast<const void*>(16));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    if (view.CameraOpticalDepth)
    {
      view.CameraOpticalDepth->Deactivate();
    }
    p->Unbind(renWin);
  }
  state->PopFramebufferBindings();
  return ok;
}

bool vtkCausticsScreenSpaceGodRays::Finish(vtkOpenGLRenderWindow* renWin,
  const caustics::ScreenSpaceSettings& settings, vtkTextureObject* volume)
{
  auto& in = *this->Internal;
  caustics::gl::EnsureTexture(volume, renWin, in.Width, in.Height, GL_RGBA32F);
  if (!in.BlurProgram->Bind(renWin))
  {
    return false;
  }
  const float sigma = static_cast<float>(settings.GodRayBlurPixels);
  const int radius = static_cast<int>(std::ceil(3.0 * settings.GodRayBlurPixels));
  vtkCausticsShaderProgram* p = in.BlurProgram;
  p->SetUniform2i("size", in.Width, in.Height);
  p->SetUniformf("sigma", sigma);
  p->SetUniformi("radius", radius);
  // Horizontal, then vertical.
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glBindImageTexture(0, in.Accumulation.Handle, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(1, in.Blurred.Handle, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  p->SetUniform2i("axis", 1, 0);
  p->DispatchCovering2D(in.Width, in.Height, 16, 16);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glBindImageTexture(0, in.Blurred.Handle, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(1, volume->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  p->SetUniform2i("axis", 0, 1);
  p->DispatchCovering2D(in.Width, in.Height, 16, 16);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  p->Unbind(renWin);
  return true;
}

void vtkCausticsScreenSpaceGodRays::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  in.Accumulation.Release();
  in.Blurred.Release();
  in.Framebuffer.Release();
  if (in.EmptyVertexArray)
  {
    glDeleteVertexArrays(1, &in.EmptyVertexArray);
    in.EmptyVertexArray = 0;
  }
  in.LineProgram->ReleaseGraphicsResources(win);
  in.BlurProgram->ReleaseGraphicsResources(win);
  in.Width = in.Height = 0;
}

void vtkCausticsScreenSpaceGodRays::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Internal->Width << " x " << this->Internal->Height << "\n";
}
