// Linked into every target of a sanitizer build (CAUSTICS_SANITIZE) only.
//
// Mesa unloads its DRI driver (dlclose) when a program closes its last display.
// What the driver still holds is then reachable only from its unmapped data, and
// LeakSanitizer reports it at exit from an unnamed module (or one misnamed after
// the nearest library) that no suppression can name: every test that opened a
// window failed with the same 240 bytes. Opening the driver once more with
// RTLD_NODELETE keeps it mapped until exit, as in a program that never closes its
// display, so its allocations stay reachable and the module's own leaks are still
// found. CAUSTICS_SANITIZE_GL_DRIVERS lists the drivers to keep (CMake finds
// Mesa's software driver, swrast_dri.so); one that is missing is skipped.
#include <dlfcn.h>

#include <initializer_list>

namespace
{
struct KeepGLDriverLoaded
{
  KeepGLDriverLoaded()
  {
    for (const char* path : { CAUSTICS_SANITIZE_GL_DRIVERS })
    {
      dlopen(path, RTLD_NOW | RTLD_NODELETE);
    }
  }
} keepGLDriverLoaded;
}
