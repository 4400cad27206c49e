#include "vtkCausticsGLUtilities.h"

#include "vtkCausticsBindings.h"
#include "vtkCausticsDensityGrid.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsShaderProgram.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkSetGet.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <vector>

namespace caustics
{
namespace gl
{
namespace
{
struct FormatInfo
{
  unsigned int format;
  unsigned int type;
  int components;
  int vtkType;
};

FormatInfo Describe(unsigned int internalFormat)
{
  switch (internalFormat)
  {
    case GL_RGBA32F:
      return { GL_RGBA, GL_FLOAT, 4, VTK_FLOAT };
    case GL_RGBA16F:
      return { GL_RGBA, GL_HALF_FLOAT, 4, VTK_FLOAT };
    case GL_RG32F:
      return { GL_RG, GL_FLOAT, 2, VTK_FLOAT };
    case GL_R32F:
      return { GL_RED, GL_FLOAT, 1, VTK_FLOAT };
    case GL_R32UI:
      return { GL_RED_INTEGER, GL_UNSIGNED_INT, 1, VTK_UNSIGNED_INT };
    case GL_RGBA32UI:
      return { GL_RGBA_INTEGER, GL_UNSIGNED_INT, 4, VTK_UNSIGNED_INT };
    case GL_RGBA8:
      return { GL_RGBA, GL_UNSIGNED_BYTE, 4, VTK_UNSIGNED_CHAR };
    case GL_DEPTH_COMPONENT32F:
      return { GL_DEPTH_COMPONENT, GL_FLOAT, 1, VTK_FLOAT };
    default:
      return { GL_RGBA, GL_FLOAT, 4, VTK_FLOAT };
  }
}
}

namespace
{
/**
 * The bookkeeping of CountGraphicsMemory(): counters for the wrappers that own raw
 * GL names, weak pointers to the vtkTextureObjects EnsureTexture() allocated. Made
 * once and never destroyed, so objects released during static destruction still
 * find it.
 */
struct Ledger
{
  std::atomic<long long> Objects[3] = { { 0 }, { 0 }, { 0 } };
  std::atomic<long long> Bytes[3] = { { 0 }, { 0 }, { 0 } };
  std::mutex TexturesLock;
  std::vector<vtkWeakPointer<vtkTextureObject>> Textures;
};

Ledger& TheLedger()
{
  static Ledger* ledger = new Ledger;
  return *ledger;
}
}

std::size_t BytesPerTexel(unsigned int internalFormat)
{
  switch (internalFormat)
  {
    case GL_R32F:
    case GL_R32UI:
    case GL_R32I:
    case GL_RGBA8:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH_COMPONENT32:
    case GL_DEPTH24_STENCIL8:
      return 4;
    case GL_DEPTH_COMPONENT16:
    case GL_R16F:
      return 2;
    case GL_RG32F:
    case GL_RGBA16F:
    case GL_RG32UI:
      return 8;
    default:
      return 16; // GL_RGBA32F, GL_RGBA32UI and anything unknown (the largest)
  }
}

void CountObject(Counted kind, long long objects, long long bytes)
{
  const int k = static_cast<int>(kind);
  TheLedger().Objects[k] += objects;
  TheLedger().Bytes[k] += bytes;
}

void TrackTexture(vtkTextureObject* texture)
{
  Ledger& ledger = TheLedger();
  std::lock_guard<std::mutex> lock(ledger.TexturesLock);
  auto& textures = ledger.Textures;
  textures.erase(std::remove_if(textures.begin(), textures.end(),
                   [](const vtkWeakPointer<vtkTextureObject>& t) { return t == nullptr; }),
    textures.end());
  if (std::find(textures.begin(), textures.end(), texture) == textures.end())
  {
    textures.emplace_back(texture);
  }
}

GraphicsCounts CountGraphicsMemory()
{
  Ledger& ledger = TheLedger();
  GraphicsCounts counts;
  counts.Textures = ledger.Objects[static_cast<int>(Counted::Texture)];
  counts.TextureBytes = ledger.Bytes[static_cast<int>(Counted::Texture)];
  counts.Buffers = ledger.Objects[static_cast<int>(Counted::Buffer)];
  counts.BufferBytes = ledger.Bytes[static_cast<int>(Counted::Buffer)];
  counts.Framebuffers = ledger.Objects[static_cast<int>(Counted::Framebuffer)];
  std::lock_guard<std::mutex> lock(ledger.TexturesLock);
  for (vtkTextureObject* texture : ledger.Textures)
  {
    if (texture && texture->GetHandle() != 0)
    {
      const long long texels = static_cast<long long>(texture->GetWidth()) * texture->GetHeight() *
        std::max(1u, texture->GetDepth());
      counts.Textures += 1;
      counts.TextureBytes += texels *
        static_cast<long long>(BytesPerTexel(texture->GetInternalFormat(VTK_FLOAT, 4, false)));
    }
  }
  return counts;
}

bool EnsureTexture(vtkTextureObject* texture, vtkOpenGLRenderWindow* renWin, int width, int height,
  unsigned int internalFormat)
{
  width = width < 1 ? 1 : width;
  height = height < 1 ? 1 : height;
  if (texture->GetHandle() != 0 && static_cast<int>(texture->GetWidth()) == width &&
    static_cast<int>(texture->GetHeight()) == height &&
    texture->GetInternalFormat(VTK_FLOAT, 4, false) == internalFormat)
  {
    return false;
  }
  texture->SetContext(renWin);
  const FormatInfo info = Describe(internalFormat);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  if (internalFormat == GL_DEPTH_COMPONENT32F)
  {
    texture->AllocateDepth(width, height, vtkTextureObject::Float32);
  }
  else
  {
    texture->SetInternalFormat(internalFormat);
    texture->SetFormat(info.format);
    texture->SetDataType(info.type);
    texture->Allocate2D(width, height, info.components, info.vtkType);
  }
  TrackTexture(texture);
  return true;
}

void SetMediumDefine(vtkCausticsShaderProgram* program, const MediumBuffer* grid)
{
  if (grid && grid->HasGrid())
  {
    program->SetDefine("CAUSTICS_MEDIUM_GRID", 1);
  }
  else
  {
    program->RemoveDefine("CAUSTICS_MEDIUM_GRID");
  }
}

void SetMediumUniforms(
  vtkCausticsShaderProgram* program, const caustics::SceneData& scene, const MediumBuffer* grid)
{
  SetMediumUniforms(program, scene.Participating, scene.Bounds, grid);
}

void SetMediumUniforms(vtkCausticsShaderProgram* program, const caustics::Medium& medium,
  const double bounds[6], const MediumBuffer* grid)
{
  program->SetUniformi("causticsMediumOn", medium.enabled ? 1 : 0);
  program->SetUniformi("causticsMediumFillsRefractors", medium.fillsRefractors ? 1 : 0);
  double low[3] = { bounds[0], bounds[2], bounds[4] };
  double high[3] = { bounds[1], bounds[3], bounds[5] };
  const bool followsGrid =
    program->HasDefine("CAUSTICS_MEDIUM_GRID") && grid && grid->HasGrid() && medium.density;
  if (followsGrid)
  {
    // The density is 0 outside the grid's bounds: march their overlap with the scene only.
    double gridBounds[6];
    grid->GetGrid()->GetWorldBounds(gridBounds);
    for (int a = 0; a < 3; ++a)
    {
      low[a] = std::max(low[a], gridBounds[2 * a]);
      high[a] = std::max(low[a], std::min(high[a], gridBounds[2 * a + 1])); // empty: flat
    }
    double worldToIndex[16];
    grid->GetGrid()->GetWorldToIndex(worldToIndex);
    float matrix[16];
    ToColumnMajor(worldToIndex, matrix);
    program->SetUniformMatrix4("causticsWorldToIndex", matrix);
    program->SetUniformf("causticsDensityScale", static_cast<float>(grid->GetGrid()->GetScale()));
    grid->Bind();
  }
  // Per unit density when the program follows the grid; else the grid's mean stands in
  // (vtkCausticsRenderPass warns about the stages that do).
  caustics::Vec3 sigmaT = medium.MeanSigmaT();
  if (followsGrid)
  {
    for (int c = 0; c < 3; ++c)
    {
      sigmaT[c] = medium.sigmaS[c] + medium.sigmaA[c];
    }
  }
  program->SetUniform3f("causticsSigmaT", static_cast<float>(sigmaT[0]),
    static_cast<float>(sigmaT[1]), static_cast<float>(sigmaT[2]));
  program->SetUniform3f("causticsMediumLow", static_cast<float>(low[0]), static_cast<float>(low[1]),
    static_cast<float>(low[2]));
  program->SetUniform3f("causticsMediumHigh", static_cast<float>(high[0]),
    static_cast<float>(high[1]), static_cast<float>(high[2]));
}

bool MediumBuffer::Update(const caustics::Medium& medium)
{
  std::shared_ptr<const caustics::DensityGrid> next = medium.enabled ? medium.density : nullptr;
  if (!next)
  {
    // Without a grid held, its voxels may be freed and their address reused: upload anew.
    this->Grid.reset();
    this->Uploaded = nullptr;
    return false;
  }
  // Placements of one load share its voxels (the held grid keeps them alive, so the same
  // address means the same voxels): only a new load uploads.
  const void* voxels = next->GetNanoVDBData();
  const std::size_t bytes = next->GetNanoVDBBytes();
  if (voxels != this->Uploaded || bytes != this->UploadedBytes)
  {
    this->Buffer.Allocate(bytes);
    this->Buffer.Write(0, bytes, voxels);
    this->Uploaded = voxels;
    this->UploadedBytes = bytes;
    ++this->Uploads;
  }
  this->Grid = std::move(next);
  return true;
}

void MediumBuffer::Bind() const
{
  this->Buffer.BindBase(GL_SHADER_STORAGE_BUFFER, CAUSTICS_MEDIUM_GRID_BINDING);
}

std::size_t MediumBuffer::Bytes() const
{
  return this->Grid ? this->Buffer.Bytes() : 0;
}

void MediumBuffer::Release()
{
  this->Buffer.Release();
  this->Grid.reset();
  this->Uploaded = nullptr;
  this->UploadedBytes = 0;
}

bool PhotonPlanes::Ensure(vtkOpenGLRenderWindow* renWin, int width, int height)
{
  bool resized = EnsureTexture(this->Position, renWin, width, height, GL_RGBA32F);
  resized |= EnsureTexture(this->Direction, renWin, width, height, GL_RGBA32F);
  resized |= EnsureTexture(this->Flux, renWin, width, height, GL_RGBA32F);
  return resized;
}

bool PhotonPlanes::EnsureWithRadius(vtkOpenGLRenderWindow* renWin, int width, int height)
{
  bool resized = this->Ensure(renWin, width, height);
  resized |= EnsureTexture(this->Radius, renWin, width, height, GL_R32F);
  return resized;
}

void PhotonPlanes::ClearPositions()
{
  const float none[4] = { 0, 0, 0, 0 };
  glClearTexImage(this->Position->GetHandle(), 0, GL_RGBA, GL_FLOAT, none);
}

void PhotonPlanes::BindImages(unsigned int first, unsigned int access) const
{
  vtkTextureObject* planes[] = { this->Position, this->Direction, this->Flux };
  for (unsigned int i = 0; i < 3; ++i)
  {
    glBindImageTexture(first + i, planes[i]->GetHandle(), 0, GL_FALSE, 0, access, GL_RGBA32F);
  }
}

void PhotonPlanes::BindRadiusImage(unsigned int unit, unsigned int access) const
{
  glBindImageTexture(unit, this->Radius->GetHandle(), 0, GL_FALSE, 0, access, GL_R32F);
}

caustics::PhotonRecords PhotonPlanes::Records() const
{
  caustics::PhotonRecords records;
  records.Position = this->Position;
  records.Direction = this->Direction;
  records.Flux = this->Flux;
  return records;
}

void PhotonPlanes::Release(vtkWindow* window)
{
  this->Position->ReleaseGraphicsResources(window);
  this->Direction->ReleaseGraphicsResources(window);
  this->Flux->ReleaseGraphicsResources(window);
  this->Radius->ReleaseGraphicsResources(window);
}

void InvertColumnMajor(const float matrix[16], float inverse[16])
{
  // Transposition commutes with inversion: invert the column-major array as it is.
  double in[16], out[16];
  std::copy(matrix, matrix + 16, in);
  vtkMatrix4x4::Invert(in, out);
  std::copy(out, out + 16, inverse);
}

void ToColumnMajor(const double rowMajor[16], float columnMajor[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      columnMajor[4 * c + r] = static_cast<float>(rowMajor[4 * r + c]);
    }
  }
}

void AppendKey(std::vector<std::uint64_t>& key, const double* values, int count)
{
  for (int i = 0; i < count; ++i)
  {
    std::uint64_t bits;
    std::memcpy(&bits, values + i, sizeof(bits));
    key.push_back(bits);
  }
}

void AppendKey(std::vector<std::uint64_t>& key, const float* values, int count)
{
  for (int i = 0; i < count; ++i)
  {
    std::uint32_t bits;
    std::memcpy(&bits, values + i, sizeof(bits));
    key.push_back(bits);
  }
}

void AppendMeshesKey(std::vector<std::uint64_t>& key, const SceneData& scene)
{
  key.push_back(scene.Meshes.size());
  for (const Mesh& mesh : scene.Meshes)
  {
    key.push_back(mesh.version);
    key.push_back(static_cast<std::uint64_t>(mesh.material));
    key.push_back(static_cast<std::uint64_t>(scene.Materials[mesh.material].role));
  }
}

std::vector<double> LightFieldSignature(const SceneData& scene, bool placement)
{
  std::vector<double> s;
  auto add = [&s](const Vec3& v) { s.insert(s.end(), v.begin(), v.end()); };
  for (const Mesh& mesh : scene.Meshes)
  {
    s.insert(s.end(),
      { placement ? static_cast<double>(mesh.version) : 0.0, static_cast<double>(mesh.material) });
  }
  for (const Material& m : scene.Materials)
  {
    s.insert(s.end(), { static_cast<double>(m.role), m.ior, m.roughness });
    add(m.metalN);
    add(m.metalK);
    add(m.attenuation);
  }
  for (const Light& light : scene.Lights)
  {
    s.push_back(static_cast<double>(light.type));
    if (placement)
    {
      add(light.position);
      add(light.direction);
    }
    add(light.radiometric);
    s.insert(s.end(), { light.cosOuter, light.cosInner });
  }
  const Medium& medium = scene.Participating;
  s.insert(s.end(), { medium.enabled ? 1.0 : 0.0, medium.g, medium.fillsRefractors ? 1.0 : 0.0 });
  add(medium.sigmaS);
  add(medium.sigmaA);
  return s;
}

vtkSmartPointer<vtkImageData> ReadTexture(
  vtkTextureObject* texture, const std::string& arrayName, int components, int firstChannel)
{
  const int width = static_cast<int>(texture->GetWidth());
  const int height = static_cast<int>(texture->GetHeight());
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  vtkNew<vtkFloatArray> array;
  array->SetName(arrayName.c_str());
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  const unsigned int internalFormat = texture->GetInternalFormat(VTK_FLOAT, 4, false);
  const bool isDepth = internalFormat == GL_DEPTH_COMPONENT32F ||
    texture->GetFormat(VTK_FLOAT, 1, false) == GL_DEPTH_COMPONENT;
  const bool isInteger = internalFormat == GL_R32UI || internalFormat == GL_RGBA32UI;
  const int channels = isDepth ? 1
                               : (internalFormat == GL_R32F || internalFormat == GL_R32UI
                                     ? 1
                                     : (internalFormat == GL_RG32F ? 2 : 4));
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * channels);
  const std::size_t bytes = pixels.size() * sizeof(float);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (isDepth)
  {
    glGetTextureImage(texture->GetHandle(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
      static_cast<GLsizei>(bytes), pixels.data());
  }
  else if (isInteger)
  {
    std::vector<unsigned int> raw(pixels.size());
    glGetTextureImage(texture->GetHandle(), 0, channels == 1 ? GL_RED_INTEGER : GL_RGBA_INTEGER,
      GL_UNSIGNED_INT, static_cast<GLsizei>(bytes), raw.data());
    for (std::size_t i = 0; i < raw.size(); ++i)
    {
      pixels[i] = static_cast<float>(raw[i]);
    }
  }
  else
  {
    const GLenum format = channels == 1 ? GL_RED : (channels == 2 ? GL_RG : GL_RGBA);
    glGetTextureImage(
      texture->GetHandle(), 0, format, GL_FLOAT, static_cast<GLsizei>(bytes), pixels.data());
  }
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(width) * height; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const int channel = firstChannel + c;
      array->SetComponent(i, c, channel < channels ? pixels[i * channels + channel] : 0.0f);
    }
  }
  image->GetPointData()->AddArray(array);
  return image;
}

