// The interactive viewer behind caustics-view: a scene loaded as caustics-render
// loads it (CausticsSceneOptions.h), shown in a window on an X display with a
// trackball camera, keys that change the technique and its quality, and an
// overlay with the technique, the photon count and the stages' times. The keys
// are methods a program or a test can call; Play() replays a recorded interaction
// (vtkInteractorEventRecorder) without anyone at the keyboard.
#ifndef CausticsViewer_h
#define CausticsViewer_h

#include "CausticsSceneOptions.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <string>

class vtkCausticsBuiltinScene;
class vtkCausticsRenderPass;
class vtkOpenGLRenderer;
class vtkRenderWindow;
class vtkRenderWindowInteractor;
class vtkRenderer;
class vtkTextActor;

namespace caustics_cli
{
class OneLineOutputWindow;

/** The keys, one per line, as --help and the 'h' key print them. */
extern const char* const ViewerKeys;

class CausticsViewer
{
public:
  /**
   * Opens a window on the X display named by DISPLAY (NoWindowError when there is
   * none: the viewer never falls back to a headless window), loads the scene,
   * applies the overrides and installs the technique's pass (std::runtime_error
   * when this OpenGL cannot hold its photon grid). `messages` (optional) is where
   * VTK's errors go; the viewer reports them as they happen.
   */
  CausticsViewer(const SceneOptions& options, OneLineOutputWindow* messages = nullptr);
  ~CausticsViewer();
  CausticsViewer(const CausticsViewer&) = delete;
  CausticsViewer& operator=(const CausticsViewer&) = delete;

  /** What a key does: true when `key` is one of the viewer's keys (see ViewerKeys). */
  bool HandleKey(char key);

  ///@{
  /** The actions behind the keys; each renders the window once. */
  void NextTechnique(int step);    ///< t / T: the next (+1) or previous (-1) technique
  void ChangePhotons(int step);    ///< + / -: double or halve the photon grid's side
  void ChangeLayers(int step);     ///< ] / [: one depth layer more or less (screen-space)
  void ToggleCaustics();           ///< c: the caustic layer (the pass) on or off
  void SetOverlayVisible(bool on); ///< o: the overlay text on or off
  void PrintKeys();                ///< h: the keys, on stdout
  void ShowPhotonLight();          ///< l: where the photons' light went (stalls once)
  ///@}

  /** Replays a recorded interaction (vtkInteractorEventRecorder's text format). */
  void Play(const std::string& eventLog);
  /** Renders the window and writes it to `path` (PNG). */
  void WriteScreenshot(const std::string& path);
  /**
   * With --progressive N: renders one more frame while the pass's mean of a still
   * scene is not complete and no one is moving the camera; true when it rendered.
   * Start() calls it from a repeating timer, so a still view refines by itself.
   */
  bool RefineStillFrame();
  /** Renders, then hands control to the user until the window closes ('q'). */
  void Start();
  void Render();

  /** The technique shown (a registered name, "best" resolved). */
  const std::string& GetTechnique() const { return this->Technique; }
  bool GetCausticsOn() const { return this->CausticsOn; }
  /** The overlay's text as the last frame showed it. */
  std::string GetOverlayText() const;
  /** The last action's message (a refused photon count, a technique without layers). */
  const std::string& GetStatus() const { return this->StatusText; }
  vtkRenderWindow* GetRenderWindow() const;
  vtkRenderWindowInteractor* GetInteractor() const;
  vtkCausticsRenderPass* GetPass() const;

private:
  void MakeWindow(const SceneOptions& options);
  void MakeOverlay();
  bool InstallPass(vtkSmartPointer<vtkCausticsRenderPass> pass);
  void Report(const std::string& status);
  void UpdateOverlay();
  std::string DescribeSettings() const;
  std::string DescribeTimings() const;

  void* XDisplay = nullptr; ///< the X display the window is on (Display*)
  OneLineOutputWindow* Messages = nullptr;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderer> OverlayRenderer;
  vtkNew<vtkTextActor> Overlay;
  vtkSmartPointer<vtkRenderWindowInteractor> Interactor;
  vtkNew<vtkCausticsBuiltinScene> Builtin;
  vtkSmartPointer<vtkCausticsRenderPass> Pass;
  std::string Technique;
  int Layers = 0; ///< depth layers asked for with [ and ]; 0: the technique's default
  bool CausticsOn = true;
  std::string StatusText;
  std::chrono::steady_clock::time_point FrameStart;
  double FrameMilliseconds = -1.0; ///< wall time of the last frame; < 0 before the first
};
}

#endif
