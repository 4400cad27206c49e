// The built-in silver ring rendered with caustics via distance impostors
// (vtkCausticsImpostorPhotonPass, 256^2 light-buffer texels, otherwise default
// settings): the nephroid, whose photons leave the light's view after the
// reflection. Its caustic irradiance (first frame, FrameIndex 0, so the roulette is
// fixed) is compared with a baseline image, as TestCascadedPhotonPassBallLens does:
// 8-bit grey 255 sqrt(min(1, 0.3 E)) per channel (exposure 0.3 m^2/W, as the other
// ring images: the nephroid's cusp reaches 6 W/m^2), VTK's default threshold.
// The baseline was regenerated when the wall came to see itself (REFLECTOR_SURFACE
// of vtkCausticsDistanceImpostors): photons the inner wall sends to the wall again
// are reflected back inside instead of streaking the floor outside the ring (VTK's
// comparison passed the old baseline too, ImageError 0: 2009 of 65536 pixels differ
// by more than 40 of 255, under its per-pixel tolerance).
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsImpostorPhotonPass.h"

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

int TestImpostorPhotonPassRing(int argc, char* argv[])
{
  vtkNew<vtkOpenGLRenderer> renderer;
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName("ring");
  if (!scene->Populate(renderer))
  {
    std::cerr << scene->GetLastError() << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkCausticsImpostorPhotonPass> pass;
  pass->SetLightBufferResolution(256);
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
      const double value = 0.3 * std::max(0.0, irradiance->GetComponent(i, c));
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
