#include "vtkCausticsScreenSpaceLineTracer.h"

#include "vtkCausticsScreenSpaceSettings.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsGLUtilities.h"
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
// Shader storage bindings (glsl/vtkCausticsScreenSpaceCommon.glsl).
// Sizes of the per-ray records, bytes.
constexpr std::size_t LineBytes = 48;
constexpr std::size_t HitBytes = 32;
// Own-surface guard: hits on the surface a ray leaves are ignored this many pixels
// (at the origin's depth) along it, where neighbouring samples' tangent planes of
// a curved surface can cross the ray.
constexpr float GuardPixels = 2.0f;

}

/** One Trace(): its inputs and the sizes derived from them. */
struct vtkCausticsScreenSpaceLineTracer::Batch
{
  const View* Against = nullptr; // what the rays are traced against
  unsigned int Rays = 0, Counter = 0;
  int Capacity = 0;
  int Width = 0, Height = 0; // of the layered depth image
  int RowWidth = 0;          // fragments of the longest line, + 1
  int Rows = 0;              // rays per batch
  int Batches = 0;
  float Tolerance = 0.0f, PixelScale = 0.0f, MinimumLength = 0.0f;
  int PositionUnit = -1, NormalUnit = -1, RowUnit = -1;

  /** Byte offset of batch b's draw arguments (its reduction's dispatch: + 16). */
  static std::size_t ArgumentBytes(int b) { return 4 * (8 + 8 * static_cast<std::size_t>(b)); }
};

struct vtkCausticsScreenSpaceLineTracer::Internals
{
  caustics::gl::StorageBuffer Lines;
  caustics::gl::StorageBuffer Hits;
  caustics::gl::StorageBuffer Arguments;
  caustics::ssp::Texture Rows; // RG32UI: t bits, stamp << 16 | layer
  caustics::ssp::Framebuffer RowFramebuffer;
  unsigned int EmptyVertexArray = 0;
  vtkNew<vtkCausticsShaderProgram> PrepareProgram;
  vtkNew<vtkCausticsShaderProgram> SetupProgram;
  vtkNew<vtkCausticsShaderProgram> LineProgram;
  vtkNew<vtkCausticsShaderProgram> ReduceProgram;
  std::uint32_t Stamp = 0;
  int Batches = 0;
  caustics::StageSteps Steps; // named by Trace()'s stage prefix

  // Trace() in steps.
  void Allocate(const Batch& batch);
  void NextStamp();
  bool PrepareArguments(vtkOpenGLRenderWindow* renWin, const Batch& batch);
  bool SetupLines(vtkOpenGLRenderWindow* renWin, const Batch& batch);
  bool RasterizeRows(vtkOpenGLRenderWindow* renWin, const Batch& batch, int b);
  bool ReduceRows(vtkOpenGLRenderWindow* renWin, const Batch& batch, int b);
  // What the row and reduction shaders both read: the traced view and its layers.
  static void SetViewUniforms(vtkCausticsShaderProgram* p, const Batch& batch);
};

void vtkCausticsScreenSpaceLineTracer::Internals::SetViewUniforms(
  vtkCausticsShaderProgram* p, const Batch& batch)
{
  const View& view = *batch.Against;
  p->SetUniformi("ldiPosition", batch.PositionUnit);
  p->SetUniformi("ldiNormal", batch.NormalUnit);
  p->SetUniformMatrix4("worldToClip", view.WorldToClip);
  p->SetUniform2f("viewport", static_cast<float>(batch.Width), static_cast<float>(batch.Height));
  const float origin[4] = { static_cast<float>(view.ViewOrigin[0]),
    static_cast<float>(view.ViewOrigin[1]), static_cast<float>(view.ViewOrigin[2]),
    static_cast<float>(view.ViewOrigin[3]) };
  p->SetUniform4f("viewOrigin", origin);
  p->SetUniformf("tolerance", batch.Tolerance);
  p->SetUniformf("pixelScale", batch.PixelScale);
}

