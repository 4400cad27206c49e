#include "vtkCausticsPhotonBufferHierarchy.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsCausticMapSettings.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsPhotonBufferUtilities.h"
#include "vtkCausticsPhotonGrid.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "vtkCausticsPhotonBufferCommon.h"
#include "vtkCausticsPhotonBufferHierarchyArgumentsCS.h"
#include "vtkCausticsPhotonBufferHierarchyBuildCS.h"
#include "vtkCausticsPhotonBufferHierarchyGatherCS.h"

#include <algorithm>
#include <cstdint>
#include <string>

vtkStandardNewMacro(vtkCausticsPhotonBufferHierarchy);

namespace
{
constexpr int LocalSize = 64; // work group width of the gather shader
constexpr int NodeBytes = 36; // struct Node in the shaders: 3 uints, 6 floats
constexpr int StageFlat = 0;  // STAGE_* of the gather shader
constexpr int StageNodes = 1;
constexpr int StagePhotons = 2;

using Usage = caustics::gl::StorageBuffer::Usage;
using Settings = caustics::CausticMapSettings;

/** Work groups covering `items`, folded into two dimensions of at most 65535. */
void Groups(std::size_t items, unsigned int& x, unsigned int& y)
{
  const std::size_t groups = (items + LocalSize - 1) / LocalSize;
  x = static_cast<unsigned int>(std::min<std::size_t>(groups, 65535));
  y = x > 0 ? static_cast<unsigned int>((groups + x - 1) / x) : 0;
}
}

struct vtkCausticsPhotonBufferHierarchy::Internals
{
  caustics::gl::StorageBuffer Nodes;   // validity mipmap, levels 1..S
  caustics::gl::StorageBuffer Control; // counters and indirect arguments (CONTROL_*)
  caustics::gl::StorageBuffer Work;    // traversal work lists, one per level
  caustics::gl::StorageBuffer Splats;  // splat entries, one region per caustic map level
};

vtkCausticsPhotonBufferHierarchy::vtkCausticsPhotonBufferHierarchy()
  : Internal(new Internals)
{
  const std::string common = vtkCausticsPhotonBufferCommon;
  this->BuildProgram->SetName("validity mipmap");
  this->BuildProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->BuildProgram->SetComputeSource((common + vtkCausticsPhotonBufferHierarchyBuildCS).c_str());
  const char* stageNames[] = { "flat gather", "hierarchical traversal", "photon transform" };
  for (int stage = 0; stage < 3; ++stage)
  {
    vtkCausticsShaderProgram* program = this->GatherPrograms[stage];
    program->SetName(stageNames[stage]);
    program->SetDefine("CAUSTICS_NO_MATERIALS", 1);
    program->SetDefine("STAGE", stage);
    program->SetComputeSource((common + vtkCausticsPhotonBufferHierarchyGatherCS).c_str());
  }
  this->ArgumentsProgram->SetName("traversal dispatch arguments");
  this->ArgumentsProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  this->ArgumentsProgram->SetComputeSource(
    (common + vtkCausticsPhotonBufferHierarchyArgumentsCS).c_str());
}

vtkCausticsPhotonBufferHierarchy::~vtkCausticsPhotonBufferHierarchy()
{
  const Internals& in = *this->Internal;
  if (in.Nodes.Handle() || in.Control.Handle() || in.Work.Handle() || in.Splats.Handle())
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL buffers leaked");
  }
}

const caustics::gl::StorageBuffer& vtkCausticsPhotonBufferHierarchy::GetControlBuffer() const
{
  return this->Internal->Control;
}

const caustics::gl::StorageBuffer& vtkCausticsPhotonBufferHierarchy::GetSplatBuffer() const
{
  return this->Internal->Splats;
}

const caustics::gl::StorageBuffer& vtkCausticsPhotonBufferHierarchy::GetNodeBuffer() const
{
  return this->Internal->Nodes;
}

unsigned int vtkCausticsPhotonBufferHierarchy::GetNodeOffset(int k) const
{
  return k >= 1 && k < static_cast<int>(this->NodeOffset.size()) ? this->NodeOffset[k] : 0;
}

int vtkCausticsPhotonBufferHierarchy::GetNodeRowLength(int k) const
{
  return k >= 0 && k < static_cast<int>(this->LevelWidth.size()) ? this->LevelWidth[k] : 1;
}

unsigned int vtkCausticsPhotonBufferHierarchy::GetDrawArgumentsOffset(int j)
{
  return static_cast<unsigned int>((caustics::hcm::ControlDraw + 4 * j) * sizeof(std::uint32_t));
}

