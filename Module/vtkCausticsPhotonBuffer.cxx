#include "vtkCausticsPhotonBuffer.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsPhotonBufferUtilities.h"
#include "vtkCausticsPhotonEmitter.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsOptics.h"
#include "vtkCausticsPhotonBufferCommon.h"
#include "vtkCausticsPhotonBufferHierarchyArgumentsCS.h"
#include "vtkCausticsPhotonBufferTraceCS.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsPhotonBuffer);

namespace
{
double Diagonal(const double bounds[6])
{
  const double dx = bounds[1] - bounds[0], dy = bounds[3] - bounds[2], dz = bounds[5] - bounds[4];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}
}

struct vtkCausticsPhotonBuffer::Internals
{
  caustics::hcm::ReceiverBoundsCache Receivers;
};

vtkCausticsPhotonBuffer::vtkCausticsPhotonBuffer()
  : Internal(new Internals)
{
  this->BackLayer->KeepFarthestOn();
  const std::string source =
    std::string(vtkCausticsOptics) + vtkCausticsPhotonBufferCommon + vtkCausticsPhotonBufferTraceCS;
  this->SortProgram->SetName("photon buffer: sort");
  this->SortProgram->SetDefine("PHASE", 0);
  this->SortProgram->SetComputeSource(source.c_str());
  this->InsideProgram->SetName("photon buffer: inside refractors");
  this->InsideProgram->SetDefine("PHASE", 1);
  this->InsideProgram->SetComputeSource(source.c_str());
  this->AirProgram->SetName("photon buffer: to the receivers");
  this->AirProgram->SetDefine("PHASE", 2);
  this->AirProgram->SetComputeSource(source.c_str());
  this->ArgumentsProgram->SetName("photon buffer dispatch arguments");
  this->ArgumentsProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->ArgumentsProgram->SetComputeSource(
    (std::string(vtkCausticsPhotonBufferCommon) + vtkCausticsPhotonBufferHierarchyArgumentsCS)
      .c_str());
}

vtkCausticsPhotonBuffer::~vtkCausticsPhotonBuffer()
{
  if (this->StatisticsBuffer || this->ListBuffer)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): statistics buffer leaked");
  }
}

bool vtkCausticsPhotonBuffer::Render(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene, int light,
  vtkCausticsPhotonEmitter* emitter, const caustics::LightView& photonView,
  const caustics::LightView& mapView, vtkCausticsGBuffer* receivers)
{
  const int resolution = emitter ? emitter->GetGridSize()[0] : 0;
  return this->RenderLayers(renWin, geometry, photonView, resolution) &&
    this->Trace(renWin, geometry, scene, light, emitter, photonView, mapView, receivers);
}

bool vtkCausticsPhotonBuffer::RenderLayers(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::LightView& photonView, int resolution)
{
  if (resolution <= 0)
  {
    vtkErrorMacro(<< "RenderLayers needs a positive resolution (emit photons first)");
    return false;
  }
  // The refractors' front and back faces, as the light sees them.
  float photonMatrix[16];
  caustics::gl::ToColumnMajor(photonView.worldToClip, photonMatrix);
  const int refractors = vtkCausticsSceneGeometry::RoleBit(3);
  bool ok =
    this->FrontLayer->Render(renWin, geometry, photonMatrix, resolution, resolution, refractors);
  ok =
    this->BackLayer->Render(renWin, geometry, photonMatrix, resolution, resolution, refractors) &&
    ok;
  return ok;
}