void vtkCausticsScreenSpaceLineTracer::Internals::Allocate(const Batch& batch)
{
  this->Batches = batch.Batches;
  this->Lines.Allocate(LineBytes * std::max(batch.Capacity, 1));
  this->Hits.Allocate(HitBytes * std::max(batch.Capacity, 1));
  this->Arguments.Allocate(Batch::ArgumentBytes(batch.Batches));
  if (this->Rows.Ensure(batch.RowWidth, batch.Rows, 0, GL_RG32UI))
  {
    this->Stamp = 0;
    const GLuint zero[2] = { 0, 0 };
    glClearTexImage(this->Rows.Handle, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, zero);
  }
  if (!this->EmptyVertexArray)
  {
    glCreateVertexArrays(1, &this->EmptyVertexArray);
  }
}

void vtkCausticsScreenSpaceLineTracer::Internals::NextStamp()
{
  // A new stamp per batch: texels not written by this batch read as misses.
  this->Stamp = (this->Stamp + 1) & 0xffffu;
  if (this->Stamp == 0)
  {
    const GLuint zero[2] = { 0, 0 };
    glClearTexImage(this->Rows.Handle, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, zero);
    this->Stamp = 1;
  }
}

bool vtkCausticsScreenSpaceLineTracer::Internals::PrepareArguments(
  vtkOpenGLRenderWindow* renWin, const Batch& batch)
{
  if (!this->PrepareProgram->Bind(renWin))
  {
    return false;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING, batch.Counter);
  this->Arguments.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_ARGUMENT_BINDING);
  this->PrepareProgram->SetUniformi("rowsPerBatch", batch.Rows);
  this->PrepareProgram->SetUniformi("batches", batch.Batches);
  this->PrepareProgram->SetUniformi("capacity", batch.Capacity);
  this->PrepareProgram->Dispatch(1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  return true;
}

bool vtkCausticsScreenSpaceLineTracer::Internals::SetupLines(
  vtkOpenGLRenderWindow* renWin, const Batch& batch)
{
  vtkCausticsShaderProgram* p = this->SetupProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  const View& view = *batch.Against;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING, batch.Counter);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, batch.Rays);
  this->Lines.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_LINE_BINDING);
  p->SetUniformMatrix4("worldToClip", view.WorldToClip);
  p->SetUniform2f("viewport", static_cast<float>(batch.Width), static_cast<float>(batch.Height));
  p->SetUniform3f("boundsMin", static_cast<float>(view.Bounds[0]),
    static_cast<float>(view.Bounds[2]), static_cast<float>(view.Bounds[4]));
  p->SetUniform3f("boundsMax", static_cast<float>(view.Bounds[1]),
    static_cast<float>(view.Bounds[3]), static_cast<float>(view.Bounds[5]));
  p->SetUniformf("tolerance", batch.Tolerance);
  p->SetUniformf("pixelScale", batch.PixelScale);
  p->SetUniformf("minimumLength", batch.MinimumLength);
  p->SetUniformf("maximumLength", static_cast<float>(batch.RowWidth - 1));
  p->SetUniformf("guardPixels", GuardPixels);
  p->SetUniformi("capacity", batch.Capacity);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, this->Arguments.Handle());
  glDispatchComputeIndirect(0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  return true;
}

bool vtkCausticsScreenSpaceLineTracer::Internals::RasterizeRows(
  vtkOpenGLRenderWindow* renWin, const Batch& batch, int b)
{
  vtkCausticsShaderProgram* p = this->LineProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  const View& view = *batch.Against;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, batch.Rays);
  this->Lines.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_LINE_BINDING);
  glBindBufferBase(
    GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_TABLE_BINDING, view.Layers->GetTableBuffer());
  p->SetUniformi("batchBase", b * batch.Rows);
  p->SetUniform2f("target", static_cast<float>(batch.RowWidth), static_cast<float>(batch.Rows));
  SetViewUniforms(p, batch);
  p->SetUniformu("stamp", this->Stamp);
  glBindVertexArray(this->EmptyVertexArray);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, this->Arguments.Handle());
  glDrawArraysIndirect(
    GL_LINES, reinterpret_cast<const void*>(static_cast<std::uintptr_t>(Batch::ArgumentBytes(b))));
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glBindVertexArray(0);
  return true;
}

