/**
 * @file   vtkCausticsScreenSpaceUtilities.h
 * @brief  Plain GL helpers of the screen-space photon tracing stages (not wrapped).
 *
 * The layered depth images and the line tracer need GL objects that
 * vtkTextureObject does not make (2D array textures with layered attachments,
 * framebuffers without attachments), so these stages own raw GL names through
 * the small classes below (buffer objects: caustics::gl::StorageBuffer):
 * - each object is created on first use and reallocated only when its size or
 *   format changes (never per frame);
 * - Release() deletes it; a destructor that finds a live name reports the leak
 *   on stderr, as VTK's passes do for theirs;
 * - TextureUnits binds raw textures on units taken from VTK's
 *   vtkTextureUnitManager and gives them back when it goes out of scope, so VTK's
 *   own texture bookkeeping stays right.
 */
#ifndef vtkCausticsScreenSpaceUtilities_h
#define vtkCausticsScreenSpaceUtilities_h

#include "vtkRenderingCausticsModule.h" // For export macro

#include <vector> // For std::vector

class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace caustics
{
namespace ssp
{
/** A 2D or 2D-array texture with immutable storage, nearest filtering, clamped. */
class VTKRENDERINGCAUSTICS_EXPORT Texture
{
public:
  Texture() = default;
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;

  /**
   * Makes this a width x height texture of `layers` layers (0: a plain 2D texture)
   * with the sized internal format (GL_RGBA32F, GL_R32UI, GL_DEPTH_COMPONENT32F, ...).
   * Returns true when it (re)allocated.
   */
  bool Ensure(int width, int height, int layers, unsigned int internalFormat);
  void Release();
  /** Bytes of storage (level 0, every layer). */
  long long Bytes() const;

  unsigned int Handle = 0;
  int Width = 0, Height = 0, Layers = 0;
  unsigned int Format = 0;
};

/** A framebuffer object whose attachments the owner sets. */
class VTKRENDERINGCAUSTICS_EXPORT Framebuffer
{
public:
  Framebuffer() = default;
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  /** Creates the framebuffer on first use; returns its name. */
  unsigned int Get();
  void Release();

  unsigned int Handle = 0;
};

/** Texture units for raw textures and vtkTextureObjects, freed on destruction. */
class VTKRENDERINGCAUSTICS_EXPORT TextureUnits
{
public:
  explicit TextureUnits(vtkOpenGLRenderWindow* renWin);
  ~TextureUnits();
  TextureUnits(const TextureUnits&) = delete;
  TextureUnits& operator=(const TextureUnits&) = delete;

  /** Binds a raw texture on a free unit and returns the unit (-1 if none is free). */
  int Bind(unsigned int texture);
  /** Activates a vtkTextureObject and returns its unit. */
  int Bind(vtkTextureObject* texture);

private:
  vtkOpenGLRenderWindow* Window;
  std::vector<int> Units;
  std::vector<vtkTextureObject*> Objects;
};

/**
 * World size of one pixel at clip w = 1 for a column-major world-to-clip matrix
 * and a width x height view: 2 / (size x scale) along the finer axis (multiply by
 * a point's clip w for its footprint; w = 1 for parallel views).
 */
VTKRENDERINGCAUSTICS_EXPORT float PixelScale(const float worldToClip[16], int width, int height);

/** GL_MAX_TEXTURE_SIZE of the current context. */
VTKRENDERINGCAUSTICS_EXPORT int MaxTextureSize();

/** Sizes of the GL structs for indirect draws and dispatches, in 32-bit words. */
constexpr int DrawArraysCommandWords = 4;
constexpr int DrawElementsCommandWords = 5;
constexpr int DispatchCommandWords = 3;
}
}

#endif
