#include "vtkCausticsLayeredDepth.h"

#include "vtkCausticsBindings.h" // CAUSTICS_*_BINDING
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneGeometry.h"
#include "vtkCausticsScreenSpaceUtilities.h"
#include "vtkCausticsShaderProgram.h"
#include "vtkCausticsTimings.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtk_glew.h"

#include "vtkCausticsFullScreenVS.h"
#include "vtkCausticsGBufferVS.h"
#include "vtkCausticsLayeredDepthClearFS.h"
#include "vtkCausticsLayeredDepthCountFS.h"
#include "vtkCausticsLayeredDepthFinalizeCS.h"
#include "vtkCausticsLayeredDepthPeelFS.h"
#include "vtkCausticsLayeredDepthReduceCS.h"
#include "vtkCausticsScreenSpaceCommon.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsLayeredDepth);

namespace
{
// Shader storage bindings (glsl/vtkCausticsScreenSpaceCommon.glsl).

/** A contiguous range of the scene geometry's index buffer. */
struct IndexRange
{
  std::uint32_t FirstIndex;
  std::uint32_t Count;
};

/**
 * Index ranges of every mesh in vtkCausticsSceneGeometry's buffers. Upload() lays
 * the meshes out stably sorted by role, each a block of indices; this must stay in
 * step with it (checked against the geometry's triangle count in Render()).
 */
std::vector<IndexRange> MeshRanges(const caustics::SceneData& scene)
{
  std::vector<int> order(scene.Meshes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
    [&](int a, int b)
    {
      return scene.Materials[scene.Meshes[a].material].role <
        scene.Materials[scene.Meshes[b].material].role;
    });
  std::vector<IndexRange> ranges(scene.Meshes.size());
  std::uint32_t first = 0;
  for (int m : order)
  {
    const auto count = static_cast<std::uint32_t>(scene.Meshes[m].indices.size());
    ranges[m] = { first, count };
    first += count;
  }
  return ranges;
}

/** Total indices of the ranges: three per triangle. */
std::uint64_t CountIndices(const std::vector<IndexRange>& ranges)
{
  std::uint64_t total = 0;
  for (const IndexRange& range : ranges)
  {
    total += range.Count;
  }
  return total;
}

/** Which LDI every mesh is peeled into, and the index ranges of every LDI. */
struct ObjectLayout
{
  std::vector<int> MeshObject; // per mesh: its object, -1 where the mesh is not drawn
  int Objects = 1;
  std::vector<std::vector<IndexRange>> Ranges; // per object
};

/** Each object's index ranges, merged where meshes are adjacent in the buffer. */
std::vector<std::vector<IndexRange>> MergeObjectRanges(
  const std::vector<IndexRange>& ranges, const std::vector<int>& meshObject, int objects)
{
  std::vector<std::vector<IndexRange>> objectRanges(objects);
  std::vector<int> byFirst(ranges.size());
  std::iota(byFirst.begin(), byFirst.end(), 0);
  std::sort(byFirst.begin(), byFirst.end(),
    [&](int a, int b) { return ranges[a].FirstIndex < ranges[b].FirstIndex; });
  for (int m : byFirst)
  {
    if (meshObject[m] < 0)
    {
      continue;
    }
    auto& list = objectRanges[meshObject[m]];
    if (!list.empty() && list.back().FirstIndex + list.back().Count == ranges[m].FirstIndex)
    {
      list.back().Count += ranges[m].Count;
    }
    else
    {
      list.push_back(ranges[m]);
    }
  }
  return objectRanges;
}

/**
 * Gives the non-empty meshes of the drawn roles their object: all the scene's one,
 * or with perObject one each, the meshes beyond maxObjects sharing the last.
 */
ObjectLayout AssignObjects(const caustics::SceneData& scene, const std::vector<IndexRange>& ranges,
  int roleMask, bool perObject, int maxObjects)
{
  ObjectLayout layout;
  layout.MeshObject.assign(scene.Meshes.size(), -1);
  int objects = 0;
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    const int role = static_cast<int>(scene.Materials[scene.Meshes[m].material].role);
    if (!(roleMask & vtkCausticsSceneGeometry::RoleBit(role)) || ranges[m].Count == 0)
    {
      continue;
    }
    if (perObject)
    {
      layout.MeshObject[m] = std::min(objects, maxObjects - 1);
      objects = std::min(objects + 1, maxObjects);
    }
    else
    {
      layout.MeshObject[m] = 0;
      objects = 1;
    }
  }
  layout.Objects = std::max(objects, 1);
  layout.Ranges = MergeObjectRanges(ranges, layout.MeshObject, layout.Objects);
  return layout;
}

