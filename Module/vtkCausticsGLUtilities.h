/**
 * @file   vtkCausticsGLUtilities.h
 * @brief  Small GL helpers shared by the caustics stages (not wrapped).
 *
 * Textures are (re)allocated only when their size or format changes, and buffer
 * objects (StorageBuffer, the one buffer class of the module) only when they must
 * grow, so the stages create no GL objects per frame; read-back turns a texture
 * into a vtkImageData array for tests and debugging (never used in the render path).
 */
#ifndef vtkCausticsGLUtilities_h
#define vtkCausticsGLUtilities_h

#include "vtkCausticsPhotonGrid.h"      // For caustics::PhotonRecords
#include "vtkNew.h"                     // For vtkNew
#include "vtkRenderingCausticsModule.h" // For export macro
#include "vtkSmartPointer.h"            // For vtkSmartPointer
#include "vtkTextureObject.h"           // For vtkNew<vtkTextureObject>

#include <cstddef> // For std::size_t
#include <cstdint> // For std::uint64_t
#include <memory>  // For std::shared_ptr
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkCausticsShaderProgram;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkWindow;

namespace caustics
{
class DensityGrid;
struct Medium;
struct SceneData;
namespace gl
{
/** GL objects and their storage held by the caustics stages of this process. */
struct GraphicsCounts
{
  long long Textures = 0;     ///< live textures (2D, 2D array, depth)
  long long TextureBytes = 0; ///< their level-0 storage
  long long Buffers = 0;      ///< live buffer objects (StorageBuffer)
  long long BufferBytes = 0;  ///< their storage
  long long Framebuffers = 0; ///< live raw framebuffer objects (screen-space stages)
};

/** Kinds of GL object counted by CountObject(). */
enum class Counted
{
  Texture,
  Buffer,
  Framebuffer
};

/**
 * Adds `objects` GL objects of `kind` holding `bytes` bytes to the bookkeeping
 * (negative to remove them). Called where a wrapper creates, resizes or deletes its
 * GL name; thread-safe.
 */
VTKRENDERINGCAUSTICS_EXPORT void CountObject(Counted kind, long long objects, long long bytes);

/**
 * Registers a vtkTextureObject whose storage the bookkeeping reads when asked (its
 * handle, size and format then): VTK's class creates and deletes the GL name itself.
 */
VTKRENDERINGCAUSTICS_EXPORT void TrackTexture(vtkTextureObject* texture);

/** What the caustics stages hold now: counted objects plus live tracked textures. */
VTKRENDERINGCAUSTICS_EXPORT GraphicsCounts CountGraphicsMemory();

/** Bytes per texel of a sized internal format (16 for a format it does not know). */
VTKRENDERINGCAUSTICS_EXPORT std::size_t BytesPerTexel(unsigned int internalFormat);

/**
 * Makes `texture` a width x height 2D texture of the given sized internal format
 * (GL_RGBA32F, GL_R32UI, GL_DEPTH_COMPONENT32F, ...), nearest filtering, clamped;
 * reallocates only when size or format differ. Returns true if it (re)allocated.
 */
VTKRENDERINGCAUSTICS_EXPORT bool EnsureTexture(vtkTextureObject* texture,
  vtkOpenGLRenderWindow* renWin, int width, int height, unsigned int internalFormat);

class MediumBuffer;

/**
 * Before Bind(): gives `program` the define CAUSTICS_MEDIUM_GRID when `grid` holds a
 * density grid (the program then compiles PNanoVDB.h and follows the density), removes
 * it otherwise, so homogeneous media keep their program as it was. A program
 * recompiles only when a grid appears or goes.
 */
VTKRENDERINGCAUSTICS_EXPORT void SetMediumDefine(
  vtkCausticsShaderProgram* program, const MediumBuffer* grid);

/**
 * Sets the participating medium's uniforms of vtkCausticsCommon.glsl
 * (causticsMediumOn, causticsSigmaT, causticsMediumLow/High: the scene's bounds) on
 * the bound program, for CausticsMediumTransmittance(). A program compiled with
 * CAUSTICS_MEDIUM_GRID (SetMediumDefine) also gets `grid`'s buffer and transform, and
 * causticsSigmaT per unit density; any other takes the grid's mean density.
 */
VTKRENDERINGCAUSTICS_EXPORT void SetMediumUniforms(vtkCausticsShaderProgram* program,
  const caustics::SceneData& scene, const MediumBuffer* grid = nullptr);
/** The same for `medium` filling `bounds` (xmin, xmax, ...: the scene's). */
VTKRENDERINGCAUSTICS_EXPORT void SetMediumUniforms(vtkCausticsShaderProgram* program,
  const caustics::Medium& medium, const double bounds[6], const MediumBuffer* grid = nullptr);

/** Row-major double matrix (vtkMatrix4x4 layout) to column-major floats for GL. */
VTKRENDERINGCAUSTICS_EXPORT void ToColumnMajor(const double rowMajor[16], float columnMajor[16]);

///@{
/**
 * Keys of kept results: a stage that keeps what it drew while its inputs stay the
 * same appends to a key everything the result is a function of, and draws again
 * only when the key differs from the one of what it holds. Values go in by their
 * exact bits (any change, however small, redraws).
 */
VTKRENDERINGCAUSTICS_EXPORT void AppendKey(
  std::vector<std::uint64_t>& key, const double* values, int count);
VTKRENDERINGCAUSTICS_EXPORT void AppendKey(
  std::vector<std::uint64_t>& key, const float* values, int count);
/**
 * What vtkCausticsSceneGeometry draws from the scene's meshes: their number and,
 * per mesh, its version (globally unique, renewed by vtkCausticsSceneExtractor
 * whenever its triangles or its actor's matrix change), material slot and role.
 * Material properties other than the role are not in it.
 */
VTKRENDERINGCAUSTICS_EXPORT void AppendMeshesKey(
  std::vector<std::uint64_t>& key, const SceneData& scene);
///@}

/**
 * What the caustic irradiance on the receivers depends on, as numbers: every mesh's
 * geometry version (vertices, actor matrix) and material slot, every material's optics
 * (role, IOR, roughness, metal n and k, attenuation; not the albedo), every light
 * (type, position, direction, emission, spot cone), the medium's coefficients. The
 * camera is not in it: irradiance does not depend on the view. Without `placement`,
 * only the optics: no mesh versions, no light positions or directions (what a rigid
 * motion of the whole scene leaves alone).
 */
VTKRENDERINGCAUSTICS_EXPORT std::vector<double> LightFieldSignature(
  const SceneData& scene, bool placement = true);

/** The inverse of a 4x4 matrix, both column-major floats (inverted in double precision). */
VTKRENDERINGCAUSTICS_EXPORT void InvertColumnMajor(const float matrix[16], float inverse[16]);

/**
 * Downloads a 2D texture (float or integer colour, or depth) into a new image whose
 * point data has one array `arrayName` with `components` components (the texture's
 * channels from `firstChannel` on). For tests and debugging only: it stalls.
 */
VTKRENDERINGCAUSTICS_EXPORT vtkSmartPointer<vtkImageData> ReadTexture(
  vtkTextureObject* texture, const std::string& arrayName, int components, int firstChannel = 0);

/**
 * A GL buffer object: shader storage, vertices, indices, indirect commands. The one
 * buffer class of the caustics stages.
 * - Allocate() creates the buffer on first use and gives it new storage only when
 *   it must grow or its usage changes, never shrinking: in a steady scene no frame
 *   allocates. Its name stays the same, so vertex arrays that refer to it stay
 *   valid; its contents are undefined after a reallocation.
 * - Release() deletes it. The destructor makes no GL call (no context need be
 *   current then) and reports a buffer that was not released, as VTK's
 *   vtkToneMappingPass does for its resources.
 * Non-copyable (one owner per GL name), movable.
 */
class VTKRENDERINGCAUSTICS_EXPORT StorageBuffer
{
public:
  /** The GL usage hint of the storage. */
  enum class Usage
  {
    Draw, ///< GL_DYNAMIC_DRAW: written by the CPU, read by the GPU
    Copy  ///< GL_DYNAMIC_COPY: written and read by the GPU (lists, counters)
  };

