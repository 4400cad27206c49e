#include "vtkCausticsVolumeSegmentList.h"

#include "vtkCausticsBindings.h" // CAUSTICS_VOLUME_APPEND_*_BINDING
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsRenderPass.h" // GetVolumeSegmentBudget()
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <algorithm>
#include <climits>
#include <sstream>

namespace caustics
{
namespace gl
{

VolumeSegmentList::VolumeSegmentList() = default;
VolumeSegmentList::~VolumeSegmentList() = default; // StorageBuffer reports what was not released

bool VolumeSegmentList::IsNeeded(const SceneData& scene)
{
  const Medium& medium = scene.Participating;
  return medium.enabled &&
    (medium.sigmaS[0] > 0.0 || medium.sigmaS[1] > 0.0 || medium.sigmaS[2] > 0.0);
}

bool VolumeSegmentList::Begin(
  vtkOpenGLRenderWindow* renWin, const SceneData& scene, int width, int height)
{
  this->On = IsNeeded(scene) && width > 0 && height > 0;
  this->Scene = &scene;
  if (this->On)
  {
    this->Camera = ChooseTraceView(scene, TraceViewMode::Camera, width, height);
    this->Width = width;
    this->Height = height;
    this->On = this->Lines->Begin(renWin, width, height);
  }
  return this->On;
}

void VolumeSegmentList::SetAppendDefine(vtkCausticsShaderProgram* program) const
{
  if (this->On)
  {
    program->SetDefine("CAUSTICS_VOLUME_SEGMENT_APPEND", 1);
  }
  else
  {
    program->RemoveDefine("CAUSTICS_VOLUME_SEGMENT_APPEND");
  }
}

VolumeSegmentCapacity::Sizing VolumeSegmentCapacity::Fit(
  const DeviceLimits& limits, long long worstCase, int pieces)
{
  Sizing sizing;
  sizing.WorstCase = std::max(worstCase, 1LL);
  sizing.Pieces = std::max(pieces, 1);
  const double record = vtkCausticsVolumeLines::SegmentBytes;
  const double depths = sizeof(float) * (sizing.Pieces + 1.0);
  double fitting = INT_MAX; // the counts and indices are 32-bit on the GPU
  if (limits.MaximumStorageBlockBytes > 0.0)
  {
    // Each buffer is one storage block: the records, and the stage's optical depths.
    fitting = std::min(fitting, limits.MaximumStorageBlockBytes / std::max(record, depths));
  }
  if (limits.MemoryBudgetBytes > 0.0)
  {
    fitting = std::min(fitting, limits.MemoryBudgetBytes / (record + depths));
  }
  sizing.Fitting = static_cast<long long>(fitting);
  sizing.Capacity = static_cast<int>(std::max(1LL, std::min(sizing.WorstCase, sizing.Fitting)));
  return sizing;
}

int VolumeSegmentCapacity::Choose(vtkOpenGLRenderWindow* renWin, vtkObject* owner,
  long long worstCase, int pieces, const char* bound, const char* knobs)
{
  if (!this->Queried)
  {
    renWin->MakeCurrent();
    this->Limits = QueryDeviceLimits(0.0); // the context's limits do not change
    this->Queried = true;
  }
  // The memory the owning pass leaves the lists (its MaximumGPUMemory, or the device's
  // budget, less its own buffers); the storage block bounds them alone without one.
  DeviceLimits limits = this->Limits;
  const auto* pass = vtkCausticsRenderPass::SafeDownCast(owner);
  limits.MemoryBudgetBytes = pass ? pass->GetVolumeSegmentBudget() : limits.MemoryBudgetBytes;
  const Sizing sizing = Fit(limits, worstCase, pieces);
  const bool changed = sizing.WorstCase != this->Last.WorstCase ||
    sizing.Fitting != this->Last.Fitting || this->Warning.empty() == sizing.IsShort();
  this->Last = sizing;
  if (!changed)
  {
    return sizing.Capacity;
  }
  this->Warning.clear();
  if (sizing.IsShort())
  {
    // The larger per-segment buffer is the one that meets the block first.
    const bool depthsBind =
      sizeof(float) * (sizing.Pieces + 1.0) > vtkCausticsVolumeLines::SegmentBytes;
    std::ostringstream why;
    why << "volume caustics: these settings allow up to " << sizing.WorstCase
        << " photon segments per light (" << bound << "); this OpenGL holds " << sizing.Fitting
        << " (their "
        << (depthsBind ? "optical depths at " + std::to_string(sizing.Pieces) + " sub-segments"
                       : std::string("records"))
        << " within GL_MAX_SHADER_STORAGE_BLOCK_SIZE, "
        << FormatBytes(this->Limits.MaximumStorageBlockBytes);
    if (limits.MemoryBudgetBytes > 0.0)
    {
      why << ", and the " << FormatBytes(limits.MemoryBudgetBytes)
          << " of GPU memory the technique's own buffers leave (MaximumGPUMemory, or the device's)";
    }
    why << "). Segments past " << sizing.Capacity
        << " are dropped and the volume caustic loses their light; lower " << knobs
        << (depthsBind ? " or VolumeSubSegments" : "") << " to keep them all.";
    this->Warning = why.str();
    vtkWarningWithObjectMacro(owner, << this->Warning);
  }
  return sizing.Capacity;
}

void VolumeSegmentList::Reserve(vtkOpenGLRenderWindow* renWin, long long worstCase, int subSegments,
  bool grid, const char* bound, const char* knobs)
{
  this->Capacity = this->Sizer.Choose(renWin, this->Owner, worstCase,
    vtkCausticsVolumeLines::PiecesFor(grid, subSegments), bound, knobs);
  this->Records.Allocate(static_cast<std::size_t>(vtkCausticsVolumeLines::SegmentBytes) *
      static_cast<std::size_t>(this->Capacity),
    StorageBuffer::Usage::Copy);
  this->Count.Allocate(16, StorageBuffer::Usage::Copy);
  this->Count.Clear(0, 4);
}

void VolumeSegmentList::BindForAppend(vtkCausticsShaderProgram* program) const
{
  this->Records.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_APPEND_SEGMENT_BINDING);
  this->Count.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_VOLUME_APPEND_COUNT_BINDING);
  program->SetUniformu("volumeSegmentCapacity", static_cast<unsigned int>(this->Capacity));
}