/** All the draw commands depend on: they are rebuilt only when it changes. */
std::vector<std::uint32_t> LayoutSignature(
  const ObjectLayout& layout, int layers, std::size_t materials)
{
  std::vector<std::uint32_t> signature = { static_cast<std::uint32_t>(layout.Objects),
    static_cast<std::uint32_t>(layers), static_cast<std::uint32_t>(materials) };
  for (std::size_t m = 0; m < layout.MeshObject.size(); ++m)
  {
    signature.push_back(static_cast<std::uint32_t>(layout.MeshObject[m] + 1));
  }
  for (const auto& list : layout.Ranges)
  {
    signature.push_back(0xffffffffu);
    for (const IndexRange& range : list)
    {
      signature.push_back(range.FirstIndex);
      signature.push_back(range.Count);
    }
  }
  return signature;
}

/**
 * Everything the LDI is a function of: the view, the size, the settings, and per
 * mesh what vtkCausticsSceneGeometry draws from it (its version, globally unique and
 * renewed whenever its triangles or its actor's matrix change, its material slot and
 * role) and the geometry object itself. Equal keys give equal layers.
 */
std::vector<std::uint64_t> ContentKey(const caustics::SceneData& scene,
  const vtkCausticsSceneGeometry* geometry, const float worldToClip[16], int width, int height,
  const std::vector<std::uint64_t>& settings)
{
  std::vector<std::uint64_t> key = settings;
  key.push_back(reinterpret_cast<std::uintptr_t>(geometry));
  key.push_back(static_cast<std::uint64_t>(width) << 32 | static_cast<std::uint32_t>(height));
  caustics::gl::AppendKey(key, worldToClip, 16);
  caustics::gl::AppendMeshesKey(key, scene);
  return key;
}

/** One full-screen-triangle command (gated by the finalize pass) per layer. */
std::vector<std::uint32_t> ClearCommandList(int layers)
{
  std::vector<std::uint32_t> clear;
  for (int i = 0; i < layers; ++i)
  {
    clear.insert(clear.end(), { 3u, 0u, 0u, 0u });
  }
  return clear;
}

/** Per material, the object of its mesh (0 for meshes not drawn). */
std::vector<std::uint32_t> MaterialObjects(
  const caustics::SceneData& scene, const ObjectLayout& layout)
{
  std::vector<std::uint32_t> objectMap(std::max<std::size_t>(scene.Materials.size(), 1), 0u);
  for (std::size_t m = 0; m < layout.MeshObject.size(); ++m)
  {
    // Materials are one per mesh, same index (vtkCausticsSceneData.h).
    objectMap[scene.Meshes[m].material] =
      static_cast<std::uint32_t>(std::max(layout.MeshObject[m], 0));
  }
  return objectMap;
}
}

struct vtkCausticsLayeredDepth::Internals
{
  caustics::ssp::Texture Complexity; // R32UI array: objects
  caustics::ssp::Texture Position;   // RGBA32F array: objects x layers
  caustics::ssp::Texture Normal;     // RGBA16F array
  caustics::ssp::Texture Depth;      // R32F array
  caustics::ssp::Texture PeelDepth[2];
  caustics::gl::StorageBuffer Table;
  caustics::gl::StorageBuffer ObjectMap;
  caustics::gl::StorageBuffer CommandInfo;
  caustics::gl::StorageBuffer DrawCommands;
  caustics::gl::StorageBuffer ClearCommands;
  caustics::ssp::Framebuffer CountFramebuffer;
  caustics::ssp::Framebuffer PeelFramebuffer;
  unsigned int VertexArray = 0;
  unsigned int EmptyVertexArray = 0;
  vtkNew<vtkCausticsShaderProgram> CountProgram;
  vtkNew<vtkCausticsShaderProgram> ReduceProgram;
  vtkNew<vtkCausticsShaderProgram> FinalizeProgram;
  vtkNew<vtkCausticsShaderProgram> ClearProgram;
  vtkNew<vtkCausticsShaderProgram> PeelProgram;

