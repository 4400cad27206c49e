// A frame's progress (vtkCausticsTimings' ProgressEvent, which caustics-render shows
// for frames over 2 s): one event per finished stage naming it, -1 in a first frame
// (its length is not known yet), then the fraction of the last frame's wall time,
// increasing, at most 0.99, and 1 at the end of every frame. Nothing observes it
// in a plain render, and then the stages do not wait for the GPU.
#include "TestTechniqueFrame.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{
struct Event
{
  double Fraction;
  std::string Stage;
};

void Record(vtkObject* caller, unsigned long, void* clientData, void* callData)
{
  auto* events = static_cast<std::vector<Event>*>(clientData);
  events->push_back(
    { *static_cast<double*>(callData), vtkCausticsTimings::SafeDownCast(caller)->GetProgressStage() });
}
}

TEST(FrameProgress, ReachesOneEveryFrame)
{
  TechniqueFrame f("screen-space", 64, 64);
  vtkCausticsRenderPass* pass = f.Pass;
  std::vector<Event> events;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(Record);
  callback->SetClientData(&events);
  pass->GetTimings()->AddObserver(vtkCommand::ProgressEvent, callback);

  for (int frame = 0; frame < 2; ++frame)
  {
    events.clear();
    f.Window->Render();
    ASSERT_GT(events.size(), 5u) << "frame " << frame;
    EXPECT_DOUBLE_EQ(events.back().Fraction, 1.0);
    EXPECT_EQ(events.back().Stage, "");
    double last = frame == 0 ? -1.0 : 0.0;
    for (std::size_t i = 0; i + 1 < events.size(); ++i)
    {
      EXPECT_FALSE(events[i].Stage.empty()) << i;
      if (frame == 0)
      {
        EXPECT_DOUBLE_EQ(events[i].Fraction, -1.0) << events[i].Stage;
      }
      else
      {
        EXPECT_GE(events[i].Fraction, last) << events[i].Stage;
        EXPECT_LE(events[i].Fraction, 0.99) << events[i].Stage;
        last = events[i].Fraction;
      }
    }
    EXPECT_GT(pass->GetTimings()->GetLastFrameMilliseconds(), 0.0);
  }
  EXPECT_EQ(events.front().Stage, "scene snapshot");
}
