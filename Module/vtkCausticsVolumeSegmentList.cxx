#include "vtkCausticsVolumeSegmentList.h"

#include "vtkCausticsBindings.h" // CAUSTICS_VOLUME_APPEND_*_BINDING
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtk_glew.h"

#include <algorithm>

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

void VolumeSegmentList::Reset(int capacity)
{
  this->Capacity = std::max(capacity, 1);
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
  this->Capacity = 0;
  this->On = false;
  this->Scene = nullptr;
}

}
}