  // Layout of the draw commands: per object, per layer, its ranges.
  std::vector<std::uint32_t> StaticSignature;
  std::vector<int> ObjectCommandCount; // ranges per object
  std::vector<int> ObjectCommandFirst; // first command of (object, layer 0)
  int Objects = 0;
  int Layers = 0; // cap used for the allocation
  int Commands = 0;
  int Width = 0, Height = 0;
  std::vector<std::uint64_t> Key; // ContentKey() of the layers held; empty: none
  bool Reused = false;            // the last Render() kept the layers held

  caustics::StageSteps Steps; // "<prefix>depth complexity", "<prefix>depth peeling"

  void UpdateCommands(const ObjectLayout& layout, int layers, const caustics::SceneData& scene);
  void UploadCommands(const ObjectLayout& layout, int layers, const caustics::SceneData& scene);
  void BindGeometry(vtkCausticsSceneGeometry* geometry);
  bool CountFragments(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const float worldToClip[16], int roleMask);
  bool ReduceComplexity(vtkOpenGLRenderWindow* renWin);
  bool GateLayers(vtkOpenGLRenderWindow* renWin);
  bool PeelLayers(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const float worldToClip[16], bool programsReady);
  void AttachLayer(int layer, int k);
  bool ClearLayer(vtkOpenGLRenderWindow* renWin, int layer);
  bool PeelLayer(vtkOpenGLRenderWindow* renWin, vtkCausticsSceneGeometry* geometry,
    const float worldToClip[16], int object, int k, int previousUnit);
};

/** Rebuilds the draw, clear and object-map buffers when the layout changed. */
void vtkCausticsLayeredDepth::Internals::UpdateCommands(
  const ObjectLayout& layout, int layers, const caustics::SceneData& scene)
{
  std::vector<std::uint32_t> signature = LayoutSignature(layout, layers, scene.Materials.size());
  const bool layoutChanged = signature != this->StaticSignature || !this->DrawCommands.Handle();
  if (layoutChanged)
  {
    this->UploadCommands(layout, layers, scene);
    this->StaticSignature = signature;
  }
}

/**
 * Per object, per layer, one indirect draw of each of the object's ranges, with its
 * (object, layer) in CommandInfo for the finalize pass to gate it.
 */
void vtkCausticsLayeredDepth::Internals::UploadCommands(
  const ObjectLayout& layout, int layers, const caustics::SceneData& scene)
{
  const int objects = layout.Objects;
  this->ObjectCommandCount.assign(objects, 0);
  this->ObjectCommandFirst.assign(objects, 0);
  std::vector<std::uint32_t> draw, info;
  for (int o = 0; o < objects; ++o)
  {
    this->ObjectCommandCount[o] = static_cast<int>(layout.Ranges[o].size());
    this->ObjectCommandFirst[o] = static_cast<int>(info.size());
    for (int k = 0; k < layers; ++k)
    {
      for (const IndexRange& range : layout.Ranges[o])
      {
        draw.insert(draw.end(), { range.Count, 0u, range.FirstIndex, 0u, 0u });
        info.push_back(static_cast<std::uint32_t>(o) | (static_cast<std::uint32_t>(k) << 16));
      }
    }
  }
  const std::vector<std::uint32_t> clear = ClearCommandList(objects * layers);
  const std::vector<std::uint32_t> objectMap = MaterialObjects(scene, layout);
  this->Commands = static_cast<int>(info.size());
  this->DrawCommands.Allocate(draw.size() * 4);
  this->CommandInfo.Allocate(info.size() * 4);
  this->ClearCommands.Allocate(clear.size() * 4);
  this->ObjectMap.Allocate(objectMap.size() * 4);
  if (!draw.empty())
  {
    this->DrawCommands.Write(0, draw.size() * 4, draw.data());
    this->CommandInfo.Write(0, info.size() * 4, info.data());
  }
  this->ClearCommands.Write(0, clear.size() * 4, clear.data());
  this->ObjectMap.Write(0, objectMap.size() * 4, objectMap.data());
}

