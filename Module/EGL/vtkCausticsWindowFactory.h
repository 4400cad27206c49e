/**
 * @class   vtkCausticsWindowFactory
 * @brief   The right render window for this machine: a display, VTK's EGL, or headless EGL.
 *
 * The same binaries run on a desktop with a GPU, on a GPU server without a display
 * and on a CI machine with neither:
 * 1. a VTK built with EGL support (VTK_OPENGL_HAS_EGL): VTK's own window;
 * 2. a DISPLAY (an X server, or Xvfb): VTK's GLX window, off-screen on request;
 * 3. no display: vtkCausticsEGLRenderWindow (Mesa surfaceless or an EGL device),
 *    unless the environment variable CAUSTICS_DISABLE_EGL is set (to anything but 0);
 * 4. none of these: nullptr and a message saying to run under xvfb-run.
 *
 * From C++, call the static Create(). From Python (or any wrapped language), call
 * NewWindow() on an instance, which keeps the path taken and the reason for a failure:
 * @code{.py}
 * factory = vtkCausticsWindowFactory()
 * window = factory.NewWindow(True)  # None when nothing works: factory.GetLastError()
 * @endcode
 */
#ifndef vtkCausticsWindowFactory_h
#define vtkCausticsWindowFactory_h

#include "vtkObject.h"
#include "vtkRenderingCausticsEGLModule.h" // For export macro
#include "vtkSmartPointer.h"            // For return value

#include <string> // For std::string and members

class vtkRenderWindow;

class VTKRENDERINGCAUSTICSEGL_EXPORT vtkCausticsWindowFactory : public vtkObject
{
public:
  static vtkCausticsWindowFactory* New();
  vtkTypeMacro(vtkCausticsWindowFactory, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Makes a window (off-screen when `offScreen`). `how` receives which path was
   * taken ("vtk-egl", "x11", "egl-surfaceless", "egl-device") or, on failure, why.
   */
  static vtkSmartPointer<vtkRenderWindow> Create(bool offScreen, std::string* how = nullptr);
#endif

  /**
   * The same choice as Create(), for wrapped languages: a new window the caller owns
   * (Python does this itself), or nullptr. Sets GetLastPath() or GetLastError().
   */
  VTK_NEWINSTANCE vtkRenderWindow* NewWindow(bool offScreen);

  /** The path the last NewWindow() took ("x11", "egl-surfaceless", ...); empty after a failure. */
  const char* GetLastPath() const { return this->LastPath.c_str(); }

  /** Why the last NewWindow() made no window; empty after a success. */
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkCausticsWindowFactory() = default;
  ~vtkCausticsWindowFactory() override = default;

  std::string LastPath;
  std::string LastError;

private:
  vtkCausticsWindowFactory(const vtkCausticsWindowFactory&) = delete;
  void operator=(const vtkCausticsWindowFactory&) = delete;
};

#endif
