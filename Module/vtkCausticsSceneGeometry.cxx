#include "vtkCausticsSceneGeometry.h"

#include "vtkCausticsBindings.h" // CAUSTICS_MATERIAL_BINDING
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <numeric>

vtkStandardNewMacro(vtkCausticsSceneGeometry);

namespace
{
// Interleaved vertex: position (3 floats), normal (3 floats), material index (uint).
constexpr int WordsPerVertex = 7;

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
}

struct vtkCausticsSceneGeometry::Internals
{
  GLuint VertexArray = 0;
  GLuint VertexBuffer = 0;
  GLuint IndexBuffer = 0;
  GLuint MaterialBuffer = 0;
  std::size_t VertexCapacity = 0, IndexCapacity = 0, MaterialCapacity = 0;
  std::vector<MeshSlot> Slots;
  std::vector<Range> Ranges;
  std::vector<GPUMaterial> Materials;
  vtkIdType LastUploadBytes = 0;
  std::vector<float> Staging;
};

vtkCausticsSceneGeometry::vtkCausticsSceneGeometry()
  : Internal(new Internals)
{
}

vtkCausticsSceneGeometry::~vtkCausticsSceneGeometry()
{
  if (this->Internal->VertexBuffer || this->Internal->VertexArray)
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
  GLuint buffers[3] = { in.VertexBuffer, in.IndexBuffer, in.MaterialBuffer };
  for (GLuint buffer : buffers)
  {
    if (buffer)
    {
      glDeleteBuffers(1, &buffer);
    }
  }
  in.VertexArray = in.VertexBuffer = in.IndexBuffer = in.MaterialBuffer = 0;
  in.VertexCapacity = in.IndexCapacity = in.MaterialCapacity = 0;
  in.Slots.clear();
  in.Ranges.clear();
  in.Materials.clear(); // the material buffer is gone: the next Upload() must resend them
}