/** Makes the vertex arrays once and points them at the geometry's current buffers. */
void vtkCausticsLayeredDepth::Internals::BindGeometry(vtkCausticsSceneGeometry* geometry)
{
  if (!this->VertexArray)
  {
    glCreateVertexArrays(1, &this->VertexArray);
    glCreateVertexArrays(1, &this->EmptyVertexArray);
    // vtkCausticsSceneGeometry's interleaved vertex: position, normal, material (7 words).
    for (GLuint a = 0; a < 3; ++a)
    {
      glEnableVertexArrayAttrib(this->VertexArray, a);
      glVertexArrayAttribBinding(this->VertexArray, a, 0);
    }
    glVertexArrayAttribFormat(this->VertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribFormat(this->VertexArray, 1, 3, GL_FLOAT, GL_FALSE, 12);
    glVertexArrayAttribIFormat(this->VertexArray, 2, 1, GL_UNSIGNED_INT, 24);
  }
  // The geometry's buffers may have been recreated: bind them every frame (cheap).
  glVertexArrayVertexBuffer(this->VertexArray, 0, geometry->GetVertexBuffer(), 0, 28);
  glVertexArrayElementBuffer(this->VertexArray, geometry->GetIndexBuffer());
}

/** Step 1: every fragment of the drawn roles adds one to its pixel in its object's slice. */
bool vtkCausticsLayeredDepth::Internals::CountFragments(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const float worldToClip[16], int roleMask)
{
  vtkOpenGLState* state = renWin->GetState();
  const GLuint zero[4] = { 0, 0, 0, 0 };
  glClearTexImage(this->Complexity.Handle, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
  glClearNamedBufferData(this->Table.Handle(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
  const GLuint countFramebuffer = this->CountFramebuffer.Get();
  glNamedFramebufferParameteri(countFramebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, this->Width);
  glNamedFramebufferParameteri(countFramebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, this->Height);
  glNamedFramebufferParameteri(countFramebuffer, GL_FRAMEBUFFER_DEFAULT_LAYERS, 0);
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, countFramebuffer);
  // Through the state cache: VTK 9.2 checks the bound framebuffer's draw buffer.
  state->vtkglDrawBuffer(GL_NONE);
  state->vtkglDisable(GL_DEPTH_TEST);
  const bool ok = this->CountProgram->Bind(renWin);
  if (ok)
  {
    this->CountProgram->SetUniformMatrix4("worldToClip", worldToClip);
    glBindImageTexture(0, this->Complexity.Handle, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    this->ObjectMap.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_OBJECT_MAP_BINDING);
    geometry->Draw(roleMask);
    this->CountProgram->Unbind(renWin);
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  return ok;
}

/** Step 2: reduce-max of the counts, per object, into the layer table. */
bool vtkCausticsLayeredDepth::Internals::ReduceComplexity(vtkOpenGLRenderWindow* renWin)
{
  if (!this->ReduceProgram->Bind(renWin))
  {
    return false;
  }
  glBindImageTexture(0, this->Complexity.Handle, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
  this->Table.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_TABLE_BINDING);
  this->ReduceProgram->SetUniform2i("size", this->Width, this->Height);
  this->ReduceProgram->SetUniformi("objectCount", this->Objects);
  this->ReduceProgram->DispatchCovering2D(this->Width, this->Height, 16, 16);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  this->ReduceProgram->Unbind(renWin);
  return true;
}

/** Step 3: layers to peel, and the gates of the clear and peel commands. */
bool vtkCausticsLayeredDepth::Internals::GateLayers(vtkOpenGLRenderWindow* renWin)
{
  if (!this->FinalizeProgram->Bind(renWin))
  {
    return false;
  }
  this->Table.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_TABLE_BINDING);
  this->CommandInfo.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_COMMAND_INFO_BINDING);
  this->DrawCommands.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_DRAW_COMMAND_BINDING);
  this->ClearCommands.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_LDI_CLEAR_COMMAND_BINDING);
  this->FinalizeProgram->SetUniformi("objectCount", this->Objects);
  this->FinalizeProgram->SetUniformi("maxLayers", this->Layers);
  this->FinalizeProgram->SetUniformi("commandCount", this->Commands);
  this->FinalizeProgram->Dispatch(1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  this->FinalizeProgram->Unbind(renWin);
  return true;
}

/**
 * Step 4: peels every object's layers in turn, each gated on the GPU. Sets up the
 * peel framebuffer even when programsReady is false, and then peels nothing.
 */
bool vtkCausticsLayeredDepth::Internals::PeelLayers(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const float worldToClip[16], bool programsReady)
{
  vtkOpenGLState* state = renWin->GetState();
  const GLuint peelFramebuffer = this->PeelFramebuffer.Get();
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, peelFramebuffer);
  const GLenum drawBuffers[3] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
    GL_COLOR_ATTACHMENT2 };
  glNamedFramebufferDrawBuffers(peelFramebuffer, 3, drawBuffers);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_TRUE);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  caustics::ssp::TextureUnits units(renWin);
  const int previousUnit = units.Bind(0u);
  bool ok = programsReady;
  for (int o = 0; ok && o < this->Objects; ++o)
  {
    for (int k = 0; ok && k < this->Layers; ++k)
    {
      ok = this->PeelLayer(renWin, geometry, worldToClip, o, k, previousUnit);
    }
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  this->PeelProgram->Unbind(renWin);
  return ok;
}

