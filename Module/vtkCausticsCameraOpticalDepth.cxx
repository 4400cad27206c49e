#include "vtkCausticsCameraOpticalDepth.h"

#include "vtkCausticsCameraOpticalDepthCS.h" // The integration shader
#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkCausticsCameraOpticalDepth);

struct vtkCausticsCameraOpticalDepth::Internals
{
  vtkNew<vtkCausticsShaderProgram> Program;
  vtkNew<vtkTextureObject> Volume; // R32F, columns x rows x slices: density x m
  int Size[3] = { 0, 0, 0 };
  float Range[2] = { 0.0f, 1.0f }; // distances (m) from the near plane of the first and last slice
  float ClipToWorld[16] = {};
  float WorldToClip[16] = {};
  bool Valid = false;
};

vtkCausticsCameraOpticalDepth::vtkCausticsCameraOpticalDepth()
  : Internal(new Internals)
{
  this->Internal->Program->SetName("camera optical depth");
  this->Internal->Program->SetComputeSource(vtkCausticsCameraOpticalDepthCS);
  this->Internal->Program->SetDefine("CAUSTICS_MEDIUM_GRID", 1);
}

vtkCausticsCameraOpticalDepth::~vtkCausticsCameraOpticalDepth()
{
  if (this->Internal->Volume->GetHandle())
  {
    vtkErrorMacro(<< "destroyed with its volume texture unreleased (call ReleaseGraphicsResources)");
  }
}

namespace
{
/** Distances along the viewing rays (from the near plane) between which `box` can lie. */
bool DistanceRange(const caustics::Camera& camera, const double box[6], float range[2])
{
  const caustics::Vec3& eye = camera.position;
  caustics::Vec3 axis{ { camera.focalPoint[0] - eye[0], camera.focalPoint[1] - eye[1],
    camera.focalPoint[2] - eye[2] } };
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(length > 0.0))
  {
    return false;
  }
  double lowest = 1e300, highest = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[3] = { box[corner & 1 ? 1 : 0], box[corner & 2 ? 3 : 2],
      box[corner & 4 ? 5 : 4] };
    const double d[3] = { p[0] - eye[0], p[1] - eye[1], p[2] - eye[2] };
    // Along any ray the distance from the near plane is at least the depth beyond it;
    // from the eye a point is at most |p - eye| away (perspective), exactly the depth
    // (parallel).
    const double depth = (d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2]) / length -
      camera.clippingRange[0];
    lowest = std::min(lowest, depth);
    highest = std::max(highest,
      camera.parallel ? depth : std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  lowest = std::max(lowest, 0.0);
  if (!(highest > lowest))
  {
    return false;
  }
  range[0] = static_cast<float>(lowest);
  range[1] = static_cast<float>(highest);
  return true;
}
}

