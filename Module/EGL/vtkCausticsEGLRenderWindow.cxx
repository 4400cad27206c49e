#include "vtkCausticsEGLRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>

vtkStandardNewMacro(vtkCausticsEGLRenderWindow);

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

struct vtkCausticsEGLRenderWindow::Internals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext Context = EGL_NO_CONTEXT;
  std::string Platform;
  std::string Error;

  bool Create()
  {
    if (this->Context != EGL_NO_CONTEXT)
    {
      return true;
    }
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay)
    {
      this->Error = "EGL has no eglGetPlatformDisplayEXT (EGL_EXT_platform_base)";
      return false;
    }
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const std::string extensions = clientExtensions ? clientExtensions : "";
    // 1. Mesa's surfaceless platform.
    if (extensions.find("EGL_MESA_platform_surfaceless") != std::string::npos)
    {
      this->TryDisplay(
        getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
        "surfaceless");
    }
    // 2. The first EGL device (NVIDIA).
    if (this->Context == EGL_NO_CONTEXT &&
      extensions.find("EGL_EXT_platform_device") != std::string::npos)
    {
      auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLDeviceEXT devices[8];
      EGLint count = 0;
      if (queryDevices && queryDevices(8, devices, &count))
      {
        for (EGLint i = 0; i < count && this->Context == EGL_NO_CONTEXT; ++i)
        {
          this->TryDisplay(
            getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device");
        }
      }
    }
    if (this->Context == EGL_NO_CONTEXT && this->Error.empty())
    {
      this->Error = "no EGL platform gave a desktop OpenGL context (need "
                    "EGL_MESA_platform_surfaceless or EGL_EXT_platform_device)";
    }
    return this->Context != EGL_NO_CONTEXT;
  }

  void TryDisplay(EGLDisplay display, const char* platform)
  {
    if (display == EGL_NO_DISPLAY)
    {
      return;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
    {
      return;
    }
    const char* displayExtensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!displayExtensions || !std::strstr(displayExtensions, "EGL_KHR_surfaceless_context") ||
      !eglBindAPI(EGL_OPENGL_API))
    {
      eglTerminate(display);
      return;
    }
    // Mesa's surfaceless platform lists no configs; with no surface none is
    // needed (EGL_KHR_no_config_context).
    const EGLint configAttributes[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &configs) || configs < 1)
    {
      if (!std::strstr(displayExtensions, "EGL_KHR_no_config_context"))
      {
        eglTerminate(display);
        return;
      }
      config = static_cast<EGLConfig>(nullptr); // EGL_NO_CONFIG_KHR
    }
    // The caustics stages want 4.5; VTK itself needs 3.2.
    const EGLint versions[2][2] = { { 4, 5 }, { 3, 2 } };
    for (const auto& version : versions)
    {
      const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, version[0],
        EGL_CONTEXT_MINOR_VERSION, version[1], EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
      EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
      if (context != EGL_NO_CONTEXT)
      {
        this->Display = display;
        this->Context = context;
        this->Platform = platform;
        return;
      }
    }
    eglTerminate(display);
  }

  void Destroy()
  {
    if (this->Display != EGL_NO_DISPLAY)
    {
      eglMakeCurrent(this->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (this->Context != EGL_NO_CONTEXT)
      {
        eglDestroyContext(this->Display, this->Context);
      }
      eglTerminate(this->Display);
    }
    this->Display = EGL_NO_DISPLAY;
    this->Context = EGL_NO_CONTEXT;
  }
};

vtkCausticsEGLRenderWindow::vtkCausticsEGLRenderWindow()
  : Internal(new Internals)
{
  this->SetOwnContext(0);
  this->SetOffScreenRendering(1);
  this->SetReadyForRendering(false);
}

vtkCausticsEGLRenderWindow::~vtkCausticsEGLRenderWindow()
{
  this->Finalize();
  this->Internal->Destroy();
}

bool vtkCausticsEGLRenderWindow::IsAvailable(std::string* reason)
{
  Internals probe;
  const bool ok = probe.Create();
  if (reason)
  {
    *reason = ok ? probe.Platform : probe.Error;
  }
  probe.Destroy();
  return ok;
}

