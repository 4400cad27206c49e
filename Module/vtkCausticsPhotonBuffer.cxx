#include "vtkCausticsPhotonBuffer.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsCausticMapSettings.h"
#include "vtkCausticsDistanceImpostors.h"
#include "vtkCausticsGBuffer.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsImpostorCommon.h"
#include "vtkCausticsPhotonBufferUtilities.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsSpecularHierarchy.h"
#include "vtkCausticsVolumeSegmentList.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsOptics.h"
#include "vtkCausticsPhotonBufferCommon.h"
#include "vtkCausticsPhotonBufferHierarchyArgumentsCS.h"
#include "vtkCausticsPhotonBufferTraceCS.h"
#include "vtkCausticsPhotonStatistics.h"
#include "vtkCausticsSpecularTrace.h"
#include "vtkCausticsVolumeLinesCommon.h"

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

/** What every phase of one trace reads besides its program (see Trace()). */
struct vtkCausticsPhotonBuffer::TraceUniforms
{
  const caustics::CausticMapSettings* Settings = nullptr;
  const caustics::Light* Source = nullptr;
  const caustics::SceneData* Scene = nullptr; // its medium and bounds
  const caustics::LightView* PhotonView = nullptr;
  const caustics::LightView* MapView = nullptr;
  const int* MapSize = nullptr;
  int Width = 0, Height = 0;
  std::size_t Capacity = 0;
  double ChordLength = 0.0, AirLength = 0.0, FluxUnit = 1.0;
  double ReceiverLow[3] = { 0, 0, 0 }, ReceiverHigh[3] = { 0, 0, 0 };
  bool Reflectors = false; // the reflector layer holds the scene's mirrors
  bool Hidden = false;     // a hidden receivers' layer is searched
  const caustics::gl::MediumBuffer* MediumGrid = nullptr;    // the medium's density, if any
  caustics::gl::VolumeSegmentList* VolumeSegments = nullptr; // phase 2 appends, when on
  bool InsideAppends = false; // phase 1 appends too (the medium fills the refractors)
  const vtkCausticsSpecularHierarchy* Traced = nullptr; // glass as triangles, or null
  vtkCausticsDistanceImpostors* Store = nullptr; // phase 2's caustic store, or null
  vtkTextureObject* Inputs[13] = { nullptr };
};

