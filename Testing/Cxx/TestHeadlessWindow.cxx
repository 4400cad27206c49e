// Without any display the factory still gives a working OpenGL 4.5 window
// (Mesa's surfaceless EGL here), and the caustics pass renders in it the same
// picture as under X.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsEGLRenderWindow.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsWindowFactory.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

namespace
{
/** Renders the ball lens in `window`; returns the final colour's RGB bytes. */
vtkSmartPointer<vtkUnsignedCharArray> RenderBallLens(vtkRenderWindow* window, std::string* error)
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->Populate(renderer);
  vtkNew<vtkCausticsRenderPass> pass;
  pass->KeepBuffersOn();
  renderer->SetPass(pass);
  window->SetSize(96, 96);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->Render();
  auto pixels = vtkSmartPointer<vtkUnsignedCharArray>::New();
  window->GetPixelData(0, 0, 95, 95, 0, pixels);
  vtkNew<vtkImageData> final;
  if (!pass->ReadBuffer("FinalColor", final))
  {
    *error = "no FinalColor buffer: the caustics stages did not run";
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  window->RemoveRenderer(renderer);
  return pixels;
}
}

TEST(HeadlessWindow, RendersWithoutADisplay)
{
  // Reference image under the X server ctest runs in (Xvfb).
  std::string how, error;
  auto x11 = vtkCausticsWindowFactory::Create(true, &how);
  ASSERT_TRUE(x11) << how;
  EXPECT_EQ(how, "x11");
  auto expected = RenderBallLens(x11, &error);
  EXPECT_TRUE(error.empty()) << error;
  // One thread, one current context: libglvnd will not switch GLX -> EGL implicitly.
  x11->ReleaseCurrent();

  const std::string display = std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "";
  unsetenv("DISPLAY");
  auto headless = vtkCausticsWindowFactory::Create(true, &how);
  if (!display.empty())
  {
    setenv("DISPLAY", display.c_str(), 1);
  }
  ASSERT_TRUE(headless) << how;
  EXPECT_EQ(how.rfind("egl-", 0), 0u) << how;
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(headless);
  auto actual = RenderBallLens(headless, &error);
  EXPECT_TRUE(error.empty()) << error;
  int major = 0, minor = 0;
  gl->GetOpenGLVersion(major, minor);
  EXPECT_GE(major * 10 + minor, 45);

  // Same Mesa rasterizer, same picture: allow one step of 8-bit rounding.
  ASSERT_EQ(actual->GetNumberOfValues(), expected->GetNumberOfValues());
  int differing = 0;
  for (vtkIdType i = 0; i < actual->GetNumberOfValues(); ++i)
  {
    differing += std::abs(int(actual->GetValue(i)) - int(expected->GetValue(i))) > 1 ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
}

TEST(HeadlessWindow, MakesItsContextOnTheFirstRender)
{
  // Used like any VTK window, without InitializeContext(): before, Render() drew
  // nothing and the read-back said "ReadPixels called before window is ready".
  vtkNew<vtkCausticsEGLRenderWindow> window;
  std::string error;
  auto pixels = RenderBallLens(window, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_STRNE(window->GetPlatformName(), "");
  int brightest = 0;
  for (vtkIdType i = 0; i < pixels->GetNumberOfValues(); ++i)
  {
    brightest = std::max(brightest, int(pixels->GetValue(i)));
  }
  EXPECT_GT(brightest, 100) << "the picture is black";
}

TEST(HeadlessWindow, ReportsWhyWhenNothingWorks)
{
  // No display and EGL switched off: no window, and a message saying what to do.
  const std::string display = std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "";
  unsetenv("DISPLAY");
  setenv("CAUSTICS_DISABLE_EGL", "1", 1);
  std::string how;
  auto window = vtkCausticsWindowFactory::Create(true, &how);
  unsetenv("CAUSTICS_DISABLE_EGL");
  if (!display.empty())
  {
    setenv("DISPLAY", display.c_str(), 1);
  }
  EXPECT_FALSE(window);
  EXPECT_NE(how.find("xvfb-run"), std::string::npos) << how;
  EXPECT_NE(how.find("CAUSTICS_DISABLE_EGL"), std::string::npos) << how;
}