  StorageBuffer() = default;
  ~StorageBuffer();
  StorageBuffer(const StorageBuffer&) = delete;
  StorageBuffer& operator=(const StorageBuffer&) = delete;
  StorageBuffer(StorageBuffer&& other) noexcept;
  /** Takes over `other`'s buffer; this one must have been released (else reported). */
  StorageBuffer& operator=(StorageBuffer&& other) noexcept;

  /**
   * Makes the buffer at least `bytes` long (16 at least) with the given usage.
   * Returns true when it (re)allocated, which leaves the contents undefined.
   */
  bool Allocate(std::size_t bytes, Usage usage = Usage::Draw);

  /** The GL name (0 before the first Allocate() or after Release()). */
  unsigned int Handle() const { return this->Name; }
  /** Bytes of storage the buffer has. */
  std::size_t Bytes() const { return this->Size; }

  /** Binds the whole buffer to indexed binding `binding` of `target` (GL_SHADER_STORAGE_BUFFER,
   * ...). */
  void BindBase(unsigned int target, unsigned int binding) const;

  /** Sets every byte (or `bytes` bytes from `offset`) to zero, on the GPU. */
  void Clear();
  void Clear(std::size_t offset, std::size_t bytes);

  /** Copies `bytes` bytes from `data` into the buffer at `offset`. */
  void Write(std::size_t offset, std::size_t bytes, const void* data);
  /** Copies `bytes` bytes at `offset` into `data` (stalls: tests and statistics only). */
  void Read(std::size_t offset, std::size_t bytes, void* data) const;