StorageBuffer::~StorageBuffer()
{
  if (this->Name)
  {
    vtkGenericWarningMacro(<< "caustics::gl::StorageBuffer destroyed before Release(): GL buffer "
                           << this->Name << " leaked");
  }
}

StorageBuffer::StorageBuffer(StorageBuffer&& other) noexcept
  : Name(other.Name)
  , Size(other.Size)
  , Use(other.Use)
{
  other.Name = 0;
  other.Size = 0;
}

StorageBuffer& StorageBuffer::operator=(StorageBuffer&& other) noexcept
{
  if (this != &other)
  {
    if (this->Name)
    {
      vtkGenericWarningMacro(<< "caustics::gl::StorageBuffer overwritten before Release(): GL "
                             << "buffer " << this->Name << " leaked");
    }
    this->Name = other.Name;
    this->Size = other.Size;
    this->Use = other.Use;
    other.Name = 0;
    other.Size = 0;
  }
  return *this;
}

bool StorageBuffer::Allocate(std::size_t bytes, Usage usage)
{
  bytes = bytes < 16 ? 16 : bytes;
  if (!this->Name)
  {
    glCreateBuffers(1, &this->Name);
    this->Size = 0;
    CountObject(Counted::Buffer, 1, 0);
  }
  else if (this->Size >= bytes && this->Use == usage)
  {
    return false;
  }
  bytes = bytes > this->Size ? bytes : this->Size; // a new usage keeps the size
  glNamedBufferData(this->Name, static_cast<GLsizeiptr>(bytes), nullptr,
    usage == Usage::Copy ? GL_DYNAMIC_COPY : GL_DYNAMIC_DRAW);
  CountObject(
    Counted::Buffer, 0, static_cast<long long>(bytes) - static_cast<long long>(this->Size));
  this->Size = bytes;
  this->Use = usage;
  return true;
}

