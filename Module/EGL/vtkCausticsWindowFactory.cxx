#include "vtkCausticsWindowFactory.h"

#include "vtkCausticsEGLRenderWindow.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderingOpenGLConfigure.h"
#include "vtksys/SystemTools.hxx"

vtkStandardNewMacro(vtkCausticsWindowFactory);

void vtkCausticsWindowFactory::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LastPath: " << this->LastPath << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
#ifdef VTK_OPENGL_HAS_EGL
  os << indent << "VTK has EGL: yes\n";
#else
  os << indent << "VTK has EGL: no (headless rendering through vtkCausticsEGLRenderWindow)\n";
#endif
}

vtkSmartPointer<vtkRenderWindow> vtkCausticsWindowFactory::Create(bool offScreen, std::string* how)
{
  auto report = [how](const std::string& text)
  {
    if (how)
    {
      *how = text;
    }
  };
#ifdef VTK_OPENGL_HAS_EGL
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(offScreen ? 1 : 0);
  report("vtk-egl");
  return window;
#else
  const char* display = vtksys::SystemTools::GetEnv("DISPLAY");
  if (display && *display)
  {
    auto window = vtkSmartPointer<vtkRenderWindow>::New();
    window->SetOffScreenRendering(offScreen ? 1 : 0);
    report("x11");
    return window;
  }
  std::string reason = "disabled by CAUSTICS_DISABLE_EGL";
  const char* disable = vtksys::SystemTools::GetEnv("CAUSTICS_DISABLE_EGL");
  const bool eglAllowed = !disable || !*disable || std::string(disable) == "0";
  if (eglAllowed && vtkCausticsEGLRenderWindow::IsAvailable(&reason))
  {
    auto window = vtkSmartPointer<vtkCausticsEGLRenderWindow>::New();
    if (window->InitializeContext())
    {
      report(std::string("egl-") + window->GetPlatformName());
      return window;
    }
    reason = window->GetLastError();
  }
  report("no display (DISPLAY is not set) and no headless EGL context (" + reason +
    "); run under xvfb-run -a");
  return nullptr;
#endif
}

vtkRenderWindow* vtkCausticsWindowFactory::NewWindow(bool offScreen)
{
  std::string how;
  vtkSmartPointer<vtkRenderWindow> window = vtkCausticsWindowFactory::Create(offScreen, &how);
  this->LastPath = window ? how : std::string();
  this->LastError = window ? std::string() : how;
  if (window)
  {
    window->Register(nullptr); // the reference handed to the caller
  }
  return window;
}