/** Targets of layer k of an object (array layer `layer`), depth ping-ponged on k. */
void vtkCausticsLayeredDepth::Internals::AttachLayer(int layer, int k)
{
  const GLuint peelFramebuffer = this->PeelFramebuffer.Handle;
  glNamedFramebufferTextureLayer(
    peelFramebuffer, GL_COLOR_ATTACHMENT0, this->Position.Handle, 0, layer);
  glNamedFramebufferTextureLayer(
    peelFramebuffer, GL_COLOR_ATTACHMENT1, this->Normal.Handle, 0, layer);
  glNamedFramebufferTextureLayer(
    peelFramebuffer, GL_COLOR_ATTACHMENT2, this->Depth.Handle, 0, layer);
  glNamedFramebufferTexture(peelFramebuffer, GL_DEPTH_ATTACHMENT, this->PeelDepth[k % 2].Handle, 0);
}

/** Clears the layer and its depth buffer, only if it will be peeled (gated command). */
bool vtkCausticsLayeredDepth::Internals::ClearLayer(vtkOpenGLRenderWindow* renWin, int layer)
{
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, this->ClearCommands.Handle());
  renWin->GetState()->vtkglDepthFunc(GL_ALWAYS);
  if (!this->ClearProgram->Bind(renWin))
  {
    return false;
  }
  glBindVertexArray(this->EmptyVertexArray);
  glDrawArraysIndirect(GL_TRIANGLES,
    reinterpret_cast<const void*>(
      static_cast<std::uintptr_t>(layer * caustics::ssp::DrawArraysCommandWords * 4)));
  return true;
}

/** Layer k of an object: the nearest fragments strictly behind layer k - 1. */
bool vtkCausticsLayeredDepth::Internals::PeelLayer(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const float worldToClip[16], int object, int k,
  int previousUnit)
{
  this->AttachLayer(object * this->Layers + k, k);
  if (!this->ClearLayer(renWin, object * this->Layers + k))
  {
    return false;
  }
  renWin->GetState()->vtkglDepthFunc(GL_LESS);
  if (!this->PeelProgram->Bind(renWin))
  {
    return false;
  }
  glBindTextureUnit(previousUnit, this->PeelDepth[(k + 1) % 2].Handle);
  this->PeelProgram->SetUniformi("previousDepth", previousUnit);
  this->PeelProgram->SetUniformi("firstLayer", k == 0 ? 1 : 0);
  this->PeelProgram->SetUniformMatrix4("worldToClip", worldToClip);
  geometry->BindMaterials();
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, this->DrawCommands.Handle());
  glBindVertexArray(this->VertexArray);
  const int count = this->ObjectCommandCount[object];
  const int first = this->ObjectCommandFirst[object] + k * count;
  if (count > 0)
  {
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
      reinterpret_cast<const void*>(
        static_cast<std::uintptr_t>(first * caustics::ssp::DrawElementsCommandWords * 4)),
      count, 0);
  }
  glBindVertexArray(0);
  return true;
}

