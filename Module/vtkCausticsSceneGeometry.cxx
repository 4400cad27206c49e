#include "vtkCausticsSceneGeometry.h"

#include "vtkCausticsBindings.h" // CAUSTICS_MATERIAL_BINDING
#include "vtkCausticsGLUtilities.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <numeric>

vtkStandardNewMacro(vtkCausticsSceneGeometry);

namespace
{
// Interleaved vertex: position (3 floats), normal (3 floats), material index (uint).
constexpr int WordsPerVertex = 7;

/** Unique in the process: a geometry's content version never repeats another's. */
vtkTypeUInt64 NextContentVersion()
{
  static std::atomic<vtkTypeUInt64> next{ 1 };
  return next++;
}

struct GPUMaterial
{
  float albedoRole[4];
  float params[4];
  float metalN[4];
  float metalK[4];
  float attenuation[4];
};

struct MeshSlot
{
  const void* actor = nullptr;
  unsigned long version = 0;
  std::size_t firstVertex = 0, vertexCount = 0;
  std::size_t firstIndex = 0, indexCount = 0;
  int role = 0;
  int material = 0;
};

/** A contiguous range of indices drawn with one call. */
struct Range
{
  int role;
  std::size_t firstIndex, indexCount;
};

/** Mesh indices stably sorted by role: the layout of the buffers (receivers first). */
std::vector<int> RoleOrder(const caustics::SceneData& scene)
{
  std::vector<int> order(scene.Meshes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
    [&](int a, int b)
    {
      return scene.Materials[scene.Meshes[a].material].role <
        scene.Materials[scene.Meshes[b].material].role;
    });
  return order;
}

/** Each mesh, in `order`, a block of vertices and indices; sums them up. */
std::vector<MeshSlot> LayOutSlots(const caustics::SceneData& scene, const std::vector<int>& order,
  std::size_t& vertices, std::size_t& indices)
{
  std::vector<MeshSlot> slots;
  vertices = indices = 0;
  for (int m : order)
  {
    const auto& mesh = scene.Meshes[m];
    MeshSlot slot;
    slot.actor = mesh.actor;
    slot.version = mesh.version;
    slot.firstVertex = vertices;
    slot.vertexCount = mesh.positions.size() / 3;
    slot.firstIndex = indices;
    slot.indexCount = mesh.indices.size();
    slot.role = static_cast<int>(scene.Materials[mesh.material].role);
    slot.material = mesh.material;
    vertices += slot.vertexCount;
    indices += slot.indexCount;
    slots.push_back(slot);
  }
  return slots;
}

/** Same actors, sizes and materials in the same places: only changed meshes are resent. */
bool SameLayout(const std::vector<MeshSlot>& slots, const std::vector<MeshSlot>& previous)
{
  bool sameLayout = slots.size() == previous.size();
  for (std::size_t i = 0; sameLayout && i < slots.size(); ++i)
  {
    sameLayout = slots[i].actor == previous[i].actor &&
      slots[i].vertexCount == previous[i].vertexCount &&
      slots[i].indexCount == previous[i].indexCount && slots[i].material == previous[i].material;
  }
  return sameLayout;
}

/**
 * Sends one mesh to its slot: interleaved vertices, and indices stored absolute
 * so that compute stages need no base vertex. Returns the bytes sent.
 */
std::size_t UploadMesh(caustics::gl::StorageBuffer& vertexBuffer,
  caustics::gl::StorageBuffer& indexBuffer, const caustics::Mesh& mesh, const MeshSlot& slot,
  std::vector<float>& staging)
{
  staging.resize(slot.vertexCount * WordsPerVertex);
  for (std::size_t v = 0; v < slot.vertexCount; ++v)
  {
    float* out = &staging[v * WordsPerVertex];
    std::memcpy(out, &mesh.positions[3 * v], 12);
    std::memcpy(out + 3, &mesh.normals[3 * v], 12);
    const std::uint32_t material = static_cast<std::uint32_t>(slot.material);
    std::memcpy(out + 6, &material, 4);
  }
  const std::size_t vertexBytes = staging.size() * 4;
  vertexBuffer.Write(slot.firstVertex * WordsPerVertex * 4, vertexBytes, staging.data());
  std::vector<std::uint32_t> shifted(mesh.indices.size());
  for (std::size_t k = 0; k < shifted.size(); ++k)
  {
    shifted[k] = mesh.indices[k] + static_cast<std::uint32_t>(slot.firstVertex);
  }
  indexBuffer.Write(slot.firstIndex * 4, shifted.size() * 4, shifted.data());
  return vertexBytes + shifted.size() * 4;
}

/** Contiguous draw ranges per role. */
std::vector<Range> DrawRanges(const std::vector<MeshSlot>& slots)
{
  std::vector<Range> ranges;
  for (const MeshSlot& slot : slots)
  {
    if (!ranges.empty() && ranges.back().role == slot.role)
    {
      ranges.back().indexCount += slot.indexCount;
    }
    else
    {
      ranges.push_back({ slot.role, slot.firstIndex, slot.indexCount });
    }
  }
  return ranges;
}

/** The scene's materials in the shaders' layout (glsl/vtkCausticsCommon.glsl). */
std::vector<GPUMaterial> PackMaterials(const caustics::SceneData& scene)
{
  std::vector<GPUMaterial> materials(scene.Materials.size());
  for (std::size_t m = 0; m < scene.Materials.size(); ++m)
  {
    const auto& src = scene.Materials[m];
    GPUMaterial& dst = materials[m];
    for (int c = 0; c < 3; ++c)
    {
      dst.albedoRole[c] = static_cast<float>(src.albedo[c]);
      dst.metalN[c] = static_cast<float>(src.metalN[c]);
      dst.metalK[c] = static_cast<float>(src.metalK[c]);
      dst.attenuation[c] = static_cast<float>(src.attenuation[c]);
    }
    dst.albedoRole[3] = static_cast<float>(static_cast<int>(src.role));
    dst.params[0] = static_cast<float>(src.ior);
    dst.params[1] = static_cast<float>(src.roughness);
    dst.params[2] = dst.params[3] = 0.0f;
    dst.metalN[3] = dst.metalK[3] = dst.attenuation[3] = 0.0f;
  }
  return materials;
}
}