bool vtkCausticsEGLRenderWindow::InitializeContext()
{
  if (!this->Internal->Create())
  {
    vtkErrorMacro(<< "headless EGL context: " << this->Internal->Error);
    return false;
  }
  this->MakeCurrent();
  this->SetReadyForRendering(true);
  return true;
}

void vtkCausticsEGLRenderWindow::Render()
{
  // vtkGenericOpenGLRenderWindow renders nothing until it is ready, and would say
  // so only at the read-back ("ReadPixels called before window is ready").
  if (!this->GetReadyForRendering() && !this->InitializeContext())
  {
    return;
  }
  this->Superclass::Render();
}

void vtkCausticsEGLRenderWindow::Initialize()
{
  if (this->InitializeContext())
  {
    this->Superclass::Initialize();
    // Load the GL entry points now, not at the first Render(): a caller may query
    // the context before it renders (vtkCausticsRenderPass::CheckResources does).
    this->OpenGLInit();
  }
}

const char* vtkCausticsEGLRenderWindow::GetLastError() const
{
  return this->Internal->Error.c_str();
}

const char* vtkCausticsEGLRenderWindow::GetPlatformName() const
{
  return this->Internal->Platform.c_str();
}

void vtkCausticsEGLRenderWindow::MakeCurrent()
{
  if (this->Internal->Context == EGL_NO_CONTEXT && !this->Internal->Create())
  {
    return;
  }
  if (eglGetCurrentContext() != this->Internal->Context &&
    !eglMakeCurrent(
      this->Internal->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, this->Internal->Context))
  {
    // libglvnd refuses while another window system's (GLX) context is current.
    vtkErrorMacro(<< "cannot make the headless EGL context current (EGL error 0x" << std::hex
                  << eglGetError() << std::dec
                  << "); if another window's GLX context is current on this thread, call "
                     "its ReleaseCurrent() first");
  }
}

bool vtkCausticsEGLRenderWindow::IsCurrent()
{
  return this->Internal->Context != EGL_NO_CONTEXT &&
    eglGetCurrentContext() == this->Internal->Context;
}

void vtkCausticsEGLRenderWindow::ReleaseCurrent()
{
  if (this->Internal->Display != EGL_NO_DISPLAY)
  {
    eglMakeCurrent(this->Internal->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

void vtkCausticsEGLRenderWindow::Finalize()
{
  if (this->Internal->Context != EGL_NO_CONTEXT && this->Initialized)
  {
    this->MakeCurrent();
    this->ReleaseGraphicsResources(this);
  }
  this->Initialized = false;
}

void vtkCausticsEGLRenderWindow::Frame()
{
  // Nothing to present: the image stays in VTK's framebuffers for read-back.
  this->Superclass::Frame();
}

int vtkCausticsEGLRenderWindow::SupportsOpenGL()
{
  return this->Internal->Create() ? 1 : 0;
}

void vtkCausticsEGLRenderWindow::SetSize(int width, int height)
{
  this->Superclass::SetSize(width, height);
}

void vtkCausticsEGLRenderWindow::OpenGLInitContext()
{
  this->ContextCreationTime.Modified();
  if (this->Initialized)
  {
    return;
  }
  const GLenum result = glewInit();
  // GLEW built for GLX loads the GL entry points, then fails to find an X
  // display; with EGL that error is expected and harmless.
  const bool loaded =
    result == GLEW_OK || (result == GLEW_ERROR_NO_GLX_DISPLAY && GLEW_VERSION_3_2);
  if (!loaded)
  {
    vtkErrorMacro(<< "GLEW could not load OpenGL through EGL: "
                  << reinterpret_cast<const char*>(glewGetErrorString(result)));
    return;
  }
  this->Initialized = true;
  GLfloat lineWidthRange[2] = { 1.0f, 1.0f };
  glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, lineWidthRange);
  this->MaximumHardwareLineWidth = glGetError() == GL_NO_ERROR ? lineWidthRange[1] : 1.0f;
}

void vtkCausticsEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "Platform: " << (this->Internal->Platform.empty() ? "(none)" : this->Internal->Platform)
     << "\n";
  os << indent << "LastError: " << this->Internal->Error << "\n";
}