vtkCausticsLayeredDepth::vtkCausticsLayeredDepth()
  : Internal(new Internals)
{
  auto& in = *this->Internal;
  const std::string common = vtkCausticsScreenSpaceCommon;
  in.CountProgram->SetName("LDI depth complexity count");
  in.CountProgram->SetVertexSource(vtkCausticsGBufferVS);
  in.CountProgram->SetFragmentSource((common + vtkCausticsLayeredDepthCountFS).c_str());
  in.CountProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.ReduceProgram->SetName("LDI depth complexity reduction");
  in.ReduceProgram->SetComputeSource((common + vtkCausticsLayeredDepthReduceCS).c_str());
  in.ReduceProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.FinalizeProgram->SetName("LDI layer gating");
  in.FinalizeProgram->SetComputeSource((common + vtkCausticsLayeredDepthFinalizeCS).c_str());
  in.FinalizeProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.ClearProgram->SetName("LDI layer clear");
  in.ClearProgram->SetVertexSource(vtkCausticsFullScreenVS);
  in.ClearProgram->SetFragmentSource(vtkCausticsLayeredDepthClearFS);
  in.ClearProgram->SetDefine("CAUSTICS_NO_MATERIALS", 1);
  in.PeelProgram->SetName("LDI depth peeling");
  in.PeelProgram->SetVertexSource(vtkCausticsGBufferVS);
  in.PeelProgram->SetFragmentSource(vtkCausticsLayeredDepthPeelFS);
}

vtkCausticsLayeredDepth::~vtkCausticsLayeredDepth()
{
  if (this->Internal->VertexArray || this->Internal->Position.Handle)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL objects leaked");
  }
}

void vtkCausticsLayeredDepth::SetTimings(vtkCausticsTimings* timings, const char* stagePrefix)
{
  this->Internal->Steps.Timings = timings;
  this->Internal->Steps.Prefix = stagePrefix ? stagePrefix : "";
}

bool vtkCausticsLayeredDepth::Render(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene, const float worldToClip[16],
  int width, int height)
{
  if (!this->CheckInputs(geometry, scene, width, height))
  {
    return false;
  }
  const std::vector<IndexRange> ranges = MeshRanges(scene);
  if (!this->CheckUploaded(geometry, CountIndices(ranges)))
  {
    return false;
  }
  auto& in = *this->Internal;
  // Nothing the layers depend on changed: they are still right (no GL work at all).
  std::vector<std::uint64_t> key = ContentKey(scene, geometry, worldToClip, width, height,
    { static_cast<std::uint64_t>(this->MaximumNumberOfLayers),
      static_cast<std::uint64_t>(this->RoleMask), static_cast<std::uint64_t>(this->PerObject),
      static_cast<std::uint64_t>(this->MaximumNumberOfObjects) });
  in.Reused = this->ReuseUnchanged && key == in.Key;
  if (in.Reused)
  {
    return true;
  }
  in.Key.clear(); // until this Render() succeeds
  const ObjectLayout layout =
    AssignObjects(scene, ranges, this->RoleMask, this->PerObject, this->MaximumNumberOfObjects);
  in.UpdateCommands(layout, this->MaximumNumberOfLayers, scene);
  if (!this->AllocateTargets(layout.Objects, this->MaximumNumberOfLayers, width, height))
  {
    return false;
  }
  in.BindGeometry(geometry);

  vtkOpenGLState* state = renWin->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglViewport viewport(state);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglViewport(0, 0, width, height);

  in.Steps.Start("depth complexity");
  bool ok = in.CountFragments(renWin, geometry, worldToClip, this->RoleMask);
  ok = ok && in.ReduceComplexity(renWin);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  ok = ok && in.GateLayers(renWin);
  in.Steps.Stop("depth complexity");

  in.Steps.Start("depth peeling");
  ok = in.PeelLayers(renWin, geometry, worldToClip, ok);
  state->PopFramebufferBindings();
  in.Steps.Stop("depth peeling");
  if (!ok)
  {
    vtkErrorMacro(<< "layered depth image: a program failed to build");
  }
  else
  {
    in.Key = std::move(key);
  }
  return ok;
}

