// The built-in ball lens rendered with cascaded image-space photon tracing
// (vtkCausticsCascadedPhotonPass, default settings: 65536 photons from 256^2
// light-buffer texels); its caustic irradiance (first frame, FrameIndex 0, so the
// sample set is fixed) is compared with a baseline image, as TestCausticMapScene
// does: 8-bit grey 255 sqrt(min(1, E)) per channel (exposure 1 m^2/W), VTK's
// default threshold.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"

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
#include <iostream>

int TestCascadedPhotonPassBallLens(int argc, char* argv[])
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName("ball-lens");
  if (!scene->Populate(renderer))
  {
    std::cerr << scene->GetLastError() << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkCausticsCascadedPhotonPass> pass;
  pass->DenoiseOff(); // the raw estimate of one frame, as the baseline holds it
  renderer->SetPass(pass);
  vtkNew<vtkRenderWindow> window;
  window->SetMultiSamples(0);
  window->SetSize(256, 256);
  window->AddRenderer(renderer);
  window->Render();
  vtkNew<vtkImageData> caustic;
  const bool read =
    pass->GetLastFrameHadCaustics() && pass->ReadBuffer("CausticIrradiance", caustic);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  if (!read)
  {
    std::cerr << "the frame made no caustics\n";
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
      const double value = std::max(0.0, irradiance->GetComponent(i, c));
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
