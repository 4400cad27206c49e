// caustics-view's viewer driven by a recorded interaction (issue 17): a left-button
// drag that rotates the camera, then the 't' key, which switches the technique from
// screen-space to caustic-maps. The image after the playback, without the overlay
// (its times change from run to run), is compared with the baseline
// TestCausticsViewerPlayback.png (vtkRegressionTestImage: -V BASELINE -T OUTPUT_DIR).
// The overlay's text must name the new technique and carry no -1 time; 'l' puts where
// the photons' light went on its last line. With
// --progressive a still view refines itself to the mean of its frames, then stops.
#include "CausticsViewer.h"

#include "vtkCamera.h"
#include "vtkCausticsRenderPass.h"
#include "vtkMath.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
// vtkInteractorEventRecorder's format: event, x, y, modifiers, key code, repeat, key sym.
// The window is 160 x 160; the drag goes 40 pixels right (the camera turns left
// around the focal point), then 't' switches the technique.
const char* EventLog = "# StreamVersion 1.1\n"
                       "MouseMoveEvent 60 80 0 0 0 0\n"
                       "LeftButtonPressEvent 60 80 0 0 0 0\n"
                       "MouseMoveEvent 70 80 0 0 0 0\n"
                       "MouseMoveEvent 80 81 0 0 0 0\n"
                       "MouseMoveEvent 90 82 0 0 0 0\n"
                       "MouseMoveEvent 100 82 0 0 0 0\n"
                       "LeftButtonReleaseEvent 100 82 0 0 0 0\n"
                       "KeyPressEvent 100 82 0 116 1 t\n"
                       "CharEvent 100 82 0 116 1 t\n"
                       "KeyReleaseEvent 100 82 0 116 1 t\n";

bool Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "TestCausticsViewer: " << what << "\n";
  }
  return ok;
}
}

int main(int argc, char* argv[])
{
  caustics_cli::SceneOptions options;
  options.Scene = "ball-lens";
  options.Technique = "screen-space";
  options.Photons = 48;
  options.Width = options.Height = 160;
  caustics_cli::CausticsViewer viewer(options);
  vtkCamera* camera =
    viewer.GetRenderWindow()->GetRenderers()->GetFirstRenderer()->GetActiveCamera();
  double before[3], after[3];
  camera->GetPosition(before);

  viewer.Play(EventLog);

  camera->GetPosition(after);
  bool ok = Check(std::sqrt(vtkMath::Distance2BetweenPoints(before, after)) > 1e-3,
    "the drag did not move the camera");
  ok &= Check(viewer.GetTechnique() == "caustic-maps",
    "'t' switched to '" + viewer.GetTechnique() + "', not caustic-maps");
  const std::string overlay = viewer.GetOverlayText();
  ok &= Check(overlay.find("technique: caustic-maps") != std::string::npos &&
      overlay.find("photons: 48 x 48") != std::string::npos &&
      overlay.find("-1") == std::string::npos,
    "unexpected overlay:\n" + overlay);
  // 'l': where the last frame's photons' light went, on the overlay's last line.
  viewer.HandleKey('l');
  ok &= Check(viewer.GetStatus().find("photon light (") == 0 &&
      viewer.GetStatus().find("lost on paths caustic-maps cannot follow") != std::string::npos &&
      viewer.GetOverlayText().find(viewer.GetStatus()) != std::string::npos,
    "'l' said: " + viewer.GetStatus());
  viewer.SetOverlayVisible(false); // renders: the compared image has no text
  const int result = vtkRegressionTestImage(viewer.GetRenderWindow());
  ok &= Check(result == vtkTesting::PASSED, "the image differs from the baseline");
  // --progressive 3: a still view refines by itself (Start()'s timer calls
  // RefineStillFrame()) until the mean holds 3 frames, then stops rendering.
  options.ProgressiveFrames = 3;
  caustics_cli::CausticsViewer still(options);
  still.Render();
  int refined = 0;
  while (refined < 10 && still.RefineStillFrame())
  {
    ++refined;
  }
  ok &= Check(refined == 2 && still.GetPass()->GetFramesAveraged() == 3,
    "--progressive 3 refined " + std::to_string(refined) + " times to " +
      std::to_string(still.GetPass()->GetFramesAveraged()) + " frames, not 2 to 3");
  ok &= Check(still.GetOverlayText().find("frames averaged: 3 of 3") != std::string::npos,
    "unexpected overlay:\n" + still.GetOverlayText());
  if (ok)
  {
    std::cout << "TestCausticsViewer: ok\n";
  }
  return ok ? 0 : 1;
}