namespace
{
const char* const TraceInputNames[13] = { "photonPosition", "photonDirection", "photonFlux",
  "frontPosition", "frontNormal", "backPosition", "backNormal", "receiverPosition",
  "receiverNormal", "reflectorPosition", "reflectorNormal", "hiddenPosition", "hiddenNormal" };

/** Whether a mesh of the scene is a reflector (a mirror). */
bool HasReflectors(const caustics::SceneData& scene)
{
  return std::any_of(scene.Meshes.begin(), scene.Meshes.end(),
    [&scene](const caustics::Mesh& mesh)
    {
      return mesh.material >= 0 && mesh.material < static_cast<int>(scene.Materials.size()) &&
        scene.Materials[mesh.material].role == caustics::Role::Reflector;
    });
}

void SetTraceUniforms(
  vtkCausticsShaderProgram* program, const vtkCausticsPhotonBuffer::TraceUniforms& trace)
{
  for (int i = 0; i < 13; ++i)
  {
    program->SetUniformi(TraceInputNames[i], trace.Inputs[i]->GetTextureUnit());
  }
  program->SetUniformi("hasReflectors", trace.Reflectors ? 1 : 0);
  program->SetUniformi("hasHiddenReceivers", trace.Hidden ? 1 : 0);
  program->SetUniformi("maximumReflections", trace.Settings->MaximumReflections);
  const caustics::Light& source = *trace.Source;
  caustics::hcm::SetViewUniforms(
    program, "photonView", *trace.PhotonView, trace.Width, trace.Width);
  caustics::hcm::SetViewUniforms(
    program, "mapView", *trace.MapView, trace.MapSize[0], trace.MapSize[1]);
  program->SetUniform2i("gridSize", trace.Width, trace.Height);
  program->SetUniformu("listCapacity", static_cast<unsigned int>(trace.Capacity));
  program->SetUniformi("lightType", static_cast<int>(source.type));
  program->SetUniform3f("lightOrigin", static_cast<float>(source.position[0]),
    static_cast<float>(source.position[1]), static_cast<float>(source.position[2]));
  program->SetUniformi("maximumInternalEvents", trace.Settings->MaximumInternalEvents);
  program->SetUniformi("marchSteps", trace.Settings->MarchSteps);
  vtkCausticsSpecularHierarchy::BindTraced(trace.Traced, program);
  caustics::gl::SetMediumUniforms(program, *trace.Scene, trace.MediumGrid);
  program->SetUniformf("chordLength", static_cast<float>(trace.ChordLength));
  program->SetUniformf("airLength", static_cast<float>(trace.AirLength));
  program->SetUniformf("fluxUnit", static_cast<float>(trace.FluxUnit));
  program->SetUniform3f("receiverLow", static_cast<float>(trace.ReceiverLow[0]),
    static_cast<float>(trace.ReceiverLow[1]), static_cast<float>(trace.ReceiverLow[2]));
  program->SetUniform3f("receiverHigh", static_cast<float>(trace.ReceiverHigh[0]),
    static_cast<float>(trace.ReceiverHigh[1]), static_cast<float>(trace.ReceiverHigh[2]));
}

/**
 * The trace's three compute phases: the sort over every texel, then one indirect
 * dispatch per work list (inside the refractors, in air), whose lengths are on the
 * GPU and become dispatch arguments there.
 */
bool RunPhases(vtkOpenGLRenderWindow* renWin, vtkCausticsShaderProgram* const phases[3],
  vtkCausticsShaderProgram* arguments, const vtkCausticsPhotonBuffer::TraceUniforms& trace)
{
  for (int phase = 0; phase < 3; ++phase)
  {
    if (phase > 0)
    {
      if (!arguments->Bind(renWin))
      {
        return false;
      }
      arguments->SetUniformi("level", phase - 1);
      arguments->Dispatch(1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
    vtkCausticsShaderProgram* program = phases[phase];
    if (!program->Bind(renWin))
    {
      return false;
    }
    SetTraceUniforms(program, trace);
    // The caustic store of phase 2's photons that no receiver layer lands (its
    // texture units held through the dispatch).
    caustics::ssp::TextureUnits units(renWin);
    if (phase == 2 && trace.Store)
    {
      trace.Store->SetUniforms(program, units);
    }
    if (trace.VolumeSegments && trace.VolumeSegments->IsOn() &&
      (phase == 2 || (phase == 1 && trace.InsideAppends)))
    {
      trace.VolumeSegments->BindForAppend(program);
    }
    if (phase == 0)
    {
      program->DispatchCovering2D(trace.Width, trace.Height, 8, 8);
    }
    else
    {
      glDispatchComputeIndirect(static_cast<GLintptr>(
        (caustics::hcm::ControlDispatch + 3 * (phase - 1)) * sizeof(std::uint32_t)));
    }
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
  return true;
}
}

struct vtkCausticsPhotonBuffer::Internals
{
  caustics::hcm::ReceiverBoundsCache Receivers;
  caustics::gl::StorageBuffer Statistics; // STAT_* counters
  caustics::gl::StorageBuffer Lists;      // control words, then two work lists
  caustics::gl::PhotonPlanes Landed;      // the trace's in-place state, then its hits
};

vtkCausticsPhotonBuffer::vtkCausticsPhotonBuffer()
  : Internal(new Internals)
{
  this->BackLayer->KeepFarthestOn();
  // The trace reads the layers' positions and normals: no albedo targets.
  this->FrontLayer->AlbedoOff();
  this->BackLayer->AlbedoOff();
  this->ReflectorLayer->AlbedoOff();
  const std::string source = std::string(vtkCausticsOptics) + vtkCausticsPhotonBufferCommon +
    vtkCausticsVolumeLinesCommon + vtkCausticsSpecularTrace + vtkCausticsImpostorCommon +
    vtkCausticsPhotonStatistics + vtkCausticsPhotonBufferTraceCS;
  this->SortProgram->SetName("photon buffer: sort");
  this->SortProgram->SetDefine("PHASE", 0);
  this->SortProgram->SetComputeSource(source.c_str());
  this->InsideProgram->SetName("photon buffer: inside refractors");
  this->InsideProgram->SetDefine("PHASE", 1);
  this->InsideProgram->SetComputeSource(source.c_str());
  this->AirProgram->SetName("photon buffer: to the receivers");
  this->AirProgram->SetDefine("PHASE", 2);
  this->AirProgram->SetComputeSource(source.c_str());
  this->StoreDrawProgram->SetName("photon buffer: the caustic store's draw");
  this->StoreDrawProgram->SetDefine("PHASE", 3);
  this->StoreDrawProgram->SetComputeSource(source.c_str());
  this->ArgumentsProgram->SetName("photon buffer dispatch arguments");
  this->ArgumentsProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->ArgumentsProgram->SetComputeSource(
    (std::string(vtkCausticsPhotonBufferCommon) + vtkCausticsPhotonBufferHierarchyArgumentsCS)
      .c_str());
}

vtkCausticsPhotonBuffer::~vtkCausticsPhotonBuffer()
{
  if (this->Internal->Statistics.Handle() || this->Internal->Lists.Handle())
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): statistics buffer leaked");
  }
}

bool vtkCausticsPhotonBuffer::Render(vtkOpenGLRenderWindow* renWin,
  const caustics::CausticMapSettings& settings, vtkCausticsSceneGeometry* geometry,
  const caustics::SceneData& scene, const caustics::PhotonGrid& grid,
  const caustics::LightView& photonView, const caustics::LightView& mapView,
  vtkCausticsGBuffer* receivers, const caustics::gl::MediumBuffer* mediumGrid)
{
  return this->RenderLayers(renWin, geometry, photonView, grid) &&
    this->Trace(
      renWin, settings, geometry, scene, grid, photonView, mapView, receivers, mediumGrid);
}

bool vtkCausticsPhotonBuffer::RenderLayers(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::LightView& photonView,
  const caustics::PhotonGrid& grid)
{
  // The layers are the light buffers' size, N x N: one texel per photon of a branch.
  const int resolution = grid.Width;
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
  const caustics::CausticMapSettings& settings, vtkCausticsSceneGeometry* geometry,
  const caustics::SceneData& scene, const caustics::PhotonGrid& grid,
  const caustics::LightView& photonView, const caustics::LightView& mapView,
  vtkCausticsGBuffer* receivers, const caustics::gl::MediumBuffer* mediumGrid,
  caustics::gl::VolumeSegmentList* volumeSegments)
{
  const int light = grid.Light;
  if (!receivers || light < 0 || light >= static_cast<int>(scene.Lights.size()))
  {
    vtkErrorMacro(<< "Trace needs emitted photons, a receiver G-buffer and a valid light index");
    return false;
  }
  if (grid.IsEmpty() || this->FrontLayer->GetSize()[0] != grid.Width)
  {
    vtkErrorMacro(<< "Trace needs emitted photons and layers of their resolution");
    return false;
  }
  this->FluxUnit = caustics::hcm::FluxUnit(grid);

  // 2. Outputs and counters: allocated when the size changes, cleared every frame.
  TraceUniforms trace;
  trace.Capacity = this->AllocateOutputs(renWin, grid.Width, grid.Height);

  // Mirrors in the way of photons in air, as the caustic map's view sees them.
  trace.Reflectors = HasReflectors(scene);
  if (trace.Reflectors)
  {
    float mapMatrix[16];
    caustics::gl::ToColumnMajor(mapView.worldToClip, mapMatrix);
    const int* size = receivers->GetSize();
    if (!this->ReflectorLayer->Render(
          renWin, geometry, mapMatrix, size[0], size[1], vtkCausticsSceneGeometry::RoleBit(2)))
    {
      return false;
    }
  }

  // 3. One thread per photon, in two phases (inside the refractors, then in air).
  this->DescribeTrace(settings, scene, grid, photonView, mapView, receivers, trace);
  // Photons follow a heterogeneous medium's density (the programs compile it in).
  trace.MediumGrid = mediumGrid;
  trace.Traced = this->TracedSpecular;
  trace.Store = this->CausticStore;
  if (trace.Store)
  {
    this->AirProgram->SetDefine("CAUSTICS_STORE_ESCAPED", 1);
  }
  else
  {
    this->AirProgram->RemoveDefine("CAUSTICS_STORE_ESCAPED");
  }
  for (vtkCausticsShaderProgram* phase : { this->SortProgram.GetPointer(),
         this->InsideProgram.GetPointer(), this->AirProgram.GetPointer() })
  {
    caustics::gl::SetMediumDefine(phase, mediumGrid);
  }
  // Phase 2's pieces in air, for the volume caustics (each photon: up to one per mirror
  // and the last), and phase 1's inside the refractors when the medium fills them (up
  // to one per interface). Without that phase 1 compiles no append (it would append
  // nothing), and the list's worst case is phase 2's alone.
  const bool fills = scene.Participating.enabled && scene.Participating.fillsRefractors;
  if (volumeSegments)
  {
    volumeSegments->SetAppendDefine(this->AirProgram);
    if (fills)
    {
      volumeSegments->SetAppendDefine(this->InsideProgram);
    }
    else
    {
      this->InsideProgram->RemoveDefine("CAUSTICS_VOLUME_SEGMENT_APPEND");
    }
    if (volumeSegments->IsOn())
    {
      // Per photon: a piece per mirror met, the last mirror's photon stopping there
      // (MaximumReflections + 1 of them), or fewer mirrors and the last piece; plus,
      // with fills, a piece per interface inside (MaximumInternalEvents).
      const int inside = fills ? settings.MaximumInternalEvents : 0;
      volumeSegments->Reserve(renWin,
        static_cast<long long>(trace.Capacity) * (settings.MaximumReflections + 1 + inside),
        settings.VolumeSubSegments, mediumGrid && mediumGrid->HasGrid(),
        fills ? "photon buffer texels, LightBufferResolution^2 per branch, x "
                "(MaximumReflections + 1 + MaximumInternalEvents)"
              : "photon buffer texels, LightBufferResolution^2 per branch, x "
                "(MaximumReflections + 1)",
        fills ? "LightBufferResolution, MaximumReflections or MaximumInternalEvents"
              : "LightBufferResolution or MaximumReflections");
      trace.VolumeSegments = volumeSegments;
      trace.InsideAppends = fills;
    }
  }
  else
  {
    this->AirProgram->RemoveDefine("CAUSTICS_VOLUME_SEGMENT_APPEND");
    this->InsideProgram->RemoveDefine("CAUSTICS_VOLUME_SEGMENT_APPEND");
  }
  for (vtkTextureObject* input : trace.Inputs)
  {
    input->Activate();
  }
  this->BindTraceOutputs(geometry);
  vtkCausticsShaderProgram* phases[] = { this->SortProgram, this->InsideProgram, this->AirProgram };
  bool ok = RunPhases(renWin, phases, this->ArgumentsProgram, trace);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  if (ok)
  {
    this->AirProgram->Unbind(renWin);
  }
  if (ok && trace.Store)
  {
    // The store's final render draws only when it took a share of the light worth a
    // full-screen pass (STAT_STORE_DRAW, set on the GPU).
    ok = this->StoreDrawProgram->Bind(renWin);
    if (ok)
    {
      this->StoreDrawProgram->SetUniformf("storeDrawShare", 1e-3f);
      this->StoreDrawProgram->Dispatch(1);
      this->StoreDrawProgram->Unbind(renWin);
    }
  }
  // Later stages read the photon buffer as textures, the counters as buffers and
  // the final renders' draw arguments from them.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
    GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  for (unsigned int i = 0; i < 3; ++i)
  {
    glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  }
  if (trace.Store)
  {
    glBindImageTexture(CAUSTICS_IMPOSTOR_CAUSTIC_IMAGE, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32I);
  }
  for (vtkTextureObject* input : trace.Inputs)
  {
    input->Deactivate();
  }
  return ok;
}

std::size_t vtkCausticsPhotonBuffer::AllocateOutputs(
  vtkOpenGLRenderWindow* renWin, int width, int height)
{
  this->Internal->Landed.Ensure(renWin, width, height);
  using Usage = caustics::gl::StorageBuffer::Usage;
  this->Internal->Statistics.Allocate(caustics::hcm::StatSize * sizeof(std::uint32_t), Usage::Copy);
  this->Internal->Statistics.Clear();
  // The hidden receivers' final render draws its triangle only if the trace finds a
  // photon that lands there (it sets the instance count).
  // So does the caustic store's, if the trace stores a photon.
  const std::uint32_t noDraw[4] = { 3u, 0u, 0u, 0u };
  this->Internal->Statistics.Write(
    caustics::hcm::StatHiddenDraw * sizeof(std::uint32_t), sizeof(noDraw), noDraw);
  this->Internal->Statistics.Write(
    caustics::hcm::StatStoreDraw * sizeof(std::uint32_t), sizeof(noDraw), noDraw);
  // Work lists (control words, then two lists of up to one entry per texel).
  const std::size_t capacity = static_cast<std::size_t>(width) * height;
  const std::size_t listBytes = (caustics::hcm::ControlSize + 2 * capacity) * sizeof(std::uint32_t);
  this->Internal->Lists.Allocate(listBytes, Usage::Copy);
  this->Internal->Lists.Clear(0, caustics::hcm::ControlSize * sizeof(std::uint32_t));
  return capacity;
}

void vtkCausticsPhotonBuffer::DescribeTrace(const caustics::CausticMapSettings& settings,
  const caustics::SceneData& scene, const caustics::PhotonGrid& grid,
  const caustics::LightView& photonView, const caustics::LightView& mapView,
  vtkCausticsGBuffer* receivers, TraceUniforms& trace)
{
  trace.Settings = &settings;
  trace.Source = &scene.Lights[grid.Light];
  trace.Scene = &scene;
  trace.PhotonView = &photonView;
  trace.MapView = &mapView;
  trace.MapSize = receivers->GetSize();
  trace.Hidden = this->HiddenReceivers &&
    this->HiddenReceivers->GetSize()[0] == trace.MapSize[0] &&
    this->HiddenReceivers->GetSize()[1] == trace.MapSize[1];
  trace.Width = grid.Width;
  trace.Height = grid.Height;
  // Longest straight paths: across one refractor, and across the scene. (The
  // march inside glass takes its steps over the chord: a mirror far away must not
  // make them coarser.)
  trace.ChordLength =
    1.01 * (scene.RefractorChord > 0.0 ? scene.RefractorChord : Diagonal(scene.SpecularBounds));
  trace.AirLength = 1.01 * Diagonal(scene.Bounds);
  trace.FluxUnit = this->FluxUnit;
  vtkTextureObject* inputs[] = { grid.Emitted.Position, grid.Emitted.Direction, grid.Emitted.Flux,
    this->FrontLayer->GetPositionTexture(), this->FrontLayer->GetNormalTexture(),
    this->BackLayer->GetPositionTexture(), this->BackLayer->GetNormalTexture(),
    receivers->GetPositionTexture(), receivers->GetNormalTexture(),
    // Without mirrors the receivers stand in (never read: hasReflectors is 0).
    trace.Reflectors ? this->ReflectorLayer->GetPositionTexture() : receivers->GetPositionTexture(),
    trace.Reflectors ? this->ReflectorLayer->GetNormalTexture() : receivers->GetNormalTexture(),
    // Without hidden receivers the receivers stand in (never read).
    trace.Hidden ? this->HiddenReceivers->GetPositionTexture() : receivers->GetPositionTexture(),
    trace.Hidden ? this->HiddenReceivers->GetNormalTexture() : receivers->GetNormalTexture() };
  std::copy(inputs, inputs + 13, trace.Inputs);
  // Photons in air can only land inside the receivers' bounds: the search is
  // clipped to them (photons that never enter them cost one box test).
  double receiverBounds[6];
  if (!this->Internal->Receivers.Compute(scene, receiverBounds))
  {
    std::copy(scene.Bounds, scene.Bounds + 6, receiverBounds);
  }
  const double margin = 1e-3 * Diagonal(scene.Bounds);
  for (int c = 0; c < 3; ++c)
  {
    trace.ReceiverLow[c] = receiverBounds[2 * c] - margin;
    trace.ReceiverHigh[c] = receiverBounds[2 * c + 1] + margin;
  }
}

void vtkCausticsPhotonBuffer::BindTraceOutputs(vtkCausticsSceneGeometry* geometry)
{
  this->Internal->Landed.BindImages(0, GL_READ_WRITE);
  this->Internal->Statistics.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_PHOTON_STATISTICS_BINDING);
  this->Internal->Lists.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_CONTROL_BINDING);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, this->Internal->Lists.Handle());
  geometry->BindMaterials();
}

