/**
 * Helpers shared by the TestHierarchicalCausticMap*.cxx and TestCausticMap*.cxx
 * tests: a window + renderer + vtkCausticsHierarchicalCausticMapPass on a built-in
 * scene, buffer read-back and image comparisons.
 */
#ifndef TestHierarchicalCausticMapUtilities_h
#define TestHierarchicalCausticMapUtilities_h

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsHierarchicalCausticMapPass.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <string>

namespace hcmtest
{
/** A built-in scene rendered through the hierarchical caustic map pass. */
struct Frame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsHierarchicalCausticMapPass> Pass;
  vtkNew<vtkCausticsBuiltinScene> Scene;

  explicit Frame(const char* scene = nullptr, int photons = 256, int size = 128)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
    this->Pass->SetLightBufferResolution(photons);
    this->Renderer->SetPass(this->Pass);
    if (scene)
    {
      this->Scene->SetSceneName(scene);
      this->Populated = this->Scene->Populate(this->Renderer);
    }
  }
  ~Frame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  void Render() { this->Window->Render(); }

  /** A buffer of the last frame (vtkCausticsRenderPass::ReadBuffer), empty on failure. */
  vtkSmartPointer<vtkImageData> Buffer(const char* name)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    if (!this->Pass->ReadBuffer(name, image))
    {
      return nullptr;
    }
    return image;
  }

  bool Populated = true;
};

inline vtkDataArray* Array(vtkImageData* image, const char* name = nullptr)
{
  return name ? image->GetPointData()->GetArray(name) : image->GetPointData()->GetArray(0);
}

/** Number of NaN or infinite values in every component of an array. */
inline vtkIdType NonFinite(vtkDataArray* array)
{
  vtkIdType count = 0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      count += std::isfinite(array->GetComponent(i, c)) ? 0 : 1;
    }
  }
  return count;
}

/** Relative L2 difference ||a - b|| / ||b|| over the first three components. */
inline double RelativeL2(vtkDataArray* a, vtkDataArray* b)
{
  double difference = 0.0, norm = 0.0;
  const int components = std::min(3, a->GetNumberOfComponents());
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const double d = a->GetComponent(i, c) - b->GetComponent(i, c);
      difference += d * d;
      norm += b->GetComponent(i, c) * b->GetComponent(i, c);
    }
  }
  return norm > 0.0 ? std::sqrt(difference / norm) : (difference > 0.0 ? 1.0 : 0.0);
}

/** Sum of the first three components of every tuple. */
inline double Total(vtkDataArray* array)
{
  double sum = 0.0;
  const int components = std::min(3, array->GetNumberOfComponents());
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      sum += array->GetComponent(i, c);
    }
  }
  return sum;
}
}

#endif
