// What an application does with the installed caustics modules: a built-in scene
// (its data found from the installed library), the registry's default technique
// rendering one small frame in the window the factory picks, the CPU reference on
// the same scene, and an EXR written and read back. Prints "consumer: ok" at the end.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsImageIO.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsWindowFactory.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <iostream>
#include <string>

namespace
{
int Fail(const std::string& message)
{
  std::cerr << "consumer: " << message << std::endl;
  return 1;
}

/** The largest first component of `array` (-1 when there is none). */
double Peak(vtkDataArray* array)
{
  double peak = -1.0;
  for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
  {
    peak = std::max(peak, array->GetComponent(i, 0));
  }
  return peak;
}
}

int main(int argc, char* argv[])
{
  const std::string output = argc > 1 ? argv[1] : "consumer";

  // The bunny reads bunny.ply from <prefix>/share/vtkcaustics/data.
  vtkNew<vtkOpenGLRenderer> bunny;
  vtkNew<vtkCausticsBuiltinScene> bunnyScene;
  bunnyScene->SetSceneName("bunny");
  if (!bunnyScene->Populate(bunny))
  {
    return Fail(std::string("the bunny scene finds no data: ") + bunnyScene->GetLastError());
  }

  std::string how;
  vtkSmartPointer<vtkRenderWindow> window = vtkCausticsWindowFactory::Create(true, &how);
  if (!window)
  {
    return Fail("no window: " + how);
  }
  window->SetMultiSamples(0);
  window->SetSize(64, 64);
  vtkNew<vtkOpenGLRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName("ball-lens");
  if (!scene->Populate(renderer))
  {
    return Fail(scene->GetLastError());
  }

  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create("best");
  pass->KeepBuffersOn();
  pass->SetLightBufferResolution(64);
  renderer->SetPass(pass);
  window->Render();
  vtkNew<vtkImageData> caustic;
  const bool read = pass->ReadBuffer("CausticIrradiance", caustic);
  const double gpuPeak = read ? Peak(caustic->GetPointData()->GetArray(0)) : -1.0;
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  if (!(gpuPeak > 0.0))
  {
    return Fail("the " + vtkCausticsTechniques::GetBestName() + " pass made no caustic");
  }

  vtkNew<vtkCausticsReferenceRenderer> reference;
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(32, 32);
  reference->SetPhotonsPerLight(20000);
  reference->UseCacheOff();
  const bool referenceOk = reference->Update();
  vtkDataArray* truth =
    referenceOk ? reference->GetOutput()->GetPointData()->GetArray("CausticIrradiance") : nullptr;
  if (!(Peak(truth) > 0.0))
  {
    return Fail(std::string("the reference made no caustic: ") + reference->GetLastError());
  }

  std::string error;
  const std::string exr = output + ".exr";
  if (!vtkCausticsImageIO::WriteEXR(
        reference->GetOutput(), { { "CausticIrradiance", "caustic" } }, exr, &error))
  {
    return Fail(error);
  }
  vtkSmartPointer<vtkImageData> back = vtkCausticsImageIO::ReadEXR(exr, &error);
  if (!back || Peak(back->GetPointData()->GetArray("caustic")) != Peak(truth))
  {
    return Fail("the EXR did not read back: " + error);
  }

  std::cout << "consumer: ok (window " << how << ", technique " << vtkCausticsTechniques::GetBestName()
            << ", GPU caustic peak " << gpuPeak << " W/m^2, reference peak "
            << Peak(truth) << " W/m^2)" << std::endl;
  return 0;
}