struct vtkCausticsSceneGeometry::Internals
{
  GLuint VertexArray = 0;
  caustics::gl::StorageBuffer VertexBuffer;
  caustics::gl::StorageBuffer IndexBuffer;
  caustics::gl::StorageBuffer MaterialBuffer;
  std::vector<MeshSlot> Slots;
  std::vector<Range> Ranges;
  std::vector<GPUMaterial> Materials;
  vtkIdType LastUploadBytes = 0;
  vtkTypeUInt64 ContentVersion = NextContentVersion();
  std::vector<float> Staging;
};

vtkCausticsSceneGeometry::vtkCausticsSceneGeometry()
  : Internal(new Internals)
{
}

vtkCausticsSceneGeometry::~vtkCausticsSceneGeometry()
{
  if (this->Internal->VertexBuffer.Handle() || this->Internal->VertexArray)
  {
    vtkErrorMacro(<< "destroyed before ReleaseGraphicsResources(): GL buffers leaked");
  }
}

void vtkCausticsSceneGeometry::ReleaseGraphicsResources(vtkWindow*)
{
  auto& in = *this->Internal;
  if (in.VertexArray)
  {
    glDeleteVertexArrays(1, &in.VertexArray);
  }
  in.VertexBuffer.Release();
  in.IndexBuffer.Release();
  in.MaterialBuffer.Release();
  in.VertexArray = 0;
  in.Slots.clear();
  in.Ranges.clear();
  in.Materials.clear(); // the material buffer is gone: the next Upload() must resend them
  in.ContentVersion = NextContentVersion();
}

bool vtkCausticsSceneGeometry::Upload(
  const caustics::SceneData& scene, vtkOpenGLRenderWindow* vtkNotUsed(renWin))
{
  auto& in = *this->Internal;
  in.LastUploadBytes = 0;
  // Judge only this upload's calls: an error someone else left pending is not ours.
  for (int pending = 0; pending < 16 && glGetError() != GL_NO_ERROR; ++pending)
  {
  }
  this->CreateBuffers();

  // Layout: meshes sorted by role (stable), each a block of vertices and indices.
  const std::vector<int> order = RoleOrder(scene);
  std::size_t vertices = 0, indices = 0;
  std::vector<MeshSlot> slots = LayOutSlots(scene, order, vertices, indices);
  const bool sameLayout = SameLayout(slots, in.Slots);
  if (!sameLayout)
  {
    this->ReserveMeshBuffers(vertices, indices);
  }
  for (std::size_t i = 0; i < slots.size(); ++i)
  {
    if (sameLayout && slots[i].version == in.Slots[i].version)
    {
      continue;
    }
    in.LastUploadBytes += static_cast<vtkIdType>(
      UploadMesh(in.VertexBuffer, in.IndexBuffer, scene.Meshes[order[i]], slots[i], in.Staging));
  }
  in.Slots = std::move(slots);
  in.Ranges = DrawRanges(in.Slots);
  this->UploadMaterials(scene);
  if (!sameLayout || in.LastUploadBytes > 0)
  {
    in.ContentVersion = NextContentVersion();
  }
  return glGetError() == GL_NO_ERROR;
}

