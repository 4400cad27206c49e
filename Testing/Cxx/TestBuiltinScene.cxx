// Base rendering of a built-in scene through vtkCausticsRenderPass, compared with
// a baseline image. The scene name comes from the command line (-scene <name>),
// so one source serves the four regression tests registered in CMakeLists.txt.
//
// Threshold: VTK's default (0.15 with 9.1's vtkImageDifference metric). The image
// is deterministic on one machine; the margin absorbs rasterization differences
// between Mesa versions and GPUs at silhouette pixels.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTimings.h"

#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

#include <cstring>
#include <iostream>
#include <string>

int TestBuiltinScene(int argc, char* argv[])
{
  std::string sceneName = "ball-lens";
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "-scene") == 0)
    {
      sceneName = argv[i + 1];
    }
  }
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName(sceneName.c_str());
  if (!scene->Populate(renderer))
  {
    std::cerr << scene->GetLastError() << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkCausticsRenderPass> pass;
  pass->KeepBuffersOn(); // exercise the buffer path even without a technique
  renderer->SetPass(pass);

  vtkNew<vtkRenderWindow> window;
  window->SetMultiSamples(0);
  window->SetSize(256, 256);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  window->Render();

  int retVal = vtkRegressionTestImage(window);
  if (retVal == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return !retVal;
}