  /** Deletes the buffer (needs the context current); Allocate() makes a new one. */
  void Release();

private:
  unsigned int Name = 0;
  std::size_t Size = 0;
  Usage Use = Usage::Draw;
};

/**
 * The density grid of the scene's heterogeneous medium on the GPU: its NanoVDB buffer
 * (caustics::DensityGrid::GetNanoVDBData) in one storage buffer, read by PNanoVDB.h in
 * the programs compiled with CAUSTICS_MEDIUM_GRID. Update() uploads only when the
 * voxels change (a new load); a new placement or scale changes uniforms only, so no
 * frame allocates or uploads in a steady scene. Owned by vtkCausticsRenderPass, shared
 * by its stages.
 */
class VTKRENDERINGCAUSTICS_EXPORT MediumBuffer
{
public:
  /** Follows `medium` (uploading its grid's voxels if new); false without a grid. */
  bool Update(const caustics::Medium& medium);
  /** True when the last Update() found a density grid. */
  bool HasGrid() const { return this->Grid != nullptr; }
  /** The grid of the last Update() (null when none). */
  const caustics::DensityGrid* GetGrid() const { return this->Grid.get(); }
  /** Binds the buffer at CAUSTICS_MEDIUM_GRID_BINDING. */
  void Bind() const;
  /** Bytes of the NanoVDB grid on the GPU (0 without a grid). */
  std::size_t Bytes() const;
  /** How many times the voxels were uploaded (tests: once per new grid). */
  int GetUploads() const { return this->Uploads; }
  /** Deletes the buffer and forgets the grid. */
  void Release();

private:
  StorageBuffer Buffer;
  std::shared_ptr<const caustics::DensityGrid> Grid; ///< what the uniforms follow
  const void* Uploaded = nullptr;                    ///< the voxels in Buffer
  std::size_t UploadedBytes = 0;
  int Uploads = 0;
};

/**
 * Owns the three RGBA32F textures of one grid of photon records
 * (caustics::PhotonRecords, the one photon record layout of vtkCausticsPhotonGrid.h)
 * and, for landed photons, their kernel radii (R32F, m). The stages that write
 * photons (the emitter, the transports) keep one; Records() is what they hand on.
 */
class VTKRENDERINGCAUSTICS_EXPORT PhotonPlanes
{
public:
  /** Sizes the planes to width x height (reallocating only on change); true if it did. */
  bool Ensure(vtkOpenGLRenderWindow* renWin, int width, int height);
  /** Also sizes the kernel-radius texture (landed photons whose transport sizes kernels). */
  bool EnsureWithRadius(vtkOpenGLRenderWindow* renWin, int width, int height);
  /** Zeroes the position plane: no photon anywhere (the other planes are then ignored). */
  void ClearPositions();
  /**
   * Binds the planes to image units first, first + 1, first + 2 (position, direction,
   * flux) with the given access (GL_READ_ONLY, GL_WRITE_ONLY, GL_READ_WRITE).
   */
  void BindImages(unsigned int first, unsigned int access) const;
  /** Binds the kernel-radius texture to image unit `unit`. */
  void BindRadiusImage(unsigned int unit, unsigned int access) const;
  /** The textures, for the next stage. */
  caustics::PhotonRecords Records() const;
  /** The kernel radii (m, R32F); unallocated unless EnsureWithRadius() was called. */
  vtkTextureObject* KernelRadius() const { return this->Radius; }
  void Release(vtkWindow* window);

private:
  vtkNew<vtkTextureObject> Position;
  vtkNew<vtkTextureObject> Direction;
  vtkNew<vtkTextureObject> Flux;
  vtkNew<vtkTextureObject> Radius;
};

/** A vertex array with no attributes, for drawing a full-screen triangle from gl_VertexID. */
class VTKRENDERINGCAUSTICS_EXPORT FullScreenTriangle
{
public:
  ~FullScreenTriangle();
  /** Draws 3 vertices (glsl/vtkCausticsFullScreenVS.glsl makes the triangle). */
  void Draw();
  /**
   * The same draw with its arguments read on the GPU (glDrawArraysIndirect) from
   * `buffer` at byte `offset`: { 3, instances, 0, 0 }, instances 0 drawing nothing.
   * A stage gated by what an earlier GPU stage found, without a read-back.
   */
  void DrawIndirect(const StorageBuffer& buffer, std::size_t offset);
  void Release();

private:
  unsigned int VertexArray = 0;
};
}
}

#endif