const caustics::gl::StorageBuffer& vtkCausticsPhotonBuffer::GetStatisticsBuffer() const
{
  return this->Internal->Statistics;
}

std::size_t vtkCausticsPhotonBuffer::GetHiddenDrawOffset()
{
  return caustics::hcm::StatHiddenDraw * sizeof(std::uint32_t);
}

std::size_t vtkCausticsPhotonBuffer::GetStoreDrawOffset()
{
  return caustics::hcm::StatStoreDraw * sizeof(std::uint32_t);
}

caustics::PhotonRecords vtkCausticsPhotonBuffer::GetLanded() const
{
  return this->Internal->Landed.Records();
}

bool vtkCausticsPhotonBuffer::GetStatistics(Statistics& statistics)
{
  statistics = Statistics();
  if (!this->Internal->Statistics.Handle())
  {
    vtkErrorMacro(<< "GetStatistics: no photon buffer was rendered");
    return false;
  }
  caustics::hcm::ReadPhotonStatistics(this->Internal->Statistics, this->FluxUnit, statistics);
  return true;
}

void vtkCausticsPhotonBuffer::ReleaseGraphicsResources(vtkWindow* win)
{
  this->FrontLayer->ReleaseGraphicsResources(win);
  this->BackLayer->ReleaseGraphicsResources(win);
  this->ReflectorLayer->ReleaseGraphicsResources(win);
  this->Internal->Landed.Release(win);
  this->SortProgram->ReleaseGraphicsResources(win);
  this->InsideProgram->ReleaseGraphicsResources(win);
  this->AirProgram->ReleaseGraphicsResources(win);
  this->ArgumentsProgram->ReleaseGraphicsResources(win);
  this->StoreDrawProgram->ReleaseGraphicsResources(win);
  this->Internal->Lists.Release();
  this->Internal->Statistics.Release();
}

void vtkCausticsPhotonBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FluxUnit: " << this->FluxUnit << " W\n";
}
