#include "vtkCausticsPhotonBufferHierarchy.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsPhotonBuffer.h"
#include "vtkCausticsPhotonBufferUtilities.h"
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

/** Grows `buffer` to at least `bytes` (never shrinks, never reallocates per frame). */
void EnsureBuffer(unsigned int& buffer, std::size_t& capacity, std::size_t bytes)
{
  bytes = std::max<std::size_t>(bytes, 16);
  if (!buffer)
  {
    glCreateBuffers(1, &buffer);
    capacity = 0;
  }
  if (bytes > capacity)
  {
    glNamedBufferData(buffer, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_COPY);
    capacity = bytes;
  }
}

/** Work groups covering `items`, folded into two dimensions of at most 65535. */
void Groups(std::size_t items, unsigned int& x, unsigned int& y)
{
  const std::size_t groups = (items + LocalSize - 1) / LocalSize;
  x = static_cast<unsigned int>(std::min<std::size_t>(groups, 65535));
  y = x > 0 ? static_cast<unsigned int>((groups + x - 1) / x) : 0;
}
}

vtkCausticsPhotonBufferHierarchy::vtkCausticsPhotonBufferHierarchy()
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
  if (this->NodeBuffer || this->ControlBuffer || this->WorkBuffer || this->SplatBuffer)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL buffers leaked");
  }
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

void vtkCausticsPhotonBufferHierarchy::Layout(int width, int height)
{
  // Level k covers 2^k x 2^k photons; the traversal starts at the first level at
  // most StartResolution nodes wide (the emitter's branches are square, so the
  // width decides; a 2N-high buffer starts from two stacked squares).
  int start = 0;
  while (start + 1 < caustics::hcm::MaxTraversalLevels &&
    ((width - 1) >> start) + 1 > this->StartResolution)
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
  EnsureBuffer(this->NodeBuffer, this->NodeCapacity, static_cast<std::size_t>(nodes) * NodeBytes);
  EnsureBuffer(this->WorkBuffer, this->WorkCapacity, static_cast<std::size_t>(list) * 4);
  this->SplatRegion = static_cast<unsigned int>(width) * static_cast<unsigned int>(height);
  EnsureBuffer(this->SplatBuffer, this->SplatCapacity,
    static_cast<std::size_t>(this->SplatRegion) * 4 * caustics::hcm::MapLevels);
}

bool vtkCausticsPhotonBufferHierarchy::Gather(vtkOpenGLRenderWindow* renWin,
  vtkCausticsPhotonBuffer* photons, const caustics::LightView& mapView, int mapResolution,
  int lightType, const caustics::Camera* camera)
{
  const int width = photons ? photons->GetGridSize()[0] : 0;
  const int height = photons ? photons->GetGridSize()[1] : 0;
  if (width <= 0 || height <= 0 || mapResolution <= 0)
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
  this->Layout(width, height);
  this->LastGatherMode = this->GatherMode;
  this->FluxUnit = photons->GetFluxUnit();
  caustics::gl::EnsureTexture(this->SplatRadius, renWin, width, height, GL_R32F);

  // Control block: counters zero, one instance per indirect draw, and the length
  // of the first list (every photon, or every node of the start level).
  std::uint32_t control[caustics::hcm::ControlSize] = { 0 };
  for (int j = 0; j < caustics::hcm::MapLevels; ++j)
  {
    control[caustics::hcm::ControlDraw + 4 * j + 1] = 1;
  }
  const bool flat = this->GatherMode == GATHER_FLAT;
  const int first = flat ? 0 : this->StartLevel;
  control[caustics::hcm::ControlListCount + first] = static_cast<std::uint32_t>(
    static_cast<std::size_t>(this->LevelWidth[first]) * this->LevelHeight[first]);
  if (!this->ControlBuffer)
  {
    glCreateBuffers(1, &this->ControlBuffer);
    glNamedBufferData(this->ControlBuffer, sizeof(control), nullptr, GL_DYNAMIC_COPY);
  }
  glNamedBufferSubData(this->ControlBuffer, 0, sizeof(control), control);

  if (!flat && !this->BuildMipmap(renWin, photons, mapView, mapResolution))
  {
    return false;
  }
  return this->Traverse(renWin, photons, mapView, mapResolution, lightType, camera);
}

