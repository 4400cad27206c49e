#include "vtkCausticsVolumeLines.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsCameraOpticalDepth.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsVolumeLinesBlurCS.h"
#include "vtkCausticsVolumeLinesCommon.h"
#include "vtkCausticsVolumeLinesFS.h"
#include "vtkCausticsVolumeLinesResampleCS.h"
#include "vtkCausticsVolumeLinesVS.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkCausticsVolumeLines);

struct vtkCausticsVolumeLines::Internals
{
  caustics::ssp::Texture Accumulation; // RGBA32F, W/(m^2 sr)
  caustics::ssp::Texture Blurred;      // RGBA32F, after the horizontal pass
  caustics::ssp::Framebuffer Framebuffer;
  caustics::gl::StorageBuffer Depths;    // (pieces + 1) floats per segment
  caustics::gl::StorageBuffer Arguments; // the lines' indirect draw
  unsigned int EmptyVertexArray = 0;
  vtkNew<vtkCausticsShaderProgram> ResampleProgram;
  vtkNew<vtkCausticsShaderProgram> LineProgram;
  vtkNew<vtkCausticsShaderProgram> BlurProgram;
  int Width = 0, Height = 0;
};

vtkCausticsVolumeLines::vtkCausticsVolumeLines()
  : Internal(new Internals)
{
  auto& in = *this->Internal;
  const std::string common = vtkCausticsVolumeLinesCommon;
  in.ResampleProgram->SetName("volume line re-sampling");
  in.ResampleProgram->SetComputeSource((common + vtkCausticsVolumeLinesResampleCS).c_str());
  in.ResampleProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.LineProgram->SetName("volume lines");
  in.LineProgram->SetVertexSource((common + vtkCausticsVolumeLinesVS).c_str());
  in.LineProgram->SetFragmentSource((common + vtkCausticsVolumeLinesFS).c_str());
  in.BlurProgram->SetName("volume line blur");
  in.BlurProgram->SetComputeSource(vtkCausticsVolumeLinesBlurCS);
  in.BlurProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
}

vtkCausticsVolumeLines::~vtkCausticsVolumeLines()
{
  const auto& in = *this->Internal;
  if (in.Accumulation.Handle || in.EmptyVertexArray || in.Depths.Handle())
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

bool vtkCausticsVolumeLines::Begin(vtkOpenGLRenderWindow*, int width, int height)
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

int vtkCausticsVolumeLines::PiecesFor(bool grid, int subSegments)
{
  // A homogeneous medium's optical depth is linear along a segment: one piece.
  return grid ? std::max(1, std::min(subSegments, 64)) : 1;
}

bool vtkCausticsVolumeLines::Draw(
  vtkOpenGLRenderWindow* renWin, const View& view, const Segments& segments, int subSegments)
{
  auto& in = *this->Internal;
  if (!view.Medium || !view.WorldToClip || !view.ClipToWorld || !view.OpaqueDepth ||
    !view.RefractiveDepth || !in.Accumulation.Handle)
  {
    vtkErrorMacro(<< "volume lines need Begin(), a medium, the camera matrices and depth buffers");
    return false;
  }
  if (!segments.Buffer || !segments.CountBuffer || segments.Capacity <= 0)
  {
    return true; // nothing traced
  }
  const bool grid = view.MediumGrid && view.MediumGrid->HasGrid();
  const int pieces = PiecesFor(grid, subSegments);
  // 0: the comparison mode that marches the density per fragment.
  if (grid && subSegments <= 0)
  {
    this->Internal->LineProgram->SetDefine("CAUSTICS_VOLUME_LINES_MARCH", 1);
  }
  else
  {
    this->Internal->LineProgram->RemoveDefine("CAUSTICS_VOLUME_LINES_MARCH");
  }
  return this->Resample(renWin, view, segments, pieces) &&
    this->DrawLines(renWin, view, segments, pieces);
}

bool vtkCausticsVolumeLines::Resample(
  vtkOpenGLRenderWindow* renWin, const View& view, const Segments& segments, int pieces)
{
  auto& in = *this->Internal;
  // Grows only: a steady scene allocates nothing.
  in.Depths.Allocate(sizeof(float) * static_cast<std::size_t>(segments.Capacity) *
      static_cast<std::size_t>(pieces + 1),
    caustics::gl::StorageBuffer::Usage::Copy);
  in.Arguments.Allocate(16, caustics::gl::StorageBuffer::Usage::Copy);
  vtkCausticsShaderProgram* p = in.ResampleProgram;
  caustics::gl::SetMediumDefine(p, view.MediumGrid);
  if (!p->Bind(renWin))
  {
    return false;
  }
  caustics::gl::SetMediumUniforms(p, *view.Medium, view.Bounds, view.MediumGrid);
  p->SetUniformi("capacity", segments.Capacity);
  p->SetUniformi("countWord", static_cast<int>(segments.CountWord));
  p->SetUniformi("pieces", pieces);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_SEGMENT_BINDING, segments.Buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_COUNT_BINDING, segments.CountBuffer);
  in.Depths.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_DEPTH_BINDING);
  in.Arguments.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_ARGUMENT_BINDING);
  p->DispatchCovering(static_cast<unsigned int>(segments.Capacity), 64);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  p->Unbind(renWin);
  return true;
}