void vtkCausticsPhotonBufferHierarchy::Layout(int width, int height, int startResolution)
{
  // Level k covers 2^k x 2^k photons; the traversal starts at the first level at
  // most startResolution nodes wide (the emitter's branches are square, so the
  // width decides; a 2N-high buffer starts from two stacked squares).
  int start = 0;
  while (
    start + 1 < caustics::hcm::MaxTraversalLevels && ((width - 1) >> start) + 1 > startResolution)
  {
    ++start;
  }
  this->StartLevel = start;
  this->LevelWidth.assign(start + 1, 0);
  this->LevelHeight.assign(start + 1, 0);
  this->NodeOffset.assign(start + 1, 0);
  this->ListOffset.assign(start + 1, 0);
  unsigned int nodes = 0, list = 0;
  for (int k = 0; k <= start; ++k)
  {
    this->LevelWidth[k] = ((width - 1) >> k) + 1;
    this->LevelHeight[k] = ((height - 1) >> k) + 1;
    const unsigned int count = static_cast<unsigned int>(this->LevelWidth[k]) *
      static_cast<unsigned int>(this->LevelHeight[k]);
    this->ListOffset[k] = list;
    list += count;
    if (k >= 1)
    {
      this->NodeOffset[k] = nodes;
      nodes += count;
    }
  }
  this->Internal->Nodes.Allocate(static_cast<std::size_t>(nodes) * NodeBytes, Usage::Copy);
  this->Internal->Work.Allocate(static_cast<std::size_t>(list) * 4, Usage::Copy);
  this->SplatRegion = static_cast<unsigned int>(width) * static_cast<unsigned int>(height);
  this->Internal->Splats.Allocate(
    static_cast<std::size_t>(this->SplatRegion) * 4 * caustics::hcm::MapLevels, Usage::Copy);
}

bool vtkCausticsPhotonBufferHierarchy::Gather(vtkOpenGLRenderWindow* renWin,
  const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
  const caustics::PhotonRecords& landed, const caustics::LightView& mapView, int lightType,
  const caustics::Camera* camera)
{
  const int mapResolution = settings.CausticMapResolution;
  const int width = grid.Width;
  const int height = grid.Height;
  if (!landed.IsSet() || grid.IsEmpty() || mapResolution <= 0)
  {
    vtkErrorMacro(<< "Gather needs a rendered photon buffer and a caustic map resolution");
    return false;
  }
  if (static_cast<long long>(width) * height > (1LL << 28) || height > 65535 ||
    mapResolution > 65535)
  {
    vtkErrorMacro(<< "photon buffer " << width << " x " << height
                  << " too large for 28-bit splat entries");
    return false;
  }
  this->Layout(width, height, settings.TraversalStartResolution);
  const bool flat = settings.GatherMode == Settings::GATHER_FLAT;
  this->LastGatherFlat = flat;
  this->LastDropCoarseSplats = settings.DropCoarseSplats;
  this->FluxUnit = caustics::hcm::FluxUnit(grid);
  caustics::gl::EnsureTexture(this->SplatRadius, renWin, width, height, GL_R32F);

  // Control block: counters zero, one instance per indirect draw, and the length
  // of the first list (every photon, or every node of the start level).
  std::uint32_t control[caustics::hcm::ControlSize] = { 0 };
  for (int j = 0; j < caustics::hcm::MapLevels; ++j)
  {
    control[caustics::hcm::ControlDraw + 4 * j + 1] = 1;
  }
  const int first = flat ? 0 : this->StartLevel;
  control[caustics::hcm::ControlListCount + first] = static_cast<std::uint32_t>(
    static_cast<std::size_t>(this->LevelWidth[first]) * this->LevelHeight[first]);
  this->Internal->Control.Allocate(sizeof(control), Usage::Copy);
  this->Internal->Control.Write(0, sizeof(control), control);

  if (!flat && !this->BuildMipmap(renWin, landed, mapView, mapResolution))
  {
    return false;
  }
  return this->Traverse(renWin, settings, grid, landed, mapView, lightType, camera);
}