void StorageBuffer::BindBase(unsigned int target, unsigned int binding) const
{
  glBindBufferBase(target, binding, this->Name);
}

void StorageBuffer::Clear()
{
  glClearNamedBufferData(this->Name, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void StorageBuffer::Clear(std::size_t offset, std::size_t bytes)
{
  glClearNamedBufferSubData(this->Name, GL_R32UI, static_cast<GLintptr>(offset),
    static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

void StorageBuffer::Write(std::size_t offset, std::size_t bytes, const void* data)
{
  glNamedBufferSubData(
    this->Name, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void StorageBuffer::Read(std::size_t offset, std::size_t bytes, void* data) const
{
  glGetNamedBufferSubData(
    this->Name, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void StorageBuffer::Release()
{
  if (this->Name)
  {
    glDeleteBuffers(1, &this->Name);
    CountObject(Counted::Buffer, -1, -static_cast<long long>(this->Size));
  }
  this->Name = 0;
  this->Size = 0;
}

FullScreenTriangle::~FullScreenTriangle() = default;

void FullScreenTriangle::Draw()
{
  if (!this->VertexArray)
  {
    glCreateVertexArrays(1, &this->VertexArray);
  }
  glBindVertexArray(this->VertexArray);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

void FullScreenTriangle::DrawIndirect(const StorageBuffer& buffer, std::size_t offset)
{
  if (!this->VertexArray)
  {
    glCreateVertexArrays(1, &this->VertexArray);
  }
  glBindVertexArray(this->VertexArray);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffer.Handle());
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
  glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(offset));
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glBindVertexArray(0);
}

void FullScreenTriangle::Release()
{
  if (this->VertexArray)
  {
    glDeleteVertexArrays(1, &this->VertexArray);
    this->VertexArray = 0;
  }
}
}
}
