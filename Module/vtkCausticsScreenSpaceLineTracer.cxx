#include "vtkCausticsScreenSpaceLineTracer.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsLayeredDepth.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTimings.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include "vtkCausticsScreenSpaceCommon.h"
#include "vtkCausticsScreenSpaceLineTracerLineFS.h"
#include "vtkCausticsScreenSpaceLineTracerLineVS.h"
#include "vtkCausticsScreenSpaceLineTracerPrepareCS.h"
#include "vtkCausticsScreenSpaceLineTracerReduceCS.h"
#include "vtkCausticsScreenSpaceLineTracerSetupCS.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

vtkStandardNewMacro(vtkCausticsScreenSpaceLineTracer);

namespace
{
// Sizes of the per-ray records, bytes.
constexpr std::size_t LineBytes = 48;
constexpr std::size_t HitBytes = 32;
// Own-surface guard: hits on the surface a ray leaves are ignored this many pixels
// (at the origin's depth) along it, where neighbouring samples' tangent planes of
// a curved surface can cross the ray.
constexpr float GuardPixels = 2.0f;

}

struct vtkCausticsScreenSpaceLineTracer::Internals
{
  caustics::ssp::Buffer Lines;
  caustics::ssp::Buffer Hits;
  caustics::ssp::Buffer Arguments;
  caustics::ssp::Texture Rows; // RG32UI: t bits, stamp << 16 | layer
  caustics::ssp::Framebuffer RowFramebuffer;
  unsigned int EmptyVertexArray = 0;
  vtkNew<vtkCausticsShaderProgram> PrepareProgram;
  vtkNew<vtkCausticsShaderProgram> SetupProgram;
  vtkNew<vtkCausticsShaderProgram> LineProgram;
  vtkNew<vtkCausticsShaderProgram> ReduceProgram;
  std::uint32_t Stamp = 0;
  int Batches = 0;
  vtkCausticsTimings* Timings = nullptr;

  void Start(const std::string& stage)
  {
    if (this->Timings)
    {
      this->Timings->StartStage(stage.c_str());
    }
  }
  void Stop(const std::string& stage)
  {
    if (this->Timings)
    {
      this->Timings->StopStage(stage.c_str());
    }
  }
};

vtkCausticsScreenSpaceLineTracer::vtkCausticsScreenSpaceLineTracer()
  : Internal(new Internals)
{
  auto& in = *this->Internal;
  const std::string common = vtkCausticsScreenSpaceCommon;
  in.PrepareProgram->SetName("line tracing arguments");
  in.PrepareProgram->SetComputeSource((common + vtkCausticsScreenSpaceLineTracerPrepareCS).c_str());
  in.SetupProgram->SetName("line setup");
  in.SetupProgram->SetComputeSource((common + vtkCausticsScreenSpaceLineTracerSetupCS).c_str());
  in.LineProgram->SetName("line tracing");
  in.LineProgram->SetVertexSource((common + vtkCausticsScreenSpaceLineTracerLineVS).c_str());
  in.LineProgram->SetFragmentSource((common + vtkCausticsScreenSpaceLineTracerLineFS).c_str());
  in.ReduceProgram->SetName("first-hit reduction");
  in.ReduceProgram->SetComputeSource((common + vtkCausticsScreenSpaceLineTracerReduceCS).c_str());
  for (vtkCausticsShaderProgram* program : { in.PrepareProgram.GetPointer(),
         in.SetupProgram.GetPointer(), in.LineProgram.GetPointer(), in.ReduceProgram.GetPointer() })
  {
    program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  }
}