bool vtkCausticsPhotonBufferHierarchy::BuildMipmap(vtkOpenGLRenderWindow* renWin,
  const caustics::PhotonRecords& landed, const caustics::LightView& mapView, int mapResolution)
{
  if (this->StartLevel < 1)
  {
    return true; // the photon buffer is already no wider than the start
  }
  vtkCausticsShaderProgram* program = this->BuildProgram;
  if (!program->Bind(renWin))
  {
    return false;
  }
  vtkTextureObject* position = landed.Position;
  vtkTextureObject* flux = landed.Flux;
  position->Activate();
  flux->Activate();
  program->SetUniformi("hitPosition", position->GetTextureUnit());
  program->SetUniformi("hitFlux", flux->GetTextureUnit());
  caustics::hcm::SetViewUniforms(program, "mapView", mapView, mapResolution, mapResolution);
  this->Internal->Nodes.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_NODES_BINDING);
  for (int k = 1; k <= this->StartLevel; ++k)
  {
    program->SetUniformi("level", k);
    program->SetUniform2i("levelSize", this->LevelWidth[k], this->LevelHeight[k]);
    program->SetUniform2i("childSize", this->LevelWidth[k - 1], this->LevelHeight[k - 1]);
    program->SetUniformu("levelOffset", this->NodeOffset[k]);
    program->SetUniformu("childOffset", k > 1 ? this->NodeOffset[k - 1] : 0u);
    program->DispatchCovering2D(this->LevelWidth[k], this->LevelHeight[k], 8, 8);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  position->Deactivate();
  flux->Deactivate();
  program->Unbind(renWin);
  return true;
}

