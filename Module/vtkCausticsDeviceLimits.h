/**
 * @file   vtkCausticsDeviceLimits.h
 * @brief  What the current OpenGL context can hold, for checks before allocating (not wrapped).
 *
 * A photon grid too large for the context does not fail loudly in OpenGL: a shader
 * storage buffer larger than GL_MAX_SHADER_STORAGE_BLOCK_SIZE is only partly
 * visible to the shaders (the caustic silently vanishes), and one larger than the
 * memory swaps a software renderer for minutes. The passes compare what a
 * technique needs (vtkCausticsRenderPass::CheckResources) with these limits first.
 * Internal: not installed.
 */
#ifndef vtkCausticsDeviceLimits_h
#define vtkCausticsDeviceLimits_h

#include <string> // For std::string

class vtkRenderWindow;

namespace caustics
{
namespace gl
{
struct DeviceLimits
{
  double MaximumStorageBlockBytes = 0.0; ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  int MaximumTextureSize = 0;            ///< GL_MAX_TEXTURE_SIZE
  double MemoryBudgetBytes = 0.0;        ///< 0: unknown, no limit
  std::string MemorySource;              ///< where the budget comes from, for messages
};

/**
 * The limits of the current context. The memory budget is `requested` when > 0;
 * otherwise what the driver reports (GL_NVX_gpu_memory_info, GL_ATI_meminfo), or,
 * for a software renderer (llvmpipe, softpipe), half of the machine's physical
 * memory, which is where its buffers live; else 0 (no limit).
 */
DeviceLimits QueryDeviceLimits(double requested);

/**
 * True when `window` is an OpenGL window whose context is a software renderer
 * (llvmpipe, softpipe, SWR: no GPU). Makes the window's context (Initialize) if it
 * has none yet, as CheckResources() does; false for no window.
 */
bool IsSoftwareOpenGL(vtkRenderWindow* window);

/** Bytes as "1.61 GB" / "134 MB" / "512 kB" (decimal units). */
std::string FormatBytes(double bytes);
}
}

#endif
