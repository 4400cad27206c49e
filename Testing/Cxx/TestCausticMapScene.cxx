// A built-in scene rendered with hierarchical caustic maps
// (vtkCausticsHierarchicalCausticMapPass, default settings, 512^2 photons per
// light); its caustic irradiance is compared with a baseline image. The scene and
// the exposure come from the command line (-scene <name> -exposure <1/(W/m^2)>):
// one source serves the ball-lens, ring and bunny tests of CMakeLists.txt.
//
// The compared image is the caustic irradiance E (W/m^2, the technique's whole
// output), 8-bit grey 255 sqrt(min(1, E x exposure)) per channel, not the final
// composite: there VTK's own lighting already saturates the lit floor, and a
// missing caustic would go unnoticed (vtkImageDifference's per-pixel threshold).
// The fixed exposure keeps flux regressions visible (no normalization).
//
// Threshold: VTK's default (0.15 with 9.1's vtkImageDifference metric), as the
// scene tests of the shared frame use. The caustics are deterministic on one
// machine (no random numbers; the GPU's atomic appends reorder splats, which
// changes float sums in the last bits only); the margin absorbs rasterization
// differences between Mesa versions and GPUs at silhouettes and splat edges.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkTesting.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

int TestCausticMapScene(int argc, char* argv[])
{
  std::string sceneName = "ball-lens";
  double exposure = 1.0;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "-scene") == 0)
    {
      sceneName = argv[i + 1];
    }
    if (std::strcmp(argv[i], "-exposure") == 0)
    {
      exposure = std::atof(argv[i + 1]);
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
  vtkNew<vtkCausticsHierarchicalCausticMapPass> pass;
  pass->SetLightBufferResolution(512);
  renderer->SetPass(pass);

  vtkNew<vtkRenderWindow> window;
  window->SetMultiSamples(0);
  window->SetSize(256, 256);
  window->AddRenderer(renderer);
  window->Render();
  if (!pass->GetLastFrameHadCaustics())
  {
    std::cerr << "the frame made no caustics\n";
    renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(window);
    return EXIT_FAILURE;
  }

  vtkNew<vtkImageData> caustic;
  const bool read = pass->ReadBuffer("CausticIrradiance", caustic);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  if (!read)
  {
    return EXIT_FAILURE;
  }
  vtkDataArray* irradiance = caustic->GetPointData()->GetArray(0);
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(caustic->GetDimensions());
  vtkNew<vtkUnsignedCharArray> grey;
  grey->SetName("CausticIrradiance");
  grey->SetNumberOfComponents(3);
  grey->SetNumberOfTuples(irradiance->GetNumberOfTuples());
  for (vtkIdType i = 0; i < irradiance->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double value = std::max(0.0, irradiance->GetComponent(i, c) * exposure);
      grey->SetValue(3 * i + c,
        static_cast<unsigned char>(std::lround(255.0 * std::sqrt(std::min(1.0, value)))));
    }
  }
  picture->GetPointData()->SetScalars(grey);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(picture);
  vtkNew<vtkTesting> testing;
  testing->AddArguments(argc, argv);
  return testing->RegressionTest(producer, 0.15) == vtkTesting::PASSED ? EXIT_SUCCESS
                                                                       : EXIT_FAILURE;
}