vtkCausticsScreenSpaceLineTracer::~vtkCausticsScreenSpaceLineTracer()
{
  if (this->Internal->Hits.Handle || this->Internal->EmptyVertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

void vtkCausticsScreenSpaceLineTracer::SetTimings(vtkCausticsTimings* timings)
{
  this->Internal->Timings = timings;
}

bool vtkCausticsScreenSpaceLineTracer::Trace(vtkOpenGLRenderWindow* renWin, const View& view,
  unsigned int rayBuffer, unsigned int counterBuffer, int capacity, const std::string& stagePrefix)
{
  auto& in = *this->Internal;
  vtkCausticsLayeredDepth* layers = view.Layers;
  if (!layers || !view.WorldToClip || capacity < 0 || !rayBuffer || !counterBuffer)
  {
    vtkErrorMacro(<< "Trace needs a layered depth image, its matrix, rays and a counter");
    return false;
  }
  const int width = layers->GetWidth(), height = layers->GetHeight();
  const int rowWidth = std::max(std::max(width, height), this->MinimumLineLength) + 1;
  const int rows = std::max(1, std::min(this->RowsPerBatch, caustics::ssp::MaxTextureSize()));
  const int batches = capacity > 0 ? (capacity + rows - 1) / rows : 0;
  in.Batches = batches;
  in.Lines.Ensure(LineBytes * std::max(capacity, 1));
  in.Hits.Ensure(HitBytes * std::max(capacity, 1));
  in.Arguments.Ensure(4 * (8 + 8 * static_cast<std::size_t>(batches)));
  if (in.Rows.Ensure(rowWidth, rows, 0, GL_RG32UI))
  {
    in.Stamp = 0;
    const GLuint zero[2] = { 0, 0 };
    glClearTexImage(in.Rows.Handle, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, zero);
  }
  if (!in.EmptyVertexArray)
  {
    glCreateVertexArrays(1, &in.EmptyVertexArray);
  }
  if (capacity == 0)
  {
    return true;
  }
  const float tolerance = static_cast<float>(this->Tolerance);
  const float pixelScale = caustics::ssp::PixelScale(view.WorldToClip, width, height);

  // 1. Indirect arguments from the GPU's ray count.
  in.Start(stagePrefix + "line setup");
  bool ok = in.PrepareProgram->Bind(renWin);
  if (ok)
  {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING, counterBuffer);
    in.Arguments.BindStorage(CAUSTICS_SSP_ARGUMENT_BINDING);
    in.PrepareProgram->SetUniformi("rowsPerBatch", rows);
    in.PrepareProgram->SetUniformi("batches", batches);
    in.PrepareProgram->SetUniformi("capacity", capacity);
    in.PrepareProgram->Dispatch(1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }

  // 2. Line setup, one thread per ray.
  ok = ok && in.SetupProgram->Bind(renWin);
  if (ok)
  {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING, counterBuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, rayBuffer);
    in.Lines.BindStorage(CAUSTICS_SSP_LINE_BINDING);
    vtkCausticsShaderProgram* p = in.SetupProgram;
    p->SetUniformMatrix4("worldToClip", view.WorldToClip);
    p->SetUniform2f("viewport", static_cast<float>(width), static_cast<float>(height));
    p->SetUniform3f("boundsMin", static_cast<float>(view.Bounds[0]),
      static_cast<float>(view.Bounds[2]), static_cast<float>(view.Bounds[4]));
    p->SetUniform3f("boundsMax", static_cast<float>(view.Bounds[1]),
      static_cast<float>(view.Bounds[3]), static_cast<float>(view.Bounds[5]));
    p->SetUniformf("tolerance", tolerance);
    p->SetUniformf("pixelScale", pixelScale);
    p->SetUniformf("minimumLength", static_cast<float>(this->MinimumLineLength));
    p->SetUniformf("maximumLength", static_cast<float>(rowWidth - 1));
    p->SetUniformf("guardPixels", GuardPixels);
    p->SetUniformi("capacity", capacity);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.Arguments.Handle);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  in.Stop(stagePrefix + "line setup");

  // 3-4. Per batch: rasterize the rows, then reduce them.
  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_SCISSOR_TEST);
  const GLuint framebuffer = in.RowFramebuffer.Get();
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, in.Rows.Handle, 0);
  glNamedFramebufferDrawBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
  const GLuint tableBuffer = layers->GetTableBuffer();
  caustics::ssp::TextureUnits units(renWin);
  const int positionUnit = units.Bind(layers->GetPositionTexture());
  const int normalUnit = units.Bind(layers->GetNormalTexture());
  const int rowUnit = units.Bind(0u);
  // One timed stage for both steps: the reductions run between the batches' draws.
  in.Start(stagePrefix + "line tracing");
  for (int b = 0; ok && b < batches; ++b)
  {
    // A new stamp per batch: texels not written by this batch read as misses.
    in.Stamp = (in.Stamp + 1) & 0xffffu;
    if (in.Stamp == 0)
    {
      const GLuint zero[2] = { 0, 0 };
      glClearTexImage(in.Rows.Handle, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, zero);
      in.Stamp = 1;
    }
    const std::size_t argumentBytes = 4 * (8 + 8 * static_cast<std::size_t>(b));

    glBindTextureUnit(rowUnit, 0);
    state->vtkglBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    state->vtkglViewport(0, 0, rowWidth, rows);
    ok = in.LineProgram->Bind(renWin);
    if (ok)
    {
      vtkCausticsShaderProgram* p = in.LineProgram;
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, rayBuffer);
      in.Lines.BindStorage(CAUSTICS_SSP_LINE_BINDING);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_TABLE_BINDING, tableBuffer);
      p->SetUniformi("batchBase", b * rows);
      p->SetUniform2f("target", static_cast<float>(rowWidth), static_cast<float>(rows));
      p->SetUniformi("ldiPosition", positionUnit);
      p->SetUniformi("ldiNormal", normalUnit);
      p->SetUniformMatrix4("worldToClip", view.WorldToClip);
      p->SetUniform2f("viewport", static_cast<float>(width), static_cast<float>(height));
      const float origin[4] = { static_cast<float>(view.ViewOrigin[0]),
        static_cast<float>(view.ViewOrigin[1]), static_cast<float>(view.ViewOrigin[2]),
        static_cast<float>(view.ViewOrigin[3]) };
      p->SetUniform4f("viewOrigin", origin);
      p->SetUniformf("tolerance", tolerance);
      p->SetUniformf("pixelScale", pixelScale);
      p->SetUniformu("stamp", in.Stamp);
      glBindVertexArray(in.EmptyVertexArray);
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, in.Arguments.Handle);
      glDrawArraysIndirect(
        GL_LINES, reinterpret_cast<const void*>(static_cast<std::uintptr_t>(argumentBytes)));
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
      glBindVertexArray(0);
    }
    ok = ok && in.ReduceProgram->Bind(renWin);
    if (ok)
    {
      vtkCausticsShaderProgram* p = in.ReduceProgram;
      glBindTextureUnit(rowUnit, in.Rows.Handle);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, rayBuffer);
      in.Lines.BindStorage(CAUSTICS_SSP_LINE_BINDING);
      in.Hits.BindStorage(CAUSTICS_SSP_HIT_BINDING);
      p->SetUniformi("rowHits", rowUnit);
      p->SetUniformMatrix4("worldToClip", view.WorldToClip);
      p->SetUniformf("pixelScale", pixelScale);
      p->SetUniformi("ldiPosition", positionUnit);
      p->SetUniformi("ldiNormal", normalUnit);
      p->SetUniform2f("viewport", static_cast<float>(width), static_cast<float>(height));
      p->SetUniformi("batchBase", b * rows);
      p->SetUniformi("capacity", capacity);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING, counterBuffer);
      p->SetUniformu("stamp", in.Stamp);
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.Arguments.Handle);
      glDispatchComputeIndirect(static_cast<GLintptr>(argumentBytes + 16));
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
  }
  in.Stop(stagePrefix + "line tracing");
  glBindTextureUnit(rowUnit, 0);
  in.ReduceProgram->Unbind(renWin);
  state->PopFramebufferBindings();
  if (!ok)
  {
    vtkErrorMacro(<< "line tracing: a program failed to build");
  }
  return ok;
}