unsigned int VolumeSegmentList::ReadAppendedCount() const
{
  unsigned int count = 0;
  if (this->Count.Handle())
  {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(this->Count.Handle(), 0, sizeof(count), &count);
  }
  return count;
}

vtkCausticsVolumeLines::Segments VolumeSegmentList::GetSegments() const
{
  return { this->Records.Handle(), this->Count.Handle(), 0, this->Capacity };
}

bool VolumeSegmentList::Draw(vtkOpenGLRenderWindow* renWin, const Frame& frame, int subSegments)
{
  if (!this->On || !this->Scene || !frame.Camera || !frame.Refractive)
  {
    return false;
  }
  // The tracer's appends before the stage reads them.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  return this->Lines->Draw(renWin,
    MakeView(*this->Scene, this->Camera, this->Width, this->Height, frame), this->GetSegments(),
    subSegments);
}

vtkCausticsVolumeLines::View VolumeSegmentList::MakeView(
  const SceneData& scene, const TraceView& camera, int width, int height, const Frame& frame)
{
  vtkCausticsVolumeLines::View view;
  view.WorldToClip = frame.WorldToClip;
  view.ClipToWorld = camera.ClipToWorld;
  view.Width = width;
  view.Height = height;
  std::copy(camera.ViewOrigin, camera.ViewOrigin + 4, view.ViewOrigin);
  std::copy(scene.Bounds, scene.Bounds + 6, view.Bounds);
  view.Medium = &scene.Participating;
  view.MediumGrid = frame.MediumGrid;
  view.CameraOpticalDepth = frame.CameraOpticalDepth;
  view.OpaqueDepth = frame.Camera ? frame.Camera->GetDepthTexture() : nullptr;
  view.RefractiveDepth = frame.Refractive ? frame.Refractive->GetDepthTexture() : nullptr;
  view.Geometry = frame.Geometry;
  view.EyeMaterial = frame.EyeMaterial;
  return view;
}

bool VolumeSegmentList::Finish(
  vtkOpenGLRenderWindow* renWin, double blurPixels, vtkTextureObject* volume)
{
  return this->On && this->Lines->Finish(renWin, blurPixels, volume);
}

void VolumeSegmentList::Release(vtkWindow* win)
{
  this->Lines->ReleaseGraphicsResources(win);
  this->Records.Release();
  this->Count.Release();
  this->Sizer.Release();
  this->Capacity = 0;
  this->On = false;
  this->Scene = nullptr;
}

}
}