bool vtkCausticsPhotonBuffer::Trace(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene, int light,
  vtkCausticsPhotonEmitter* emitter, const caustics::LightView& photonView,
  const caustics::LightView& mapView, vtkCausticsGBuffer* receivers)
{
  if (!emitter || !receivers || light < 0 || light >= static_cast<int>(scene.Lights.size()))
  {
    vtkErrorMacro(<< "Trace needs an emitter, a receiver G-buffer and a valid light index");
    return false;
  }
  const int width = emitter->GetGridSize()[0];
  const int height = emitter->GetGridSize()[1];
  if (width <= 0 || height <= 0 || this->FrontLayer->GetSize()[0] != width)
  {
    vtkErrorMacro(<< "Trace needs emitted photons and layers of their resolution");
    return false;
  }
  this->GridSize[0] = width;
  this->GridSize[1] = height;
  this->BranchRows = width;
  const caustics::Light& source = scene.Lights[light];
  this->FluxUnit =
    caustics::hcm::TexelFluxBound(source, photonView, width) / caustics::hcm::UnitsPerTexelFlux;

  // 2. Outputs and counters: allocated when the size changes, cleared every frame.
  caustics::gl::EnsureTexture(this->HitPosition, renWin, width, height, GL_RGBA32F);
  caustics::gl::EnsureTexture(this->HitNormal, renWin, width, height, GL_RGBA32F);
  caustics::gl::EnsureTexture(this->HitFlux, renWin, width, height, GL_RGBA32F);
  if (!this->StatisticsBuffer)
  {
    glCreateBuffers(1, &this->StatisticsBuffer);
    glNamedBufferData(this->StatisticsBuffer, caustics::hcm::StatSize * sizeof(std::uint32_t),
      nullptr, GL_DYNAMIC_COPY);
  }
  glClearNamedBufferData(
    this->StatisticsBuffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  // Work lists (control words, then two lists of up to one entry per texel).
  const std::size_t capacity = static_cast<std::size_t>(width) * height;
  const std::size_t listBytes = (caustics::hcm::ControlSize + 2 * capacity) * sizeof(std::uint32_t);
  if (!this->ListBuffer)
  {
    glCreateBuffers(1, &this->ListBuffer);
    this->ListCapacity = 0;
  }
  if (listBytes > this->ListCapacity)
  {
    glNamedBufferData(
      this->ListBuffer, static_cast<GLsizeiptr>(listBytes), nullptr, GL_DYNAMIC_COPY);
    this->ListCapacity = listBytes;
  }
  glClearNamedBufferSubData(this->ListBuffer, GL_R32UI, 0,
    caustics::hcm::ControlSize * sizeof(std::uint32_t), GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);

  // 3. One thread per photon, in two phases (inside the refractors, then in air).
  vtkTextureObject* inputs[] = { emitter->GetPositionTexture(), emitter->GetDirectionTexture(),
    emitter->GetFluxTexture(), this->FrontLayer->GetPositionTexture(),
    this->FrontLayer->GetNormalTexture(), this->BackLayer->GetPositionTexture(),
    this->BackLayer->GetNormalTexture(), receivers->GetPositionTexture(),
    receivers->GetNormalTexture() };
  const char* names[] = { "photonPosition", "photonDirection", "photonFlux", "frontPosition",
    "frontNormal", "backPosition", "backNormal", "receiverPosition", "receiverNormal" };
  for (vtkTextureObject* input : inputs)
  {
    input->Activate();
  }
  // Photons in air can only land inside the receivers' bounds: the search is
  // clipped to them (photons that never enter them cost one box test).
  double receiverBounds[6];
  if (!this->Internal->Receivers.Compute(scene, receiverBounds))
  {
    std::copy(scene.Bounds, scene.Bounds + 6, receiverBounds);
  }
  const double margin = 1e-3 * Diagonal(scene.Bounds);
  const int* mapSize = receivers->GetSize();
  vtkTextureObject* outputs[] = { this->HitPosition, this->HitNormal, this->HitFlux };
  for (unsigned int i = 0; i < 3; ++i)
  {
    glBindImageTexture(i, outputs[i]->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  }
  glBindBufferBase(
    GL_SHADER_STORAGE_BUFFER, CAUSTICS_PHOTON_STATISTICS_BINDING, this->StatisticsBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_CONTROL_BINDING, this->ListBuffer);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, this->ListBuffer);
  geometry->BindMaterials();
  bool ok = true;
  vtkCausticsShaderProgram* phases[] = { this->SortProgram, this->InsideProgram, this->AirProgram };
  for (int phase = 0; phase < 3 && ok; ++phase)
  {
    vtkCausticsShaderProgram* program = phases[phase];
    if (phase > 0)
    {
      // The list's length is on the GPU: turn it into dispatch arguments there.
      ok = this->ArgumentsProgram->Bind(renWin);
      if (!ok)
      {
        break;
      }
      this->ArgumentsProgram->SetUniformi("level", phase - 1);
      this->ArgumentsProgram->Dispatch(1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
    if (!program->Bind(renWin))
    {
      ok = false;
      break;
    }
    for (int i = 0; i < 9; ++i)
    {
      program->SetUniformi(names[i], inputs[i]->GetTextureUnit());
    }
    caustics::hcm::SetViewUniforms(program, "photonView", photonView, width, width);
    caustics::hcm::SetViewUniforms(program, "mapView", mapView, mapSize[0], mapSize[1]);
    program->SetUniform2i("gridSize", width, height);
    program->SetUniformu("listCapacity", static_cast<unsigned int>(capacity));
    program->SetUniformi("lightType", static_cast<int>(source.type));
    program->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
      static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
    program->SetUniformi("maximumInternalEvents", this->MaximumInternalEvents);
    program->SetUniformi("marchSteps", this->MarchSteps);
    // Longest straight paths: across the refractors' bounds, and across the scene.
    program->SetUniformf("chordLength", static_cast<float>(1.01 * Diagonal(scene.SpecularBounds)));
    program->SetUniformf("airLength", static_cast<float>(1.01 * Diagonal(scene.Bounds)));
    program->SetUniformf("fluxUnit", static_cast<float>(this->FluxUnit));
    program->SetUniform3f("receiverLow", static_cast<float>(receiverBounds[0] - margin),
      static_cast<float>(receiverBounds[2] - margin),
      static_cast<float>(receiverBounds[4] - margin));
    program->SetUniform3f("receiverHigh", static_cast<float>(receiverBounds[1] + margin),
      static_cast<float>(receiverBounds[3] + margin),
      static_cast<float>(receiverBounds[5] + margin));
    if (phase == 0)
    {
      program->DispatchCovering2D(width, height, 8, 8);
    }
    else
    {
      glDispatchComputeIndirect(static_cast<GLintptr>(
        (caustics::hcm::ControlDispatch + 3 * (phase - 1)) * sizeof(std::uint32_t)));
    }
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  if (ok)
  {
    this->AirProgram->Unbind(renWin);
  }
  // Later stages read the photon buffer as textures and the counters as buffers.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
    GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  for (unsigned int i = 0; i < 3; ++i)
  {
    glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  }
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  return ok;
}

bool vtkCausticsPhotonBuffer::GetStatistics(Statistics& statistics)
{
  statistics = Statistics();
  if (!this->StatisticsBuffer)
  {
    vtkErrorMacro(<< "GetStatistics: no photon buffer was rendered");
    return false;
  }
  std::vector<std::uint32_t> words(caustics::hcm::StatSize, 0);
  glGetNamedBufferSubData(
    this->StatisticsBuffer, 0, words.size() * sizeof(std::uint32_t), words.data());
  statistics.Photons = words[caustics::hcm::StatPhotons];
  statistics.Hits = words[caustics::hcm::StatHits];
  statistics.LostInside = words[caustics::hcm::StatLostInside];
  statistics.Escaped = words[caustics::hcm::StatEscaped];
  const double unit = this->FluxUnit;
  using caustics::hcm::FluxFromWords;
  statistics.FluxIn = FluxFromWords(&words[caustics::hcm::StatFluxIn], unit);
  statistics.FluxHits = FluxFromWords(&words[caustics::hcm::StatFluxHits], unit);
  statistics.FluxLostInside = FluxFromWords(&words[caustics::hcm::StatFluxLostInside], unit);
  statistics.FluxEscaped = FluxFromWords(&words[caustics::hcm::StatFluxEscaped], unit);
  statistics.FluxInternalReflection =
    FluxFromWords(&words[caustics::hcm::StatFluxInternalReflection], unit);
  statistics.FluxAbsorbed = FluxFromWords(&words[caustics::hcm::StatFluxAbsorbed], unit);
  return true;
}

void vtkCausticsPhotonBuffer::ReleaseGraphicsResources(vtkWindow* win)
{
  this->FrontLayer->ReleaseGraphicsResources(win);
  this->BackLayer->ReleaseGraphicsResources(win);
  this->HitPosition->ReleaseGraphicsResources(win);
  this->HitNormal->ReleaseGraphicsResources(win);
  this->HitFlux->ReleaseGraphicsResources(win);
  this->SortProgram->ReleaseGraphicsResources(win);
  this->InsideProgram->ReleaseGraphicsResources(win);
  this->AirProgram->ReleaseGraphicsResources(win);
  this->ArgumentsProgram->ReleaseGraphicsResources(win);
  if (this->ListBuffer)
  {
    glDeleteBuffers(1, &this->ListBuffer);
    this->ListBuffer = 0;
    this->ListCapacity = 0;
  }
  if (this->StatisticsBuffer)
  {
    glDeleteBuffers(1, &this->StatisticsBuffer);
    this->StatisticsBuffer = 0;
  }
  this->GridSize[0] = this->GridSize[1] = 0;
}

void vtkCausticsPhotonBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumInternalEvents: " << this->MaximumInternalEvents << "\n";
  os << indent << "MarchSteps: " << this->MarchSteps << "\n";
  os << indent << "GridSize: " << this->GridSize[0] << " x " << this->GridSize[1] << "\n";
  os << indent << "FluxUnit: " << this->FluxUnit << " W\n";
}
