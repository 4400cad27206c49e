#include "vtkCausticsDeviceLimits.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <cstdio>
#include <cstring>
#include <unistd.h> // sysconf

namespace caustics
{
namespace gl
{
namespace
{
bool HasExtension(const char* name)
{
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
  {
    const char* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i));
    if (extension && std::strcmp(extension, name) == 0)
    {
      return true;
    }
  }
  return false;
}

bool IsSoftwareRenderer()
{
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer &&
    (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe") ||
      std::strstr(renderer, "SWR"));
}

double PhysicalMemoryBytes()
{
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize)
                                   : 0.0;
}
}

DeviceLimits QueryDeviceLimits(double requested)
{
  DeviceLimits limits;
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  limits.MaximumStorageBlockBytes = static_cast<double>(block);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits.MaximumTextureSize);
  if (requested > 0.0)
  {
    limits.MemoryBudgetBytes = requested;
    limits.MemorySource = "MaximumGPUMemory";
  }
  else if (HasExtension("GL_NVX_gpu_memory_info"))
  {
    GLint kilobytes = 0;
    glGetIntegerv(0x9048, &kilobytes); // GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX
    limits.MemoryBudgetBytes = 1024.0 * kilobytes;
    limits.MemorySource = "the GPU's memory";
  }
  else if (HasExtension("GL_ATI_meminfo"))
  {
    GLint info[4] = { 0, 0, 0, 0 };
    glGetIntegerv(0x87FC, info); // TEXTURE_FREE_MEMORY_ATI: free kB first
    limits.MemoryBudgetBytes = 1024.0 * info[0];
    limits.MemorySource = "the GPU's free memory";
  }
  else if (IsSoftwareRenderer())
  {
    limits.MemoryBudgetBytes = 0.5 * PhysicalMemoryBytes();
    limits.MemorySource = "half the physical memory (software OpenGL)";
  }
  return limits;
}

bool IsSoftwareOpenGL(vtkRenderWindow* window)
{
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin)
  {
    return false;
  }
  renWin->Initialize(); // makes the context if the window has none yet
  renWin->MakeCurrent();
  return IsSoftwareRenderer();
}

std::string FormatBytes(double bytes)
{
  const char* units[] = { "B", "kB", "MB", "GB", "TB" };
  int unit = 0;
  while (bytes >= 1000.0 && unit < 4)
  {
    bytes /= 1000.0;
    ++unit;
  }
  char text[32];
  std::snprintf(
    text, sizeof(text), bytes < 10.0 && unit > 0 ? "%.2f %s" : "%.0f %s", bytes, units[unit]);
  return text;
}
}
}
