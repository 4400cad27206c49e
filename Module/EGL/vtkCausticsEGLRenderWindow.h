/**
 * @class   vtkCausticsEGLRenderWindow
 * @brief   Headless OpenGL 4.5 core context through EGL, for VTK builds made for GLX.
 *
 * Debian's VTK 9.1 is built for GLX only (no vtkEGLRenderWindow), so without an X
 * server it cannot render. This window makes its own EGL context and lets VTK
 * render into it:
 * 1. an EGL display from Mesa's surfaceless platform (EGL_PLATFORM_SURFACELESS_MESA,
 *    llvmpipe or any Mesa driver) or, failing that, the first EGL device
 *    (EGL_PLATFORM_DEVICE_EXT: NVIDIA's headless path);
 * 2. a desktop OpenGL core context (4.5, else 3.2) made current without a surface
 *    (EGL_KHR_surfaceless_context); VTK renders into its own framebuffer objects;
 * 3. VTK's GLEW is GLX-flavoured: glewInit() loads every GL entry point, then fails
 *    with GLEW_ERROR_NO_GLX_DISPLAY because there is no X display. OpenGLInitContext
 *    accepts exactly that error when GL >= 3.2 was loaded, and nothing else.
 * The context is made on the first Render() (or Initialize(), or InitializeContext()),
 * so the window is used like any other, from C++ or Python.
 * Use IsAvailable() to probe; vtkCausticsWindowFactory picks this window when no
 * display exists. VTK builds with EGL support do not need it.
 */
#ifndef vtkCausticsEGLRenderWindow_h
#define vtkCausticsEGLRenderWindow_h

#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkRenderingCausticsEGLModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class VTKRENDERINGCAUSTICSEGL_EXPORT vtkCausticsEGLRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkCausticsEGLRenderWindow* New();
  vtkTypeMacro(vtkCausticsEGLRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Creates the EGL context if needed; false (see GetLastError()) if EGL cannot give one. */
  bool InitializeContext();

  /** True if a headless EGL OpenGL context can be created on this machine. */
  static bool IsAvailable(std::string* reason = nullptr);

  /** Why the context could not be created, empty otherwise. */
  const char* GetLastError() const;
  /** "surfaceless" or "device" once initialized. */
  const char* GetPlatformName() const;

  /**
   * Creates the EGL context on the first call, then renders. Without a context it
   * draws nothing and reports why (vtkErrorMacro; GetLastError()).
   */
  void Render() override;

  void Initialize() override;
  void MakeCurrent() override;
  bool IsCurrent() override;
  void ReleaseCurrent() override;
  void Finalize() override;
  void Frame() override;
  void OpenGLInitContext() override;
  int SupportsOpenGL() override;
  void SetSize(int width, int height) override;
  void SetSize(int a[2]) override { this->SetSize(a[0], a[1]); }

protected:
  vtkCausticsEGLRenderWindow();
  ~vtkCausticsEGLRenderWindow() override;

private:
  vtkCausticsEGLRenderWindow(const vtkCausticsEGLRenderWindow&) = delete;
  void operator=(const vtkCausticsEGLRenderWindow&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