bool vtkCausticsSceneGeometry::Upload(
  const caustics::SceneData& scene, vtkOpenGLRenderWindow* vtkNotUsed(renWin))
{
  auto& in = *this->Internal;
  in.LastUploadBytes = 0;
  if (!in.VertexArray)
  {
    glCreateVertexArrays(1, &in.VertexArray);
    glCreateBuffers(1, &in.VertexBuffer);
    glCreateBuffers(1, &in.IndexBuffer);
    glCreateBuffers(1, &in.MaterialBuffer);
    glVertexArrayVertexBuffer(in.VertexArray, 0, in.VertexBuffer, 0, WordsPerVertex * 4);
    glVertexArrayElementBuffer(in.VertexArray, in.IndexBuffer);
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

  // Layout: meshes sorted by role (stable), each a block of vertices and indices.
  std::vector<int> order(scene.Meshes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
    [&](int a, int b)
    {
      return scene.Materials[scene.Meshes[a].material].role <
        scene.Materials[scene.Meshes[b].material].role;
    });
  std::vector<MeshSlot> slots;
  std::size_t vertices = 0, indices = 0;
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
  bool sameLayout = slots.size() == in.Slots.size();
  for (std::size_t i = 0; sameLayout && i < slots.size(); ++i)
  {
    sameLayout = slots[i].actor == in.Slots[i].actor &&
      slots[i].vertexCount == in.Slots[i].vertexCount &&
      slots[i].indexCount == in.Slots[i].indexCount && slots[i].material == in.Slots[i].material;
  }
  if (!sameLayout)
  {
    const std::size_t vertexBytes = std::max<std::size_t>(vertices * WordsPerVertex * 4, 4);
    const std::size_t indexBytes = std::max<std::size_t>(indices * 4, 4);
    if (vertexBytes > in.VertexCapacity)
    {
      glNamedBufferData(in.VertexBuffer, vertexBytes, nullptr, GL_DYNAMIC_DRAW);
      in.VertexCapacity = vertexBytes;
    }
    if (indexBytes > in.IndexCapacity)
    {
      glNamedBufferData(in.IndexBuffer, indexBytes, nullptr, GL_DYNAMIC_DRAW);
      in.IndexCapacity = indexBytes;
    }
  }

  for (std::size_t i = 0; i < slots.size(); ++i)
  {
    if (sameLayout && slots[i].version == in.Slots[i].version)
    {
      continue;
    }
    const auto& mesh = scene.Meshes[order[i]];
    const MeshSlot& slot = slots[i];
    in.Staging.resize(slot.vertexCount * WordsPerVertex);
    for (std::size_t v = 0; v < slot.vertexCount; ++v)
    {
      float* out = &in.Staging[v * WordsPerVertex];
      std::memcpy(out, &mesh.positions[3 * v], 12);
      std::memcpy(out + 3, &mesh.normals[3 * v], 12);
      const std::uint32_t material = static_cast<std::uint32_t>(slot.material);
      std::memcpy(out + 6, &material, 4);
    }
    const std::size_t vertexBytes = in.Staging.size() * 4;
    glNamedBufferSubData(
      in.VertexBuffer, slot.firstVertex * WordsPerVertex * 4, vertexBytes, in.Staging.data());
    // Indices are stored absolute, so that compute stages need no base vertex.
    std::vector<std::uint32_t> shifted(mesh.indices.size());
    for (std::size_t k = 0; k < shifted.size(); ++k)
    {
      shifted[k] = mesh.indices[k] + static_cast<std::uint32_t>(slot.firstVertex);
    }
    glNamedBufferSubData(in.IndexBuffer, slot.firstIndex * 4, shifted.size() * 4, shifted.data());
    in.LastUploadBytes += static_cast<vtkIdType>(vertexBytes + shifted.size() * 4);
  }
  in.Slots = std::move(slots);

  // Contiguous draw ranges per role.
  in.Ranges.clear();
  for (const MeshSlot& slot : in.Slots)
  {
    if (!in.Ranges.empty() && in.Ranges.back().role == slot.role)
    {
      in.Ranges.back().indexCount += slot.indexCount;
    }
    else
    {
      in.Ranges.push_back({ slot.role, slot.firstIndex, slot.indexCount });
    }
  }

  // Materials (tiny: always sent when they differ).
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
  const std::size_t materialBytes =
    std::max<std::size_t>(materials.size(), 1) * sizeof(GPUMaterial);
  const bool materialsChanged = materials.size() != in.Materials.size() ||
    (!materials.empty() &&
      std::memcmp(materials.data(), in.Materials.data(), materials.size() * sizeof(GPUMaterial)) !=
        0);
  if (materialBytes > in.MaterialCapacity)
  {
    glNamedBufferData(in.MaterialBuffer, materialBytes, nullptr, GL_DYNAMIC_DRAW);
    in.MaterialCapacity = materialBytes;
  }
  if (materialsChanged && !materials.empty())
  {
    glNamedBufferSubData(
      in.MaterialBuffer, 0, materials.size() * sizeof(GPUMaterial), materials.data());
    in.LastUploadBytes += static_cast<vtkIdType>(materials.size() * sizeof(GPUMaterial));
  }
  in.Materials = std::move(materials);
  return glGetError() == GL_NO_ERROR;
}

void vtkCausticsSceneGeometry::BindMaterials()
{
  glBindBufferBase(
    GL_SHADER_STORAGE_BUFFER, CAUSTICS_MATERIAL_BINDING, this->Internal->MaterialBuffer);
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
  return this->Internal->VertexBuffer;
}
unsigned int vtkCausticsSceneGeometry::GetIndexBuffer() const
{
  return this->Internal->IndexBuffer;
}
unsigned int vtkCausticsSceneGeometry::GetMaterialBuffer() const
{
  return this->Internal->MaterialBuffer;
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
  os << indent << "VertexBytes: " << this->Internal->VertexCapacity << "\n";
  os << indent << "LastUploadBytes: " << this->Internal->LastUploadBytes << "\n";
}