bool vtkCausticsLayeredDepth::CheckInputs(
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene, int width, int height)
{
  const int maxSize = caustics::ssp::MaxTextureSize();
  if (width < 1 || height < 1 || width > maxSize || height > maxSize)
  {
    vtkErrorMacro(<< "layered depth image of " << width << " x " << height
                  << " pixels: each side must be in [1, " << maxSize << "]");
    return false;
  }
  if (!geometry || scene.Materials.size() != scene.Meshes.size())
  {
    vtkErrorMacro(<< "layered depth image needs the scene geometry and one material per mesh");
    return false;
  }
  return true;
}

bool vtkCausticsLayeredDepth::CheckUploaded(
  vtkCausticsSceneGeometry* geometry, vtkTypeUInt64 sceneIndices)
{
  const vtkIdType triangles = geometry->GetNumberOfTriangles(vtkCausticsSceneGeometry::AllRoles);
  if (sceneIndices != static_cast<std::uint64_t>(triangles) * 3)
  {
    vtkErrorMacro(<< "the scene geometry was not uploaded from this scene (" << sceneIndices / 3
                  << " triangles in the scene, " << triangles << " on the GPU)");
    return false;
  }
  return true;
}

bool vtkCausticsLayeredDepth::AllocateTargets(int objects, int layers, int width, int height)
{
  auto& in = *this->Internal;
  in.Objects = objects;
  in.Layers = layers;
  in.Width = width;
  in.Height = height;
  in.Table.Allocate(16 * (1 + static_cast<std::size_t>(objects)));

  // Reallocated only when the size, cap or object count changes.
  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (objects * layers > maxLayers)
  {
    vtkErrorMacro(<< objects << " objects x " << layers << " layers exceed the " << maxLayers
                  << " layers of an array texture on this GPU");
    return false;
  }
  in.Complexity.Ensure(width, height, objects, GL_R32UI);
  in.Position.Ensure(width, height, objects * layers, GL_RGBA32F);
  in.Normal.Ensure(width, height, objects * layers, GL_RGBA16F);
  in.Depth.Ensure(width, height, objects * layers, GL_R32F);
  in.PeelDepth[0].Ensure(width, height, 0, GL_DEPTH_COMPONENT32F);
  in.PeelDepth[1].Ensure(width, height, 0, GL_DEPTH_COMPONENT32F);
  return true;
}

unsigned int vtkCausticsLayeredDepth::GetPositionTexture() const
{
  return this->Internal->Position.Handle;
}
unsigned int vtkCausticsLayeredDepth::GetNormalTexture() const
{
  return this->Internal->Normal.Handle;
}
unsigned int vtkCausticsLayeredDepth::GetDepthTexture() const
{
  return this->Internal->Depth.Handle;
}
unsigned int vtkCausticsLayeredDepth::GetComplexityTexture() const
{
  return this->Internal->Complexity.Handle;
}
unsigned int vtkCausticsLayeredDepth::GetTableBuffer() const
{
  return this->Internal->Table.Handle();
}
int vtkCausticsLayeredDepth::GetNumberOfObjects() const
{
  return this->Internal->Objects;
}
int vtkCausticsLayeredDepth::GetNumberOfAllocatedLayers() const
{
  return this->Internal->Objects * this->Internal->Layers;
}
bool vtkCausticsLayeredDepth::GetLastRenderReused() const
{
  return this->Internal->Reused;
}

int vtkCausticsLayeredDepth::GetWidth() const
{
  return this->Internal->Width;
}
int vtkCausticsLayeredDepth::GetHeight() const
{
  return this->Internal->Height;
}

int vtkCausticsLayeredDepth::ReadDepthComplexity()
{
  if (!this->Internal->Table.Handle())
  {
    return 0;
  }
  std::uint32_t header[4] = { 0, 0, 0, 0 };
  glGetNamedBufferSubData(this->Internal->Table.Handle(), 0, sizeof(header), header);
  return static_cast<int>(header[2]);
}

