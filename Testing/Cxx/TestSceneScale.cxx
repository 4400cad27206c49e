// A far-away actor used to take the caustic away: both techniques sized their
// resolution by the whole scene. They now size it by the part the camera sees
// (caustics::VisibleBounds), so an actor out of view changes nothing, and a view
// much larger than the reflectors and refractors still loses the caustic's detail:
// the frame must say so once, beyond the technique's measured limit
// (docs/reliability.md, "Far-away actors").
#include "TestTechniqueFrame.h"

#include "vtkActor.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

class SceneScale : public testing::TestWithParam<std::string>
{
};

namespace
{
/** The largest caustic irradiance (W/m^2, any channel) of the pass's last frame. */
double Peak(vtkCausticsRenderPass* pass)
{
  vtkNew<vtkImageData> image;
  if (!pass->ReadBuffer("CausticIrradiance", image))
  {
    return -1.0;
  }
  vtkDataArray* values = image->GetPointData()->GetArray(0);
  double peak = 0.0;
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    peak = std::max(peak, values->GetVariantValue(i).ToDouble());
  }
  return peak;
}
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, SceneScale, testing::Values("screen-space", "caustic-maps"),
  [](const testing::TestParamInfo<std::string>& info)
  { return info.param == "screen-space" ? std::string("ScreenSpace") : std::string("CausticMaps"); });

TEST_P(SceneScale, FarAwayActorIsIgnoredUntilSeen)
{
  TechniqueFrame f(GetParam(), 64, 64);
  vtkCausticsRenderPass* pass = f.Pass;
  vtkRenderWindow* window = f.Window;
  vtkRenderer* renderer = f.Renderer;
  vtkNew<vtkTest::ErrorObserver> warnings;
  pass->GlobalWarningDisplayOn();
  pass->AddObserver(vtkCommand::WarningEvent, warnings);
  pass->KeepBuffersOn();

  window->Render();
  // The ball lens: the part of the 12 m floor the camera sees, with the 2 m ball,
  // over the ball's 3.46 m diagonal: 4.38 (the whole scene: 17.4 / 3.46 = 5.0).
  const double seen = pass->GetLastSceneScaleRatio();
  EXPECT_NEAR(seen, 4.38, 0.01);
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  const double peak = Peak(pass);
  ASSERT_GT(peak, 0.0);

  // A 1 m cube at twice the technique's limit along x, out of the camera's view:
  // the caustic is computed over what the camera sees, so nothing changes. (Over
  // the whole scene, caustic maps lost 88 % of the peak and screen-space all of it.)
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> far;
  far->SetMapper(mapper);
  const double limit = GetParam() == "screen-space" ? 500.0 : 20.0;
  far->SetPosition(2.0 * limit * 2.0 * std::sqrt(3.0), 0.0, 0.0);
  renderer->AddActor(far);
  window->Render();
  // VTK moves the far clipping plane out to the cube, which shows a little more
  // of the floor towards the horizon (4.38 to 4.44).
  EXPECT_NEAR(pass->GetLastSceneScaleRatio(), seen, 0.02 * seen);
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  EXPECT_NEAR(Peak(pass) / peak, 1.0, 0.02);
  EXPECT_EQ(vtkCausticsTechniques::GetBestNameFor(renderer), "caustic-maps");

  // The camera pulled back to show the cube too: now the view is beyond the limit,
  // and the frame says so, once.
  renderer->ResetCamera();
  window->Render();
  EXPECT_GT(pass->GetLastSceneScaleRatio(), 1.9 * limit);
  EXPECT_NE(warnings->GetWarningMessage().find("times the size of its reflectors"),
    std::string::npos)
    << warnings->GetWarningMessage();
  warnings->Clear();
  window->Render(); // the same view: said once
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  EXPECT_EQ(vtkCausticsTechniques::GetBestNameFor(renderer), "screen-space");
}