bool vtkCausticsScreenSpaceLineTracer::Internals::ReduceRows(
  vtkOpenGLRenderWindow* renWin, const Batch& batch, int b)
{
  vtkCausticsShaderProgram* p = this->ReduceProgram;
  if (!p->Bind(renWin))
  {
    return false;
  }
  glBindTextureUnit(batch.RowUnit, this->Rows.Handle);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_RAY_BINDING, batch.Rays);
  this->Lines.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_LINE_BINDING);
  this->Hits.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_HIT_BINDING);
  const View& view = *batch.Against;
  glBindBufferBase(
    GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_TABLE_BINDING, view.Layers->GetTableBuffer());
  p->SetUniformi("rowHits", batch.RowUnit);
  SetViewUniforms(p, batch);
  p->SetUniformi("batchBase", b * batch.Rows);
  p->SetUniformi("capacity", batch.Capacity);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_SSP_COUNTER_BINDING, batch.Counter);
  p->SetUniformu("stamp", this->Stamp);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, this->Arguments.Handle());
  glDispatchComputeIndirect(static_cast<GLintptr>(Batch::ArgumentBytes(b) + 16));
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  return true;
}

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
  if (this->Internal->Hits.Handle() || this->Internal->EmptyVertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

void vtkCausticsScreenSpaceLineTracer::SetTimings(vtkCausticsTimings* timings)
{
  this->Internal->Steps.Timings = timings;
}

bool vtkCausticsScreenSpaceLineTracer::Trace(vtkOpenGLRenderWindow* renWin,
  const caustics::ScreenSpaceSettings& settings, const View& view, unsigned int rayBuffer,
  unsigned int counterBuffer, int capacity, const std::string& stagePrefix)
{
  auto& in = *this->Internal;
  vtkCausticsLayeredDepth* layers = view.Layers;
  if (!layers || !view.WorldToClip || capacity < 0 || !rayBuffer || !counterBuffer)
  {
    vtkErrorMacro(<< "Trace needs a layered depth image, its matrix, rays and a counter");
    return false;
  }
  Batch batch;
  batch.Against = &view;
  batch.Rays = rayBuffer;
  batch.Counter = counterBuffer;
  batch.Capacity = capacity;
  batch.Width = layers->GetWidth();
  batch.Height = layers->GetHeight();
  batch.RowWidth = std::max(std::max(batch.Width, batch.Height), settings.MinimumLineLength) + 1;
  batch.Rows = std::max(1, std::min(settings.RowsPerBatch, caustics::ssp::MaxTextureSize()));
  batch.Batches = capacity > 0 ? (capacity + batch.Rows - 1) / batch.Rows : 0;
  batch.Tolerance = static_cast<float>(view.Tolerance);
  batch.PixelScale = caustics::ssp::PixelScale(view.WorldToClip, batch.Width, batch.Height);
  batch.MinimumLength = static_cast<float>(settings.MinimumLineLength);
  in.Allocate(batch);
  if (capacity == 0)
  {
    return true;
  }

  // 1. Indirect arguments from the GPU's ray count. 2. Line setup, one thread per ray.
  in.Steps.Start(stagePrefix + "line setup");
  bool ok = in.PrepareArguments(renWin, batch) && in.SetupLines(renWin, batch);
  in.Steps.Stop(stagePrefix + "line setup");

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
  caustics::ssp::TextureUnits units(renWin);
  batch.PositionUnit = units.Bind(layers->GetPositionTexture());
  batch.NormalUnit = units.Bind(layers->GetNormalTexture());
  batch.RowUnit = units.Bind(0u);
  // One timed stage for both steps: the reductions run between the batches' draws.
  in.Steps.Start(stagePrefix + "line tracing");
  for (int b = 0; ok && b < batch.Batches; ++b)
  {
    in.NextStamp();
    glBindTextureUnit(batch.RowUnit, 0);
    state->vtkglBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    state->vtkglViewport(0, 0, batch.RowWidth, batch.Rows);
    ok = in.RasterizeRows(renWin, batch, b) && in.ReduceRows(renWin, batch, b);
  }
  in.Steps.Stop(stagePrefix + "line tracing");
  glBindTextureUnit(batch.RowUnit, 0);
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
  return this->Internal->Hits.Handle();
}
unsigned int vtkCausticsScreenSpaceLineTracer::GetLineBuffer() const
{
  return this->Internal->Lines.Handle();
}
unsigned int vtkCausticsScreenSpaceLineTracer::GetArgumentBuffer() const
{
  return this->Internal->Arguments.Handle();
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
  os << indent << "Batches (last trace): " << this->Internal->Batches << "\n";
}
