#include "vtkCausticsPhotonBufferUtilities.h"

#include "vtkCausticsBindings.h" // CAUSTICS_PHOTON_STATISTICS_BINDING
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkMath.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace caustics
{
namespace hcm
{
namespace
{
/** One flux unit for every light of a frame (FluxUnit's rule for their largest photon). */
double FrameFluxUnit(
  const caustics::SceneData& scene, vtkCausticsLightBuffers* lights, double texelsPerPhoton)
{
  const int n = lights->GetResolution();
  double largest = 0.0;
  const int count = std::min(lights->GetNumberOfLights(), static_cast<int>(scene.Lights.size()));
  for (int light = 0; light < count; ++light)
  {
    const caustics::LightView& view = lights->GetView(light);
    if (view.valid)
    {
      largest = std::max(
        largest, caustics::MaximumTexelFlux(scene.Lights[light], view, n) * texelsPerPhoton);
    }
  }
  return (largest > 0.0 ? largest : 1.0) / UnitsPerTexelFlux;
}

// Fills the GLSL struct CausticsView `name` (vtkCausticsPhotonBufferCommon.glsl).
// texel: one texel's width (at unit depth when perspective), both axes.
void SetViewStruct(vtkCausticsShaderProgram* program, const std::string& name,
  const double worldToClip[16], const double clipToWorld[16], const Vec3& eye, const Vec3& axis,
  int width, int height, double texel, bool perspective)
{
  float matrix[16];
  caustics::gl::ToColumnMajor(worldToClip, matrix);
  program->SetUniformMatrix4((name + ".worldToClip").c_str(), matrix);
  caustics::gl::ToColumnMajor(clipToWorld, matrix);
  program->SetUniformMatrix4((name + ".clipToWorld").c_str(), matrix);
  program->SetUniform3f((name + ".eye").c_str(), static_cast<float>(eye[0]),
    static_cast<float>(eye[1]), static_cast<float>(eye[2]));
  program->SetUniform3f((name + ".axis").c_str(), static_cast<float>(axis[0]),
    static_cast<float>(axis[1]), static_cast<float>(axis[2]));
  program->SetUniform2f(
    (name + ".size").c_str(), static_cast<float>(width), static_cast<float>(height));
  program->SetUniformf((name + ".texel").c_str(), static_cast<float>(texel));
  program->SetUniformi((name + ".perspective").c_str(), perspective ? 1 : 0);
}
}

void SetViewUniforms(vtkCausticsShaderProgram* program, const std::string& name,
  const caustics::LightView& view, int width, int height)
{
  // One texel width for both axes: the larger, where a fitted view's texels are
  // longer along one (LightView::aspect); the shaders use it as a tolerance.
  SetViewStruct(program, name, view.worldToClip, view.clipToWorld, view.eye, view.axis, width,
    height,
    std::max(
      2.0 * view.halfExtent / std::max(width, 1), 2.0 * view.HalfExtentUp() / std::max(height, 1)),
    view.perspective);
}

void SetCameraViewUniforms(
  vtkCausticsShaderProgram* program, const std::string& name, const caustics::Camera& camera)
{
  Vec3 axis{ { camera.focalPoint[0] - camera.position[0], camera.focalPoint[1] - camera.position[1],
    camera.focalPoint[2] - camera.position[2] } };
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (double& a : axis)
  {
    a = length > 0.0 ? a / length : 0.0;
  }
  const int width = std::max(camera.width, 1);
  const int height = std::max(camera.height, 1);
  // viewAngle is vertical: the pixel height, which is its width too (square pixels).
  const double halfHeight = camera.parallel
    ? camera.parallelScale
    : std::tan(0.5 * vtkMath::RadiansFromDegrees(camera.viewAngle));
  SetViewStruct(program, name, camera.worldToClip, camera.clipToWorld, camera.position, axis, width,
    height, 2.0 * halfHeight / height, !camera.parallel);
}

double FluxUnit(const caustics::PhotonGrid& grid)
{
  return grid.MaximumPhotonFlux / UnitsPerTexelFlux;
}

void StatisticsBuffer::Begin(
  const caustics::SceneData& scene, vtkCausticsLightBuffers* lights, double texelsPerPhoton)
{
  this->Unit = FrameFluxUnit(scene, lights, texelsPerPhoton);
  this->Buffer.Allocate(StatSize * sizeof(std::uint32_t), caustics::gl::StorageBuffer::Usage::Copy);
  this->Buffer.Clear();
}

void StatisticsBuffer::Bind(vtkCausticsShaderProgram* program) const
{
  this->Buffer.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_PHOTON_STATISTICS_BINDING);
  program->SetUniformf("fluxUnit", static_cast<float>(this->Unit));
}

bool StatisticsBuffer::Read(caustics::PhotonStatistics& statistics) const
{
  statistics = caustics::PhotonStatistics();
  if (!this->Buffer.Handle())
  {
    return false;
  }
  ReadPhotonStatistics(this->Buffer, this->Unit, statistics);
  return statistics.Photons > 0;
}

void StatisticsBuffer::Release()
{
  this->Buffer.Release();
}

void ReadPhotonStatistics(
  const caustics::gl::StorageBuffer& buffer, double unit, caustics::PhotonStatistics& statistics)
{
  std::vector<std::uint32_t> words(StatSize, 0);
  buffer.Read(0, words.size() * sizeof(std::uint32_t), words.data());
  statistics = caustics::PhotonStatistics();
  statistics.Photons = words[StatPhotons];
  statistics.Hits = words[StatHits];
  statistics.HiddenHits = words[StatHiddenHits];
  statistics.LostInside = words[StatLostInside];
  statistics.Escaped = words[StatEscaped];
  statistics.Stored = words[StatStored];
  statistics.FluxIn = FluxFromWords(&words[StatFluxIn], unit);
  statistics.FluxHits = FluxFromWords(&words[StatFluxHits], unit);
  statistics.FluxLostInside = FluxFromWords(&words[StatFluxLostInside], unit);
  statistics.FluxEscaped = FluxFromWords(&words[StatFluxEscaped], unit);
  statistics.FluxStored = FluxFromWords(&words[StatFluxStored], unit);
  statistics.FluxInternalReflection = FluxFromWords(&words[StatFluxInternalReflection], unit);
  statistics.FluxAbsorbed = FluxFromWords(&words[StatFluxAbsorbed], unit);
}

bool ReceiverBoundsCache::Compute(const caustics::SceneData& scene, double bounds[6])
{
  this->Entries.resize(scene.Meshes.size());
  bool any = false;
  double result[6] = { 1.0, -1.0, 1.0, -1.0, 1.0, -1.0 };
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    const caustics::Mesh& mesh = scene.Meshes[m];
    if (mesh.material < 0 || mesh.material >= static_cast<int>(scene.Materials.size()) ||
      scene.Materials[mesh.material].role != caustics::Role::Receiver)
    {
      continue;
    }
    Entry& entry = this->Entries[m];
    if (entry.Actor != mesh.actor || entry.Version != mesh.version || !entry.Valid)
    {
      entry.Actor = mesh.actor;
      entry.Version = mesh.version;
      entry.Valid = false;
      for (std::size_t k = 0; k + 2 < mesh.positions.size(); k += 3)
      {
        for (int c = 0; c < 3; ++c)
        {
          const double v = mesh.positions[k + c];
          if (!std::isfinite(v))
          {
            continue;
          }
          entry.Bounds[2 * c] = entry.Valid ? std::min(entry.Bounds[2 * c], v) : v;
          entry.Bounds[2 * c + 1] = entry.Valid ? std::max(entry.Bounds[2 * c + 1], v) : v;
        }
        entry.Valid = true;
      }
    }
    if (!entry.Valid)
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      result[2 * c] = any ? std::min(result[2 * c], entry.Bounds[2 * c]) : entry.Bounds[2 * c];
      result[2 * c + 1] =
        any ? std::max(result[2 * c + 1], entry.Bounds[2 * c + 1]) : entry.Bounds[2 * c + 1];
    }
    any = true;
  }
  if (any)
  {
    std::copy(result, result + 6, bounds);
  }
  return any;
}
}
}
