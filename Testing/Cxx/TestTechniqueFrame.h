// A built-in scene rendered off-screen by one registered technique: the window,
// renderer and pass the small GPU tests share (TestSpecularShadows,
// TestSceneScale, TestFrameProgress, TestPhotonStatistics). The pass's resources are released with
// it.
#ifndef TestTechniqueFrame_h
#define TestTechniqueFrame_h

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <string>

struct TechniqueFrame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  vtkSmartPointer<vtkCausticsRenderPass> Pass;

  /** The ball lens (index of refraction `ior`, 0: the scene's own) by `technique`. */
  TechniqueFrame(const std::string& technique, int size, int photons, double ior = 0.0)
  {
    if (ior > 0.0)
    {
      this->Scene->SetRefractiveIndex(ior);
    }
    EXPECT_TRUE(this->Scene->Populate(this->Renderer));
    this->Pass = vtkCausticsTechniques::Create(technique);
    this->Pass->SetLightBufferResolution(photons);
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
  }
  ~TechniqueFrame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  TechniqueFrame(const TechniqueFrame&) = delete;
  TechniqueFrame& operator=(const TechniqueFrame&) = delete;

  /** Renders a frame and reads one of its buffers (KeepBuffers on); nullptr if it has none. */
  vtkSmartPointer<vtkImageData> Render(const char* buffer)
  {
    this->Window->Render();
    auto image = vtkSmartPointer<vtkImageData>::New();
    return this->Pass->ReadBuffer(buffer, image) ? image : nullptr;
  }
};

#endif