void vtkCausticsSceneGeometry::CreateBuffers()
{
  auto& in = *this->Internal;
  if (!in.VertexArray)
  {
    glCreateVertexArrays(1, &in.VertexArray);
    // The buffers keep their names when they grow: the vertex array stays valid.
    in.VertexBuffer.Allocate(0);
    in.IndexBuffer.Allocate(0);
    in.MaterialBuffer.Allocate(0);
    glVertexArrayVertexBuffer(in.VertexArray, 0, in.VertexBuffer.Handle(), 0, WordsPerVertex * 4);
    glVertexArrayElementBuffer(in.VertexArray, in.IndexBuffer.Handle());
    glEnableVertexArrayAttrib(in.VertexArray, 0);
    glEnableVertexArrayAttrib(in.VertexArray, 1);
    glEnableVertexArrayAttrib(in.VertexArray, 2);
    glVertexArrayAttribFormat(in.VertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribFormat(in.VertexArray, 1, 3, GL_FLOAT, GL_FALSE, 12);
    glVertexArrayAttribIFormat(in.VertexArray, 2, 1, GL_UNSIGNED_INT, 24);
    glVertexArrayAttribBinding(in.VertexArray, 0, 0);
    glVertexArrayAttribBinding(in.VertexArray, 1, 0);
    glVertexArrayAttribBinding(in.VertexArray, 2, 0);
  }
}

void vtkCausticsSceneGeometry::ReserveMeshBuffers(std::size_t vertices, std::size_t indices)
{
  auto& in = *this->Internal;
  const std::size_t vertexBytes = std::max<std::size_t>(vertices * WordsPerVertex * 4, 4);
  const std::size_t indexBytes = std::max<std::size_t>(indices * 4, 4);
  in.VertexBuffer.Allocate(vertexBytes);
  in.IndexBuffer.Allocate(indexBytes);
}

void vtkCausticsSceneGeometry::UploadMaterials(const caustics::SceneData& scene)
{
  auto& in = *this->Internal;
  // Materials (tiny: always sent when they differ).
  std::vector<GPUMaterial> materials = PackMaterials(scene);
  const std::size_t materialBytes =
    std::max<std::size_t>(materials.size(), 1) * sizeof(GPUMaterial);
  const bool materialsChanged = materials.size() != in.Materials.size() ||
    (!materials.empty() &&
      std::memcmp(materials.data(), in.Materials.data(), materials.size() * sizeof(GPUMaterial)) !=
        0);
  in.MaterialBuffer.Allocate(materialBytes);
  if (materialsChanged && !materials.empty())
  {
    in.MaterialBuffer.Write(0, materials.size() * sizeof(GPUMaterial), materials.data());
    in.LastUploadBytes += static_cast<vtkIdType>(materials.size() * sizeof(GPUMaterial));
  }
  in.Materials = std::move(materials);
}

void vtkCausticsSceneGeometry::BindMaterials()
{
  this->Internal->MaterialBuffer.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_MATERIAL_BINDING);
}

void vtkCausticsSceneGeometry::Draw(int roleMask)
{
  auto& in = *this->Internal;
  if (!in.VertexArray)
  {
    return;
  }
  glBindVertexArray(in.VertexArray);
  for (const Range& range : in.Ranges)
  {
    if ((roleMask & RoleBit(range.role)) && range.indexCount > 0)
    {
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(range.indexCount), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(range.firstIndex * 4));
    }
  }
  glBindVertexArray(0);
}

vtkIdType vtkCausticsSceneGeometry::GetNumberOfTriangles(int roleMask) const
{
  vtkIdType count = 0;
  for (const Range& range : this->Internal->Ranges)
  {
    if (roleMask & RoleBit(range.role))
    {
      count += static_cast<vtkIdType>(range.indexCount / 3);
    }
  }
  return count;
}

unsigned int vtkCausticsSceneGeometry::GetVertexBuffer() const
{
  return this->Internal->VertexBuffer.Handle();
}
unsigned int vtkCausticsSceneGeometry::GetIndexBuffer() const
{
  return this->Internal->IndexBuffer.Handle();
}
unsigned int vtkCausticsSceneGeometry::GetMaterialBuffer() const
{
  return this->Internal->MaterialBuffer.Handle();
}
vtkTypeUInt64 vtkCausticsSceneGeometry::GetContentVersion() const
{
  return this->Internal->ContentVersion;
}

vtkIdType vtkCausticsSceneGeometry::GetLastUploadBytes() const
{
  return this->Internal->LastUploadBytes;
}

void vtkCausticsSceneGeometry::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Meshes: " << this->Internal->Slots.size() << "\n";
  os << indent << "Triangles: receivers " << this->GetNumberOfTriangles(RoleBit(1))
     << ", reflectors " << this->GetNumberOfTriangles(RoleBit(2)) << ", refractors "
     << this->GetNumberOfTriangles(RoleBit(3)) << "\n";
  os << indent << "VertexBytes: " << this->Internal->VertexBuffer.Bytes() << "\n";
  os << indent << "LastUploadBytes: " << this->Internal->LastUploadBytes << "\n";
  os << indent << "ContentVersion: " << this->Internal->ContentVersion << "\n";
}
