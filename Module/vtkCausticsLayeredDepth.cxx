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
}

struct vtkCausticsLayeredDepth::Internals
{
  caustics::ssp::Texture Complexity; // R32UI array: objects
  caustics::ssp::Texture Position;   // RGBA32F array: objects x layers
  caustics::ssp::Texture Normal;     // RGBA16F array
  caustics::ssp::Texture Depth;      // R32F array
  caustics::ssp::Texture PeelDepth[2];
  caustics::ssp::Buffer Table;
  caustics::ssp::Buffer ObjectMap;
  caustics::ssp::Buffer CommandInfo;
  caustics::ssp::Buffer DrawCommands;
  caustics::ssp::Buffer ClearCommands;
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

  vtkCausticsTimings* Timings = nullptr;
  std::string StagePrefix;

  void Start(const char* stage)
  {
    if (this->Timings)
    {
      this->Timings->StartStage((this->StagePrefix + stage).c_str());
    }
  }
  void Stop(const char* stage)
  {
    if (this->Timings)
    {
      this->Timings->StopStage((this->StagePrefix + stage).c_str());
    }
  }
};

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
  this->Internal->Timings = timings;
  this->Internal->StagePrefix = stagePrefix ? stagePrefix : "";
}

bool vtkCausticsLayeredDepth::Render(vtkOpenGLRenderWindow* renWin,
  vtkCausticsSceneGeometry* geometry, const caustics::SceneData& scene, const float worldToClip[16],
  int width, int height)
{
  auto& in = *this->Internal;
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

  // 0. Objects and their draw commands (rebuilt only when the layout changes).
  const std::vector<IndexRange> ranges = MeshRanges(scene);
  std::uint64_t total = 0;
  for (const IndexRange& range : ranges)
  {
    total += range.Count;
  }
  if (total !=
    static_cast<std::uint64_t>(geometry->GetNumberOfTriangles(vtkCausticsSceneGeometry::AllRoles)) *
      3)
  {
    vtkErrorMacro(<< "the scene geometry was not uploaded from this scene (" << total / 3
                  << " triangles in the scene, "
                  << geometry->GetNumberOfTriangles(vtkCausticsSceneGeometry::AllRoles)
                  << " on the GPU)");
    return false;
  }
  std::vector<int> meshObject(scene.Meshes.size(), -1);
  int objects = 0;
  for (std::size_t m = 0; m < scene.Meshes.size(); ++m)
  {
    const int role = static_cast<int>(scene.Materials[scene.Meshes[m].material].role);
    if (!(this->RoleMask & vtkCausticsSceneGeometry::RoleBit(role)) || ranges[m].Count == 0)
    {
      continue;
    }
    if (this->PerObject)
    {
      meshObject[m] = std::min(objects, this->MaximumNumberOfObjects - 1);
      objects = std::min(objects + 1, this->MaximumNumberOfObjects);
    }
    else
    {
      meshObject[m] = 0;
      objects = 1;
    }
  }
  objects = std::max(objects, 1);
  const int layers = this->MaximumNumberOfLayers;
  // Each object's index ranges, merged where meshes are adjacent in the buffer.
  std::vector<std::vector<IndexRange>> objectRanges(objects);
  {
    std::vector<int> byFirst(scene.Meshes.size());
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
  }
  std::vector<std::uint32_t> signature = { static_cast<std::uint32_t>(objects),
    static_cast<std::uint32_t>(layers), static_cast<std::uint32_t>(scene.Materials.size()) };
  for (std::size_t m = 0; m < meshObject.size(); ++m)
  {
    signature.push_back(static_cast<std::uint32_t>(meshObject[m] + 1));
  }
  for (const auto& list : objectRanges)
  {
    signature.push_back(0xffffffffu);
    for (const IndexRange& range : list)
    {
      signature.push_back(range.FirstIndex);
      signature.push_back(range.Count);
    }
  }
  const bool layoutChanged = signature != in.StaticSignature || !in.DrawCommands.Handle;
  if (layoutChanged)
  {
    in.ObjectCommandCount.assign(objects, 0);
    in.ObjectCommandFirst.assign(objects, 0);
    std::vector<std::uint32_t> draw, info;
    for (int o = 0; o < objects; ++o)
    {
      in.ObjectCommandCount[o] = static_cast<int>(objectRanges[o].size());
      in.ObjectCommandFirst[o] = static_cast<int>(info.size());
      for (int k = 0; k < layers; ++k)
      {
        for (const IndexRange& range : objectRanges[o])
        {
          draw.insert(draw.end(), { range.Count, 0u, range.FirstIndex, 0u, 0u });
          info.push_back(static_cast<std::uint32_t>(o) | (static_cast<std::uint32_t>(k) << 16));
        }
      }
    }
    std::vector<std::uint32_t> clear;
    for (int i = 0; i < objects * layers; ++i)
    {
      clear.insert(clear.end(), { 3u, 0u, 0u, 0u });
    }
    std::vector<std::uint32_t> objectMap(std::max<std::size_t>(scene.Materials.size(), 1), 0u);
    for (std::size_t m = 0; m < meshObject.size(); ++m)
    {
      // Materials are one per mesh, same index (vtkCausticsSceneData.h).
      objectMap[scene.Meshes[m].material] = static_cast<std::uint32_t>(std::max(meshObject[m], 0));
    }
    in.Commands = static_cast<int>(info.size());
    in.DrawCommands.Ensure(draw.size() * 4);
    in.CommandInfo.Ensure(info.size() * 4);
    in.ClearCommands.Ensure(clear.size() * 4);
    in.ObjectMap.Ensure(objectMap.size() * 4);
    if (!draw.empty())
    {
      glNamedBufferSubData(in.DrawCommands.Handle, 0, draw.size() * 4, draw.data());
      glNamedBufferSubData(in.CommandInfo.Handle, 0, info.size() * 4, info.data());
    }
    glNamedBufferSubData(in.ClearCommands.Handle, 0, clear.size() * 4, clear.data());
    glNamedBufferSubData(in.ObjectMap.Handle, 0, objectMap.size() * 4, objectMap.data());
    in.StaticSignature = signature;
  }
  in.Objects = objects;
  in.Layers = layers;
  in.Width = width;
  in.Height = height;
  in.Table.Ensure(16 * (1 + static_cast<std::size_t>(objects)));

  // Targets (reallocated only when the size, cap or object count changes).
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
  if (!in.VertexArray)
  {
    glCreateVertexArrays(1, &in.VertexArray);
    glCreateVertexArrays(1, &in.EmptyVertexArray);
    // vtkCausticsSceneGeometry's interleaved vertex: position, normal, material (7 words).
    for (GLuint a = 0; a < 3; ++a)
    {
      glEnableVertexArrayAttrib(in.VertexArray, a);
      glVertexArrayAttribBinding(in.VertexArray, a, 0);
    }
    glVertexArrayAttribFormat(in.VertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribFormat(in.VertexArray, 1, 3, GL_FLOAT, GL_FALSE, 12);
    glVertexArrayAttribIFormat(in.VertexArray, 2, 1, GL_UNSIGNED_INT, 24);
  }
  // The geometry's buffers may have been recreated: bind them every frame (cheap).
  glVertexArrayVertexBuffer(in.VertexArray, 0, geometry->GetVertexBuffer(), 0, 28);
  glVertexArrayElementBuffer(in.VertexArray, geometry->GetIndexBuffer());

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

  // 1. Count fragments per pixel and object.
  in.Start("depth complexity");
  const GLuint zero[4] = { 0, 0, 0, 0 };
  glClearTexImage(in.Complexity.Handle, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
  glClearNamedBufferData(in.Table.Handle, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
  const GLuint countFramebuffer = in.CountFramebuffer.Get();
  glNamedFramebufferParameteri(countFramebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(countFramebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
  glNamedFramebufferParameteri(countFramebuffer, GL_FRAMEBUFFER_DEFAULT_LAYERS, 0);
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, countFramebuffer);
  glNamedFramebufferDrawBuffer(countFramebuffer, GL_NONE);
  state->vtkglDisable(GL_DEPTH_TEST);
  bool ok = in.CountProgram->Bind(renWin);
  if (ok)
  {
    in.CountProgram->SetUniformMatrix4("worldToClip", worldToClip);
    glBindImageTexture(0, in.Complexity.Handle, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    in.ObjectMap.BindStorage(CAUSTICS_LDI_OBJECT_MAP_BINDING);
    geometry->Draw(this->RoleMask);
    in.CountProgram->Unbind(renWin);
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  // 2. Reduce-max of the counts, per object.
  ok = ok && in.ReduceProgram->Bind(renWin);
  if (ok)
  {
    glBindImageTexture(0, in.Complexity.Handle, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    in.Table.BindStorage(CAUSTICS_LDI_TABLE_BINDING);
    in.ReduceProgram->SetUniform2i("size", width, height);
    in.ReduceProgram->SetUniformi("objectCount", objects);
    in.ReduceProgram->DispatchCovering2D(width, height, 16, 16);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    in.ReduceProgram->Unbind(renWin);
  }
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);

  // 3. Layers to peel, and the gates of the peel commands.
  ok = ok && in.FinalizeProgram->Bind(renWin);
  if (ok)
  {
    in.Table.BindStorage(CAUSTICS_LDI_TABLE_BINDING);
    in.CommandInfo.BindStorage(CAUSTICS_LDI_COMMAND_INFO_BINDING);
    in.DrawCommands.BindStorage(CAUSTICS_LDI_DRAW_COMMAND_BINDING);
    in.ClearCommands.BindStorage(CAUSTICS_LDI_CLEAR_COMMAND_BINDING);
    in.FinalizeProgram->SetUniformi("objectCount", objects);
    in.FinalizeProgram->SetUniformi("maxLayers", layers);
    in.FinalizeProgram->SetUniformi("commandCount", in.Commands);
    in.FinalizeProgram->Dispatch(1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    in.FinalizeProgram->Unbind(renWin);
  }
  in.Stop("depth complexity");

  // 4. Peel, layer after layer, each gated on the GPU.
  in.Start("depth peeling");
  const GLuint peelFramebuffer = in.PeelFramebuffer.Get();
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, peelFramebuffer);
  const GLenum drawBuffers[3] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
    GL_COLOR_ATTACHMENT2 };
  glNamedFramebufferDrawBuffers(peelFramebuffer, 3, drawBuffers);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_TRUE);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  caustics::ssp::TextureUnits units(renWin);
  const int previousUnit = units.Bind(0u);
  for (int o = 0; ok && o < objects; ++o)
  {
    for (int k = 0; ok && k < layers; ++k)
    {
      const int layer = o * layers + k;
      glNamedFramebufferTextureLayer(
        peelFramebuffer, GL_COLOR_ATTACHMENT0, in.Position.Handle, 0, layer);
      glNamedFramebufferTextureLayer(
        peelFramebuffer, GL_COLOR_ATTACHMENT1, in.Normal.Handle, 0, layer);
      glNamedFramebufferTextureLayer(
        peelFramebuffer, GL_COLOR_ATTACHMENT2, in.Depth.Handle, 0, layer);
      glNamedFramebufferTexture(
        peelFramebuffer, GL_DEPTH_ATTACHMENT, in.PeelDepth[k % 2].Handle, 0);

      // Clear the layer and its depth buffer, only if it will be peeled.
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, in.ClearCommands.Handle);
      state->vtkglDepthFunc(GL_ALWAYS);
      ok = in.ClearProgram->Bind(renWin);
      if (!ok)
      {
        break;
      }
      glBindVertexArray(in.EmptyVertexArray);
      glDrawArraysIndirect(GL_TRIANGLES,
        reinterpret_cast<const void*>(
          static_cast<std::uintptr_t>(layer * caustics::ssp::DrawArraysCommandWords * 4)));

      // Peel the layer.
      state->vtkglDepthFunc(GL_LESS);
      ok = in.PeelProgram->Bind(renWin);
      if (!ok)
      {
        break;
      }
      glBindTextureUnit(previousUnit, in.PeelDepth[(k + 1) % 2].Handle);
      in.PeelProgram->SetUniformi("previousDepth", previousUnit);
      in.PeelProgram->SetUniformi("firstLayer", k == 0 ? 1 : 0);
      in.PeelProgram->SetUniformMatrix4("worldToClip", worldToClip);
      geometry->BindMaterials();
      glBindBuffer(GL_DRAW_INDIRECT_BUFFER, in.DrawCommands.Handle);
      glBindVertexArray(in.VertexArray);
      const int first = in.ObjectCommandFirst[o] + k * in.ObjectCommandCount[o];
      if (in.ObjectCommandCount[o] > 0)
      {
        glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
          reinterpret_cast<const void*>(
            static_cast<std::uintptr_t>(first * caustics::ssp::DrawElementsCommandWords * 4)),
          in.ObjectCommandCount[o], 0);
      }
      glBindVertexArray(0);
    }
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  in.PeelProgram->Unbind(renWin);
  state->PopFramebufferBindings();
  in.Stop("depth peeling");
  if (!ok)
  {
    vtkErrorMacro(<< "layered depth image: a program failed to build");
  }
  return ok;
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
  return this->Internal->Table.Handle;
}
int vtkCausticsLayeredDepth::GetNumberOfObjects() const
{
  return this->Internal->Objects;
}
int vtkCausticsLayeredDepth::GetNumberOfAllocatedLayers() const
{
  return this->Internal->Objects * this->Internal->Layers;
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
  if (!this->Internal->Table.Handle)
  {
    return 0;
  }
  std::uint32_t header[4] = { 0, 0, 0, 0 };
  glGetNamedBufferSubData(this->Internal->Table.Handle, 0, sizeof(header), header);
  return static_cast<int>(header[2]);
}

int vtkCausticsLayeredDepth::ReadNumberOfPeeledLayers(int object)
{
  if (!this->Internal->Table.Handle || object < 0 || object >= this->Internal->Objects)
  {
    return 0;
  }
  std::uint32_t entry[4] = { 0, 0, 0, 0 };
  glGetNamedBufferSubData(this->Internal->Table.Handle, 16 * (1 + object), sizeof(entry), entry);
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
  for (caustics::ssp::Buffer* buffer :
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
  in.Objects = in.Layers = in.Commands = 0;
}

void vtkCausticsLayeredDepth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumNumberOfLayers: " << this->MaximumNumberOfLayers << "\n";
  os << indent << "RoleMask: " << this->RoleMask << "\n";
  os << indent << "PerObject: " << this->PerObject << "\n";
  os << indent << "MaximumNumberOfObjects: " << this->MaximumNumberOfObjects << "\n";
  os << indent << "Objects: " << this->Internal->Objects << "\n";
  os << indent << "Size: " << this->Internal->Width << " x " << this->Internal->Height << "\n";
  os << indent << "AllocatedLayers: " << this->GetNumberOfAllocatedLayers() << "\n";
}
