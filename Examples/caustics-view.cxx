// caustics-view: shows a built-in caustics scene, a glTF 2.0 file or a mesh in a
// window, with a trackball camera and keys that switch the technique and change its
// photon count and layers (docs/viewer.md).
//
//   caustics-view [options] [SCENE | FILE.gltf | FILE.glb | FILE.ply|obj|stl]
//
// It takes caustics-render's scene, technique, light and camera options. Every error
// is one line on stderr and a non-zero exit: 2 for bad arguments, 3 when there is no
// X display to show the window on (the viewer never renders headless), 1 otherwise.
#include "CausticsCommandLine.h"
#include "CausticsSceneOptions.h"
#include "CausticsViewer.h"
#include "vtkCausticsProgressivePhotonPass.h"

#include "vtksys/SystemTools.hxx"

#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

namespace
{
const char* UsageHead =
  R"(usage: caustics-view [options] [SCENE | FILE.gltf | FILE.glb | MESH.ply|obj|stl]

Shows caustics rendered by a VTK render pass in a window on the X display, with a
trackball camera and keys that change the technique, its photon count and its
depth layers. An overlay shows the technique, the photon count and the time of
each stage of the last frame. Needs an X display (DISPLAY); without one it exits
with code 3 (caustics-render renders images without a display).
)";

const char* UsageTail = R"(
Playback (no one at the keyboard):
  --playback FILE            replay a recorded interaction (vtkInteractorEventRecorder's
                             text format), then carry on interactively
  --screenshot PREFIX        write PREFIX.png after the playback (if any) and exit
  --no-overlay               start with the overlay hidden ('o' shows it)
  --help                     this text

)";

struct Options : caustics_cli::SceneOptions
{
  std::string Playback;
  std::string Screenshot;
  bool Overlay = true;
};

Options Parse(int argc, char* argv[], bool& help)
{
  Options options;
  help = false;
  bool sceneGiven = false;
  caustics_cli::Arguments arguments;
  arguments.Flag("--help", [&help] { help = true; });
  arguments.Flag("-h", [&help] { help = true; });
  caustics_cli::DeclareSceneOptions(arguments, options, sceneGiven);
  arguments.Value("--playback", caustics_cli::Text(options.Playback));
  arguments.Value("--screenshot", caustics_cli::Text(options.Screenshot));
  arguments.Flag("--no-overlay", [&options] { options.Overlay = false; });
  caustics_cli::FinishSceneOptions(arguments.Parse(argc, argv), options, sceneGiven);
  return options;
}

std::string UsageText()
{
  return std::string(UsageHead) + "\n" + caustics_cli::SceneUsage + "\nTechnique and quality:\n" +
    caustics_cli::QualityUsage() + "\n" + caustics_cli::OverridesUsage + UsageTail +
    caustics_cli::ViewerKeys;
}

/** The recorded interaction of --playback, read before any window opens. */
std::string ReadPlayback(const std::string& path)
{
  std::string log;
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    throw caustics_cli::UsageError("--playback: " + path + ": no such file");
  }
  std::ifstream in(path);
  log.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return log;
}
}

int main(int argc, char* argv[])
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique(); // the CPU technique, by name
  return caustics_cli::RunMain("caustics-view", caustics_cli::LoggedErrors::Remember,
    [&](caustics_cli::OneLineOutputWindow* messages)
    {
      bool help = false;
      const Options options = Parse(argc, argv, help);
      if (help)
      {
        std::cout << UsageText();
        return 0;
      }
      const std::string playback = options.Playback.empty() ? "" : ReadPlayback(options.Playback);
      caustics_cli::CausticsViewer viewer(options, messages);
      if (!options.Overlay)
      {
        viewer.SetOverlayVisible(false);
      }
      if (!playback.empty())
      {
        viewer.Play(playback);
      }
      if (!options.Screenshot.empty())
      {
        viewer.WriteScreenshot(options.Screenshot + ".png");
        std::cout << "wrote " << options.Screenshot << ".png\n";
        return 0;
      }
      viewer.Start();
      return 0;
    });
}