bool vtkCausticsCameraOpticalDepth::Build(vtkOpenGLRenderWindow* window, int width, int height,
  const caustics::SceneData& scene, const caustics::gl::MediumBuffer* grid)
{
  auto& in = *this->Internal;
  in.Valid = false;
  if (!this->Enabled || !grid || !grid->HasGrid() || !scene.Participating.enabled || width < 1 ||
    height < 1)
  {
    return false;
  }
  // The medium's box: the scene's bounds where the grid has density (as SetMediumUniforms).
  double box[6], gridBounds[6];
  grid->GetGrid()->GetWorldBounds(gridBounds);
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = std::max(scene.Bounds[2 * a], gridBounds[2 * a]);
    box[2 * a + 1] = std::min(scene.Bounds[2 * a + 1], gridBounds[2 * a + 1]);
    if (!(box[2 * a + 1] > box[2 * a]))
    {
      return false;
    }
  }
  if (!DistanceRange(scene.View, box, in.Range))
  {
    return false;
  }
  // At least 64 columns each way (a small viewport still resolves the medium's edges),
  // never more than the pixels.
  auto columns = [this](int pixels)
  { return std::min(pixels, std::max(64, (pixels + this->PixelsPerColumn - 1) / this->PixelsPerColumn)); };
  const int size[3] = { columns(width), columns(height), this->Slices };
  if (!in.Volume->GetHandle() || size[0] != in.Size[0] || size[1] != in.Size[1] ||
    size[2] != in.Size[2])
  {
    in.Volume->ReleaseGraphicsResources(window);
    in.Volume->SetContext(window);
    in.Volume->SetInternalFormat(GL_R32F);
    in.Volume->SetFormat(GL_RED);
    in.Volume->SetDataType(GL_FLOAT);
    in.Volume->SetWrapS(vtkTextureObject::ClampToEdge);
    in.Volume->SetWrapT(vtkTextureObject::ClampToEdge);
    in.Volume->SetWrapR(vtkTextureObject::ClampToEdge);
    in.Volume->SetMinificationFilter(vtkTextureObject::Linear);
    in.Volume->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!in.Volume->Allocate3D(size[0], size[1], size[2], 1, VTK_FLOAT))
    {
      vtkErrorMacro(<< "cannot allocate the " << size[0] << " x " << size[1] << " x " << size[2]
                    << " camera optical-depth volume");
      return false;
    }
    std::copy(size, size + 3, in.Size);
  }
  if (!in.Program->Bind(window))
  {
    return false;
  }
  caustics::gl::ToColumnMajor(scene.View.clipToWorld, in.ClipToWorld);
  caustics::gl::ToColumnMajor(scene.View.worldToClip, in.WorldToClip);
  in.Program->SetUniformMatrix4("clipToWorld", in.ClipToWorld);
  in.Program->SetUniform2i("columns", size[0], size[1]);
  in.Program->SetUniformi("slices", size[2]);
  in.Program->SetUniform2f("range", in.Range[0], in.Range[1]);
  caustics::gl::SetMediumUniforms(in.Program, scene, grid);
  glBindImageTexture(0, in.Volume->GetHandle(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  in.Program->DispatchCovering2D(size[0], size[1], 8, 8);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  in.Program->Unbind(window);
  in.Valid = true;
  return true;
}

bool vtkCausticsCameraOpticalDepth::IsValid() const
{
  return this->Internal->Valid;
}

void vtkCausticsCameraOpticalDepth::Invalidate()
{
  this->Internal->Valid = false;
}

void vtkCausticsCameraOpticalDepth::SetDefine(vtkCausticsShaderProgram* program) const
{
  if (this->Internal->Valid)
  {
    program->SetDefine("CAUSTICS_CAMERA_OPTICAL_DEPTH", 1);
  }
  else
  {
    program->RemoveDefine("CAUSTICS_CAMERA_OPTICAL_DEPTH");
  }
}

void vtkCausticsCameraOpticalDepth::SetUniforms(vtkCausticsShaderProgram* program)
{
  auto& in = *this->Internal;
  if (!in.Valid || !program->HasDefine("CAUSTICS_CAMERA_OPTICAL_DEPTH"))
  {
    return;
  }
  in.Volume->Activate();
  program->SetUniformi("causticsCameraDepthVolume", in.Volume->GetTextureUnit());
  program->SetUniformMatrix4("causticsCameraClipToWorld", in.ClipToWorld);
  program->SetUniformMatrix4("causticsCameraWorldToClip", in.WorldToClip);
  program->SetUniform2f("causticsCameraDepthRange", in.Range[0], in.Range[1]);
}

void vtkCausticsCameraOpticalDepth::Deactivate()
{
  if (this->Internal->Volume->GetHandle() && this->Internal->Volume->IsBound())
  {
    this->Internal->Volume->Deactivate();
  }
}

void vtkCausticsCameraOpticalDepth::ReleaseGraphicsResources(vtkWindow* window)
{
  auto& in = *this->Internal;
  in.Volume->ReleaseGraphicsResources(window);
  in.Program->ReleaseGraphicsResources(window);
  std::fill(in.Size, in.Size + 3, 0);
  in.Valid = false;
}

void vtkCausticsCameraOpticalDepth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const auto& in = *this->Internal;
  os << indent << "Enabled: " << (this->Enabled ? "on" : "off") << "\n";
  os << indent << "PixelsPerColumn: " << this->PixelsPerColumn << "\n";
  os << indent << "Slices: " << this->Slices << "\n";
  os << indent << "Volume: " << in.Size[0] << " x " << in.Size[1] << " x " << in.Size[2]
     << (in.Valid ? "" : " (not built)") << "\n";
  os << indent << "Range (m from the near plane): " << in.Range[0] << " to " << in.Range[1]
     << "\n";
}