unsigned int vtkCausticsScreenSpaceLineTracer::GetHitBuffer() const
{
  return this->Internal->Hits.Handle;
}
unsigned int vtkCausticsScreenSpaceLineTracer::GetLineBuffer() const
{
  return this->Internal->Lines.Handle;
}
unsigned int vtkCausticsScreenSpaceLineTracer::GetArgumentBuffer() const
{
  return this->Internal->Arguments.Handle;
}
int vtkCausticsScreenSpaceLineTracer::GetNumberOfBatches() const
{
  return this->Internal->Batches;
}

void vtkCausticsScreenSpaceLineTracer::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  in.Lines.Release();
  in.Hits.Release();
  in.Arguments.Release();
  in.Rows.Release();
  in.RowFramebuffer.Release();
  if (in.EmptyVertexArray)
  {
    glDeleteVertexArrays(1, &in.EmptyVertexArray);
    in.EmptyVertexArray = 0;
  }
  for (vtkCausticsShaderProgram* program : { in.PrepareProgram.GetPointer(),
         in.SetupProgram.GetPointer(), in.LineProgram.GetPointer(), in.ReduceProgram.GetPointer() })
  {
    program->ReleaseGraphicsResources(win);
  }
  in.Batches = 0;
}

void vtkCausticsScreenSpaceLineTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance << " m\n";
  os << indent << "MinimumLineLength: " << this->MinimumLineLength << " fragments\n";
  os << indent << "RowsPerBatch: " << this->RowsPerBatch << "\n";
  os << indent << "Batches (last trace): " << this->Internal->Batches << "\n";
}
