// A scene much larger than its reflectors and refractors (a far-away actor) makes
// every technique's caustics lose detail, since their resolution follows the
// whole scene's size (docs/reliability.md, "Far-away actors"). The frame must say
// so once, beyond the technique's measured limit, and stay quiet below it.
#include "TestTechniqueFrame.h"

#include "vtkActor.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

class SceneScale : public testing::TestWithParam<std::string>
{
};

INSTANTIATE_TEST_SUITE_P(EveryTechnique, SceneScale, testing::Values("screen-space", "caustic-maps"),
  [](const testing::TestParamInfo<std::string>& info)
  { return info.param == "screen-space" ? std::string("ScreenSpace") : std::string("CausticMaps"); });

TEST_P(SceneScale, FarAwayActorIsReported)
{
  TechniqueFrame f(GetParam(), 64, 64);
  vtkCausticsRenderPass* pass = f.Pass;
  vtkRenderWindow* window = f.Window;
  vtkRenderer* renderer = f.Renderer;
  vtkNew<vtkTest::ErrorObserver> warnings;
  pass->GlobalWarningDisplayOn();
  pass->AddObserver(vtkCommand::WarningEvent, warnings);

  window->Render();
  // The ball lens: a 12 m floor under a 2 m ball, 17.4 / 3.46 = 5.
  EXPECT_NEAR(pass->GetLastSceneScaleRatio(), 5.0, 0.1);
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();

  // A 1 m cube this far along x puts the scene at twice the technique's limit.
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> far;
  far->SetMapper(mapper);
  const double limit = GetParam() == "screen-space" ? 500.0 : 20.0;
  far->SetPosition(2.0 * limit * 2.0 * std::sqrt(3.0), 0.0, 0.0);
  renderer->AddActor(far);
  window->Render();
  EXPECT_GT(pass->GetLastSceneScaleRatio(), 1.9 * limit);
  EXPECT_NE(warnings->GetWarningMessage().find("times the size of its reflectors"),
    std::string::npos)
    << warnings->GetWarningMessage();
  warnings->Clear();
  window->Render(); // the same scene: said once
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  EXPECT_EQ(vtkCausticsTechniques::GetBestNameFor(renderer), "screen-space");
}