bool vtkCausticsPhotonBufferHierarchy::Traverse(vtkOpenGLRenderWindow* renWin,
  const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
  const caustics::PhotonRecords& landed, const caustics::LightView& mapView, int lightType,
  const caustics::Camera* camera)
{
  vtkTextureObject* inputs[] = { landed.Position, landed.Direction, landed.Flux };
  const char* names[] = { "hitPosition", "hitNormal", "hitFlux" };
  for (vtkTextureObject* input : inputs)
  {
    input->Activate();
  }
  glBindImageTexture(0, this->SplatRadius->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  Internals& in = *this->Internal;
  in.Nodes.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_NODES_BINDING);
  in.Control.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_CONTROL_BINDING);
  in.Work.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_WORK_BINDING);
  in.Splats.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_SPLATS_BINDING);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.Control.Handle());

  const bool flat = settings.GatherMode == Settings::GATHER_FLAT;
  const int start = flat ? 0 : this->StartLevel;
  bool ok = true;
  for (int k = start; k >= 0 && ok; --k)
  {
    const bool implicit = k == start;
    if (!implicit)
    {
      // The list's length is on the GPU: turn it into dispatch arguments there.
      ok = this->ArgumentsProgram->Bind(renWin);
      if (!ok)
      {
        break;
      }
      this->ArgumentsProgram->SetUniformi("level", k);
      this->ArgumentsProgram->Dispatch(1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    }
    vtkCausticsShaderProgram* gather =
      this->GatherPrograms[flat ? StageFlat : (k > 0 ? StageNodes : StagePhotons)];
    if (!gather->Bind(renWin))
    {
      ok = false;
      break;
    }
    for (int i = 0; i < 3; ++i)
    {
      gather->SetUniformi(names[i], inputs[i]->GetTextureUnit());
    }
    this->SetGatherUniforms(gather, settings, grid, mapView, lightType, camera);
    this->SetLevelUniforms(gather, settings, k, implicit);
    if (implicit)
    {
      unsigned int x, y;
      Groups(static_cast<std::size_t>(this->LevelWidth[k]) * this->LevelHeight[k], x, y);
      gather->Dispatch(x, y, 1);
    }
    else
    {
      glDispatchComputeIndirect(
        static_cast<GLintptr>((caustics::hcm::ControlDispatch + 3 * k) * sizeof(std::uint32_t)));
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gather->Unbind(renWin);
  }
  // The caustic map draws from the lists and radii, with arguments from the GPU.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
    GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  for (vtkTextureObject* input : inputs)
  {
    input->Deactivate();
  }
  return ok;
}

void vtkCausticsPhotonBufferHierarchy::SetGatherUniforms(vtkCausticsShaderProgram* gather,
  const caustics::CausticMapSettings& settings, const caustics::PhotonGrid& grid,
  const caustics::LightView& mapView, int lightType, const caustics::Camera* camera)
{
  caustics::hcm::SetViewUniforms(
    gather, "mapView", mapView, settings.CausticMapResolution, settings.CausticMapResolution);
  if (camera)
  {
    caustics::hcm::SetCameraViewUniforms(gather, "cameraView", *camera);
  }
  gather->SetUniformf("minimumCameraRadiusPixels",
    camera ? static_cast<float>(settings.MinimumCameraSplatRadius) : 0.0f);
  gather->SetUniform2i("gridSize", grid.Width, grid.Height);
  gather->SetUniformi("branchRows", std::max(grid.BranchRows, 1));
  gather->SetUniformu("splatRegion", this->SplatRegion);
  gather->SetUniformi("lightType", lightType);
  gather->SetUniformi("splatMode", settings.SplatMode);
  gather->SetUniformf("splatScale", static_cast<float>(settings.SplatScale));
  gather->SetUniformf("maxDistanceFraction", static_cast<float>(settings.MaxDistanceFraction));
  gather->SetUniformf("constantRadiusPixels", static_cast<float>(settings.ConstantSplatRadius));
  gather->SetUniformf("splatSizeThreshold", static_cast<float>(settings.SplatSizeThreshold));
  gather->SetUniformi("dropCoarseSplats", settings.DropCoarseSplats ? 1 : 0);
  gather->SetUniformf("fluxUnit", static_cast<float>(this->FluxUnit));
}

void vtkCausticsPhotonBufferHierarchy::SetLevelUniforms(vtkCausticsShaderProgram* gather,
  const caustics::CausticMapSettings& settings, int k, bool implicit)
{
  gather->SetUniformi("level", k);
  gather->SetUniformi("implicitList", implicit ? 1 : 0);
  gather->SetUniform2i("levelSize", this->LevelWidth[k], this->LevelHeight[k]);
  gather->SetUniform2i(
    "childSize", this->LevelWidth[std::max(k - 1, 0)], this->LevelHeight[std::max(k - 1, 0)]);
  gather->SetUniformu("nodeOffset", k > 0 ? this->NodeOffset[k] : 0u);
  gather->SetUniformu("listOffset", this->ListOffset[k]);
  gather->SetUniformu("childListOffset", k > 0 ? this->ListOffset[k - 1] : 0u);
  const bool test = k > 0 &&
    (settings.ClusterMode == Settings::CLUSTER_ALL_LEVELS ||
      (settings.ClusterMode == Settings::CLUSTER_LAST_LEVEL && k == 1));
  gather->SetUniformi("testConvergence", test ? 1 : 0);
  // The start level holds every valid photon; the flat gather meets each one.
  gather->SetUniformi("countValid", implicit ? 1 : 0);
}

bool vtkCausticsPhotonBufferHierarchy::GetCounters(Counters& counters)
{
  counters = Counters();
  if (!this->Internal->Control.Handle())
  {
    vtkErrorMacro(<< "GetCounters: no gather ran");
    return false;
  }
  std::uint32_t words[caustics::hcm::ControlSize];
  this->Internal->Control.Read(0, sizeof(words), words);
  counters.StartLevel = this->LastGatherFlat ? 0 : this->StartLevel;
  for (int k = 0; k <= counters.StartLevel; ++k)
  {
    counters.Processed[k] = words[caustics::hcm::ControlListCount + k];
    counters.TotalProcessed += counters.Processed[k];
  }
  counters.Valid = words[caustics::hcm::ControlValid];
  counters.Clusters = words[caustics::hcm::ControlClusters];
  counters.ClusteredPhotons = words[caustics::hcm::ControlClusteredPhotons];
  counters.CoarseSplats = words[caustics::hcm::ControlCoarseSplats];
  double gathered = 0.0;
  for (int j = 0; j < caustics::hcm::MapLevels; ++j)
  {
    counters.Splats[j] = words[caustics::hcm::ControlDraw + 4 * j];
    counters.SplatFlux[j] =
      caustics::hcm::FluxFromWords(&words[caustics::hcm::ControlSplatFlux + 2 * j], this->FluxUnit);
    gathered += counters.SplatFlux[j];
  }
  counters.CoarseFlux =
    caustics::hcm::FluxFromWords(&words[caustics::hcm::ControlCoarseFlux], this->FluxUnit);
  if (this->LastDropCoarseSplats)
  {
    gathered += counters.CoarseFlux;
  }
  counters.CoarseFluxFraction = gathered > 0.0 ? counters.CoarseFlux / gathered : 0.0;
  counters.DroppedFluxFraction = this->LastDropCoarseSplats ? counters.CoarseFluxFraction : 0.0;
  return true;
}

void vtkCausticsPhotonBufferHierarchy::ReleaseGraphicsResources(vtkWindow* win)
{
  this->BuildProgram->ReleaseGraphicsResources(win);
  for (auto& program : this->GatherPrograms)
  {
    program->ReleaseGraphicsResources(win);
  }
  this->ArgumentsProgram->ReleaseGraphicsResources(win);
  this->SplatRadius->ReleaseGraphicsResources(win);
  Internals& in = *this->Internal;
  for (caustics::gl::StorageBuffer* buffer : { &in.Nodes, &in.Control, &in.Work, &in.Splats })
  {
    buffer->Release();
  }
}

void vtkCausticsPhotonBufferHierarchy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Last gather: " << (this->LastGatherFlat ? "flat" : "hierarchical") << "\n";
  os << indent << "StartLevel: " << this->StartLevel << "\n";
  os << indent << "SplatRegion: " << this->SplatRegion << " entries per map level\n";
}