bool vtkCausticsVolumeLines::DrawLines(
  vtkOpenGLRenderWindow* renWin, const View& view, const Segments& segments, int pieces)
{
  auto& in = *this->Internal;
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
  vtkCausticsShaderProgram* p = in.LineProgram;
  caustics::gl::SetMediumDefine(p, view.MediumGrid);
  if (view.CameraOpticalDepth)
  {
    view.CameraOpticalDepth->SetDefine(p);
  }
  const bool ok = p->Bind(renWin);
  if (ok)
  {
    caustics::ssp::TextureUnits units(renWin);
    p->SetUniformi("opaqueDepth", units.Bind(view.OpaqueDepth));
    p->SetUniformi("refractiveDepth", units.Bind(view.RefractiveDepth));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_SEGMENT_BINDING, segments.Buffer);
    in.Depths.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_DEPTH_BINDING);
    p->SetUniformMatrix4("worldToClip", view.WorldToClip);
    p->SetUniformMatrix4("clipToWorld", view.ClipToWorld);
    p->SetUniform2f("viewport", static_cast<float>(in.Width), static_cast<float>(in.Height));
    p->SetUniformi("pieces", pieces);
    const float origin[4] = { static_cast<float>(view.ViewOrigin[0]),
      static_cast<float>(view.ViewOrigin[1]), static_cast<float>(view.ViewOrigin[2]),
      static_cast<float>(view.ViewOrigin[3]) };
    p->SetUniform4f("viewOrigin", origin);
    const caustics::Medium& medium = *view.Medium;
    // With a grid the coefficients are per unit density (the shader samples the density);
    // else the homogeneous ones. SetMediumUniforms sets the extinction and the box.
    caustics::gl::SetMediumUniforms(p, medium, view.Bounds, view.MediumGrid);
    if (view.CameraOpticalDepth && p->HasDefine("CAUSTICS_CAMERA_OPTICAL_DEPTH"))
    {
      view.CameraOpticalDepth->SetUniforms(p);
    }
    const bool grid = p->HasDefine("CAUSTICS_MEDIUM_GRID");
    const caustics::Vec3 sigmaS = grid ? medium.sigmaS : medium.MeanSigmaS();
    p->SetUniform3f("sigmaS", static_cast<float>(sigmaS[0]), static_cast<float>(sigmaS[1]),
      static_cast<float>(sigmaS[2]));
    p->SetUniformf("anisotropy", static_cast<float>(medium.g));
    // Every technique's view carries the table (VolumeSegmentList::MakeView).
    p->SetUniformi("eyeMaterial", view.Geometry ? view.EyeMaterial : -1);
    if (view.Geometry)
    {
      view.Geometry->BindMaterials();
    }
    glBindVertexArray(in.EmptyVertexArray);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, in.Arguments.Handle());
    glDrawArraysIndirect(GL_LINES, nullptr);
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

bool vtkCausticsVolumeLines::Finish(
  vtkOpenGLRenderWindow* renWin, double blurPixels, vtkTextureObject* volume)
{
  auto& in = *this->Internal;
  caustics::gl::EnsureTexture(volume, renWin, in.Width, in.Height, GL_RGBA32F);
  if (!in.BlurProgram->Bind(renWin))
  {
    return false;
  }
  const double sigma = std::max(0.0, blurPixels);
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  vtkCausticsShaderProgram* p = in.BlurProgram;
  p->SetUniform2i("size", in.Width, in.Height);
  p->SetUniformf("sigma", static_cast<float>(sigma));
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

void vtkCausticsVolumeLines::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  in.Accumulation.Release();
  in.Blurred.Release();
  in.Framebuffer.Release();
  in.Depths.Release();
  in.Arguments.Release();
  if (in.EmptyVertexArray)
  {
    glDeleteVertexArrays(1, &in.EmptyVertexArray);
    in.EmptyVertexArray = 0;
  }
  in.ResampleProgram->ReleaseGraphicsResources(win);
  in.LineProgram->ReleaseGraphicsResources(win);
  in.BlurProgram->ReleaseGraphicsResources(win);
  in.Width = in.Height = 0;
}

void vtkCausticsVolumeLines::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const auto& in = *this->Internal;
  os << indent << "Size: " << in.Width << " x " << in.Height << "\n";
  os << indent << "DepthBytes: " << in.Depths.Bytes() << "\n";
}
