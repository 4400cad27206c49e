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
 */
#ifndef vtkCausticsWindowFactory_h
#define vtkCausticsWindowFactory_h

#include "vtkObject.h"
#include "vtkRenderingCausticsEGLModule.h" // For export macro
#include "vtkSmartPointer.h"            // For return value

#include <string> // For std::string

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

protected:
  vtkCausticsWindowFactory() = default;
  ~vtkCausticsWindowFactory() override = default;

private:
  vtkCausticsWindowFactory(const vtkCausticsWindowFactory&) = delete;
  void operator=(const vtkCausticsWindowFactory&) = delete;
};

#endif