int vtkCausticsLayeredDepth::ReadNumberOfPeeledLayers(int object)
{
  if (!this->Internal->Table.Handle() || object < 0 || object >= this->Internal->Objects)
  {
    return 0;
  }
  std::uint32_t entry[4] = { 0, 0, 0, 0 };
  glGetNamedBufferSubData(this->Internal->Table.Handle(), 16 * (1 + object), sizeof(entry), entry);
  return static_cast<int>(entry[1]);
}

bool vtkCausticsLayeredDepth::ReadLayer(const char* texture, int layer, vtkImageData* output)
{
  auto& in = *this->Internal;
  const std::string name = texture ? texture : "";
  caustics::ssp::Texture* source = nullptr;
  int components = 4;
  GLenum format = GL_RGBA, type = GL_FLOAT;
  if (name == "Position")
  {
    source = &in.Position;
  }
  else if (name == "Normal")
  {
    source = &in.Normal;
  }
  else if (name == "Depth")
  {
    source = &in.Depth;
    components = 1;
    format = GL_RED;
  }
  else if (name == "Complexity")
  {
    source = &in.Complexity;
    components = 1;
    format = GL_RED_INTEGER;
    type = GL_UNSIGNED_INT;
  }
  if (!output || !source || !source->Handle || layer < 0 || layer >= source->Layers)
  {
    vtkErrorMacro(<< "ReadLayer: no layer " << layer << " of '" << name
                  << "' (names: Position, Normal, Depth, Complexity)");
    return false;
  }
  const int w = source->Width, h = source->Height;
  std::vector<float> pixels(static_cast<std::size_t>(w) * h * components);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(source->Handle, 0, 0, 0, layer, w, h, 1, format, type,
    static_cast<GLsizei>(pixels.size() * 4), pixels.data());
  if (type == GL_UNSIGNED_INT)
  {
    for (float& value : pixels)
    {
      std::uint32_t raw;
      std::memcpy(&raw, &value, 4);
      value = static_cast<float>(raw);
    }
  }
  output->Initialize();
  output->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> array;
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  std::copy(pixels.begin(), pixels.end(), array->GetPointer(0));
  output->GetPointData()->AddArray(array);
  return true;
}

void vtkCausticsLayeredDepth::ReleaseGraphicsResources(vtkWindow* win)
{
  auto& in = *this->Internal;
  for (caustics::ssp::Texture* texture :
    { &in.Complexity, &in.Position, &in.Normal, &in.Depth, &in.PeelDepth[0], &in.PeelDepth[1] })
  {
    texture->Release();
  }
  for (caustics::gl::StorageBuffer* buffer :
    { &in.Table, &in.ObjectMap, &in.CommandInfo, &in.DrawCommands, &in.ClearCommands })
  {
    buffer->Release();
  }
  in.CountFramebuffer.Release();
  in.PeelFramebuffer.Release();
  if (in.VertexArray)
  {
    glDeleteVertexArrays(1, &in.VertexArray);
    glDeleteVertexArrays(1, &in.EmptyVertexArray);
  }
  in.VertexArray = in.EmptyVertexArray = 0;
  for (vtkCausticsShaderProgram* program :
    { in.CountProgram.GetPointer(), in.ReduceProgram.GetPointer(), in.FinalizeProgram.GetPointer(),
      in.ClearProgram.GetPointer(), in.PeelProgram.GetPointer() })
  {
    program->ReleaseGraphicsResources(win);
  }
  in.StaticSignature.clear();
  in.Key.clear();
  in.Reused = false;
  in.Objects = in.Layers = in.Commands = 0;
}

void vtkCausticsLayeredDepth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumNumberOfLayers: " << this->MaximumNumberOfLayers << "\n";
  os << indent << "RoleMask: " << this->RoleMask << "\n";
  os << indent << "PerObject: " << this->PerObject << "\n";
  os << indent << "MaximumNumberOfObjects: " << this->MaximumNumberOfObjects << "\n";
  os << indent << "ReuseUnchanged: " << this->ReuseUnchanged << "\n";
  os << indent << "LastRenderReused: " << this->Internal->Reused << "\n";
  os << indent << "Objects: " << this->Internal->Objects << "\n";
  os << indent << "Size: " << this->Internal->Width << " x " << this->Internal->Height << "\n";
  os << indent << "AllocatedLayers: " << this->GetNumberOfAllocatedLayers() << "\n";
}