bool vtkCausticsPhotonBufferHierarchy::BuildMipmap(vtkOpenGLRenderWindow* renWin,
  vtkCausticsPhotonBuffer* photons, const caustics::LightView& mapView, int mapResolution)
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
  vtkTextureObject* position = photons->GetHitPositionTexture();
  vtkTextureObject* flux = photons->GetHitFluxTexture();
  position->Activate();
  flux->Activate();
  program->SetUniformi("hitPosition", position->GetTextureUnit());
  program->SetUniformi("hitFlux", flux->GetTextureUnit());
  caustics::hcm::SetViewUniforms(program, "mapView", mapView, mapResolution, mapResolution);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_NODES_BINDING, this->NodeBuffer);
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
  vtkCausticsPhotonBuffer* photons, const caustics::LightView& mapView, int mapResolution,
  int lightType, const caustics::Camera* camera)
{
  vtkTextureObject* inputs[] = { photons->GetHitPositionTexture(), photons->GetHitNormalTexture(),
    photons->GetHitFluxTexture() };
  const char* names[] = { "hitPosition", "hitNormal", "hitFlux" };
  for (vtkTextureObject* input : inputs)
  {
    input->Activate();
  }
  const int* grid = photons->GetGridSize();
  glBindImageTexture(0, this->SplatRadius->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_NODES_BINDING, this->NodeBuffer);
  glBindBufferBase(
    GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_CONTROL_BINDING, this->ControlBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_WORK_BINDING, this->WorkBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_HIERARCHY_SPLATS_BINDING, this->SplatBuffer);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, this->ControlBuffer);

  const bool flat = this->GatherMode == GATHER_FLAT;
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
    caustics::hcm::SetViewUniforms(gather, "mapView", mapView, mapResolution, mapResolution);
    if (camera)
    {
      caustics::hcm::SetCameraViewUniforms(gather, "cameraView", *camera);
    }
    gather->SetUniformf("minimumCameraRadiusPixels",
      camera ? static_cast<float>(this->MinimumCameraSplatRadius) : 0.0f);
    gather->SetUniform2i("gridSize", grid[0], grid[1]);
    gather->SetUniformi("branchRows", std::max(photons->GetBranchRows(), 1));
    gather->SetUniformu("splatRegion", this->SplatRegion);
    gather->SetUniformi("lightType", lightType);
    gather->SetUniformi("splatMode", this->SplatMode);
    gather->SetUniformf("splatScale", static_cast<float>(this->SplatScale));
    gather->SetUniformf("constantRadiusPixels", static_cast<float>(this->ConstantSplatRadius));
    gather->SetUniformf("splatSizeThreshold", static_cast<float>(this->SplatSizeThreshold));
    gather->SetUniformi("dropCoarseSplats", this->DropCoarseSplats ? 1 : 0);
    gather->SetUniformf("fluxUnit", static_cast<float>(this->FluxUnit));
    gather->SetUniformi("level", k);
    gather->SetUniformi("implicitList", implicit ? 1 : 0);
    gather->SetUniform2i("levelSize", this->LevelWidth[k], this->LevelHeight[k]);
    gather->SetUniform2i(
      "childSize", this->LevelWidth[std::max(k - 1, 0)], this->LevelHeight[std::max(k - 1, 0)]);
    gather->SetUniformu("nodeOffset", k > 0 ? this->NodeOffset[k] : 0u);
    gather->SetUniformu("listOffset", this->ListOffset[k]);
    gather->SetUniformu("childListOffset", k > 0 ? this->ListOffset[k - 1] : 0u);
    const bool test = k > 0 &&
      (this->ClusterMode == CLUSTER_ALL_LEVELS ||
        (this->ClusterMode == CLUSTER_LAST_LEVEL && k == 1));
    gather->SetUniformi("testConvergence", test ? 1 : 0);
    // The start level holds every valid photon; the flat gather meets each one.
    gather->SetUniformi("countValid", implicit ? 1 : 0);
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

bool vtkCausticsPhotonBufferHierarchy::GetCounters(Counters& counters)
{
  counters = Counters();
  if (!this->ControlBuffer)
  {
    vtkErrorMacro(<< "GetCounters: no gather ran");
    return false;
  }
  std::uint32_t words[caustics::hcm::ControlSize];
  glGetNamedBufferSubData(this->ControlBuffer, 0, sizeof(words), words);
  const bool flat = this->LastGatherMode == GATHER_FLAT;
  counters.StartLevel = flat ? 0 : this->StartLevel;
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
  if (this->DropCoarseSplats)
  {
    gathered += counters.CoarseFlux;
  }
  counters.CoarseFluxFraction = gathered > 0.0 ? counters.CoarseFlux / gathered : 0.0;
  counters.DroppedFluxFraction = this->DropCoarseSplats ? counters.CoarseFluxFraction : 0.0;
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
  for (unsigned int* buffer :
    { &this->NodeBuffer, &this->ControlBuffer, &this->WorkBuffer, &this->SplatBuffer })
  {
    if (*buffer)
    {
      glDeleteBuffers(1, buffer);
      *buffer = 0;
    }
  }
  this->NodeCapacity = this->WorkCapacity = this->SplatCapacity = 0;
}

void vtkCausticsPhotonBufferHierarchy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const char* gathers[] = { "flat", "hierarchical" };
  const char* clusters[] = { "none", "last level", "all levels" };
  const char* splats[] = { "constant", "varying, single map", "varying, multi-resolution" };
  os << indent << "GatherMode: " << gathers[this->GatherMode] << "\n";
  os << indent << "ClusterMode: " << clusters[this->ClusterMode] << "\n";
  os << indent << "SplatMode: " << splats[this->SplatMode] << "\n";
  os << indent << "StartResolution: " << this->StartResolution << "\n";
  os << indent << "SplatScale: " << this->SplatScale << "\n";
  os << indent << "ConstantSplatRadius: " << this->ConstantSplatRadius << " px\n";
  os << indent << "SplatSizeThreshold: " << this->SplatSizeThreshold << " px\n";
  os << indent << "DropCoarseSplats: " << this->DropCoarseSplats << "\n";
  os << indent << "MinimumCameraSplatRadius: " << this->MinimumCameraSplatRadius
     << " camera pixel footprints\n";
  os << indent << "StartLevel: " << this->StartLevel << "\n";
}
