// The viewer behind caustics-view (CausticsViewer.h).
#include "CausticsViewer.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkCausticsTimings.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkInteractorEventRecorder.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <vector>

// Last: Xlib's macros (None, Status, Bool) would clash with VTK's headers.
#include <X11/Xlib.h>

namespace caustics_cli
{
const char* const ViewerKeys = R"(Keys:
  left drag                  rotate the camera (trackball); middle drag pans, wheel zooms
  t / T                      next / previous technique
  + / -                      photon grid side per light x2 / /2 (refused beyond what
                             this OpenGL can hold)
  ] / [                      one depth layer more / less (techniques with layers:
                             screen-space)
  c                          caustic layer on / off (off: VTK's own shading)
  o                          overlay on / off
  l                          where the last frame's photons' light went: landed, left
                             the views, lost (reads the GPU's counters once)
  h                          this help
  r                          reset the camera
  q                          quit
)";

namespace
{
/** The trackball camera with the viewer's keys; any other key does what VTK's does. */
class ViewerStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static ViewerStyle* New();
  vtkTypeMacro(ViewerStyle, vtkInteractorStyleTrackballCamera);
  void OnChar() override
  {
    if (!this->Viewer || !this->Viewer->HandleKey(this->Interactor->GetKeyCode()))
    {
      this->Superclass::OnChar();
    }
  }
  CausticsViewer* Viewer = nullptr;
};
vtkStandardNewMacro(ViewerStyle);

/** The overlay lists this many of the last frame's stages, the slowest first. */
constexpr std::size_t OverlayStages = 6;

/** "ms" with two decimals below 10, one below 100, none above: short and steady. */
std::string Milliseconds(double ms)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(ms < 10.0 ? 2 : (ms < 100.0 ? 1 : 0)) << ms << " ms";
  return text.str();
}

/** The X display DISPLAY names, or NoWindowError: no display means no viewer. */
Display* OpenDisplay()
{
  const char* name = vtksys::SystemTools::GetEnv("DISPLAY");
  if (!name || !*name)
  {
    throw NoWindowError("no display (DISPLAY is not set): caustics-view needs an X display "
                        "(caustics-render renders images without one)");
  }
  Display* display = XOpenDisplay(nullptr);
  if (!display)
  {
    throw NoWindowError(std::string("cannot open the X display '") + name +
      "': caustics-view needs an X display (caustics-render renders images without one)");
  }
  return display;
}
}

CausticsViewer::CausticsViewer(const SceneOptions& options, OneLineOutputWindow* messages)
  : Messages(messages)
{
  this->MakeWindow(options);
  LoadScene(options, this->Window, this->Renderer, this->Builtin);
  ApplyOverrides(options, this->Renderer);
  this->MakeOverlay();
  this->Technique = TechniqueFor(options, this->Renderer);
  // Refuse a photon grid this OpenGL cannot hold before anything is allocated.
  if (!this->InstallPass(MakePass(options, this->Renderer)))
  {
    throw std::runtime_error(this->StatusText);
  }
}

CausticsViewer::~CausticsViewer()
{
  this->Renderer->SetPass(nullptr);
  if (this->Pass)
  {
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  this->Window->Finalize();
  this->Interactor = nullptr;
  this->Window = nullptr;
  XCloseDisplay(static_cast<Display*>(this->XDisplay)); // the window does not own it
}

void CausticsViewer::MakeWindow(const SceneOptions& options)
{
  this->XDisplay = OpenDisplay();
  this->Window = vtkSmartPointer<vtkRenderWindow>::New();
  if (!this->Window->IsA("vtkXOpenGLRenderWindow"))
  {
    XCloseDisplay(static_cast<Display*>(this->XDisplay));
    throw NoWindowError(std::string("this VTK makes no window on an X display (it makes a ") +
      this->Window->GetClassName() + "): caustics-view needs one");
  }
  this->Window->SetDisplayId(this->XDisplay);
  this->Window->SetMultiSamples(0);
  this->Window->SetSize(options.Width, options.Height);
  this->Window->SetWindowName(("caustics-view: " + options.Scene).c_str());
  // The overlay has its own layer, so the pass never composites caustics over the text.
  this->Window->SetNumberOfLayers(2);
  this->Window->AddRenderer(this->Renderer); // first: a glTF file imports into it
  this->OverlayRenderer->SetLayer(1);
  this->OverlayRenderer->InteractiveOff();
  this->Window->AddRenderer(this->OverlayRenderer);
  this->Interactor = vtkSmartPointer<vtkRenderWindowInteractor>::New();
  vtkNew<ViewerStyle> style;
  style->Viewer = this;
  this->Interactor->SetInteractorStyle(style);
  this->Interactor->SetRenderWindow(this->Window);
}

void CausticsViewer::MakeOverlay()
{
  vtkTextProperty* text = this->Overlay->GetTextProperty();
  text->SetFontFamilyToCourier();
  text->SetFontSize(11);
  text->SetColor(1.0, 1.0, 0.8);
  text->SetBackgroundColor(0.0, 0.0, 0.0);
  text->SetBackgroundOpacity(0.35);
  text->SetVerticalJustificationToTop();
  this->Overlay->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->Overlay->SetPosition(0.01, 0.99);
  this->OverlayRenderer->AddActor2D(this->Overlay);
  // The frame's wall time, and the stages' times read once the scene's renderer has
  // drawn, before the overlay's renderer draws the text.
  vtkNew<vtkCallbackCommand> start, end;
  start->SetClientData(this);
  start->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<CausticsViewer*>(data)->FrameStart = std::chrono::steady_clock::now(); });
  this->Renderer->AddObserver(vtkCommand::StartEvent, start);
  end->SetClientData(this);
  end->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<CausticsViewer*>(data)->UpdateOverlay(); });
  this->Renderer->AddObserver(vtkCommand::EndEvent, end);
}

/**
 * Installs `pass` with the viewer's photon count and layers, if this OpenGL can
 * hold its photon grid; otherwise keeps the pass shown and says why (Status, not
 * reported: the caller reports it or fails with it).
 */
bool CausticsViewer::InstallPass(vtkSmartPointer<vtkCausticsRenderPass> pass)
{
  if (this->Pass)
  {
    pass->SetLightBufferResolution(this->Pass->GetLightBufferResolution());
    pass->SetProgressiveFrames(this->Pass->GetProgressiveFrames());
  }
  auto* layered = vtkCausticsScreenSpacePhotonPass::SafeDownCast(pass);
  if (layered && this->Layers > 0)
  {
    layered->SetMaximumNumberOfLayers(this->Layers);
  }
  if (!pass->CheckResources(this->Window))
  {
    this->StatusText = pass->GetResourceError();
    return false;
  }
  if (this->Pass)
  {
    this->Pass->ReleaseGraphicsResources(this->Window);
  }
  this->Pass = pass;
  this->Renderer->SetPass(this->CausticsOn ? this->Pass.Get() : nullptr);
  return true;
}

bool CausticsViewer::HandleKey(char key)
{
  switch (key)
  {
    case 't':
    case 'T':
      this->NextTechnique(key == 't' ? 1 : -1);
      return true;
    case '+':
    case '=':
    case '-':
    case '_':
      this->ChangePhotons(key == '+' || key == '=' ? 1 : -1);
      return true;
    case ']':
    case '[':
      this->ChangeLayers(key == ']' ? 1 : -1);
      return true;
    case 'c':
    case 'C':
      this->ToggleCaustics();
      return true;
    case 'o':
    case 'O':
      this->SetOverlayVisible(!this->Overlay->GetVisibility());
      return true;
    case 'h':
    case 'H':
      this->PrintKeys();
      return true;
    case 'l':
    case 'L':
      this->ShowPhotonLight();
      return true;
    default:
      return false;
  }
}

void CausticsViewer::NextTechnique(int step)
{
  const std::vector<std::string> names = vtkCausticsTechniques::GetNames();
  const auto found = std::find(names.begin(), names.end(), this->Technique);
  const int count = static_cast<int>(names.size());
  const int current = found == names.end() ? 0 : static_cast<int>(found - names.begin());
  const std::string next = names[((current + step) % count + count) % count];
  this->StatusText.clear();
  if (this->InstallPass(vtkCausticsTechniques::Create(next)))
  {
    this->Technique = next;
  }
  else
  {
    this->Report(next + ": " + this->StatusText);
  }
  this->Render();
}

void CausticsViewer::ChangePhotons(int step)
{
  const int now = this->Pass->GetLightBufferResolution();
  const int wanted = std::min(this->Pass->GetLightBufferResolutionMaxValue(),
    std::max(this->Pass->GetLightBufferResolutionMinValue(), step > 0 ? 2 * now : now / 2));
  this->StatusText.clear();
  if (wanted == now)
  {
    this->Report(
      "photons: already " + std::to_string(now) + (step > 0 ? ", the most" : ", the least"));
  }
  this->Pass->SetLightBufferResolution(wanted);
  if (!this->Pass->CheckResources(this->Window))
  {
    this->Report(this->Pass->GetResourceError());
    this->Pass->SetLightBufferResolution(now);
  }
  this->Render();
}

void CausticsViewer::ChangeLayers(int step)
{
  auto* layered = vtkCausticsScreenSpacePhotonPass::SafeDownCast(this->Pass);
  this->StatusText.clear();
  if (!layered)
  {
    this->Report(this->Technique + " has no depth layers");
    this->Render();
    return;
  }
  const int now = layered->GetMaximumNumberOfLayers();
  layered->SetMaximumNumberOfLayers(now + step); // clamped to the pass's range
  this->Layers = layered->GetMaximumNumberOfLayers();
  if (this->Layers == now)
  {
    this->Report(
      "layers: already " + std::to_string(now) + (step > 0 ? ", the most" : ", the least"));
  }
  this->Render();
}

void CausticsViewer::ToggleCaustics()
{
  this->CausticsOn = !this->CausticsOn;
  this->StatusText.clear();
  this->Renderer->SetPass(this->CausticsOn ? this->Pass.Get() : nullptr);
  this->Render();
}

void CausticsViewer::SetOverlayVisible(bool on)
{
  this->Overlay->SetVisibility(on);
  this->Render();
}

void CausticsViewer::ShowPhotonLight()
{
  std::string warning;
  const std::string line =
    this->CausticsOn ? DescribePhotonLight(this->Pass, this->Technique, warning) : std::string();
  this->Report(line.empty() ? this->Technique + " counts no photons' light here"
                            : line + (warning.empty() ? "" : "; warning: " + warning));
  this->Render();
}

void CausticsViewer::PrintKeys()
{
  std::cout << ViewerKeys << std::flush;
}

/** A message for the user: on the overlay's last line and as one line on stderr. */
void CausticsViewer::Report(const std::string& status)
{
  this->StatusText = status;
  std::cerr << "caustics-view: " << status << "\n";
}

void CausticsViewer::UpdateOverlay()
{
  this->FrameMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - this->FrameStart)
      .count();
  const std::string error = this->Messages ? this->Messages->TakeError() : "";
  if (!error.empty())
  {
    this->Report(error);
  }
  this->Overlay->SetInput(this->GetOverlayText().c_str());
}

std::string CausticsViewer::GetOverlayText() const
{
  std::string text = this->DescribeSettings() + this->DescribeTimings();
  if (!this->StatusText.empty())
  {
    text += this->StatusText + "\n";
  }
  text += "h: keys";
  return text;
}

/** Technique, photons, layers: what the keys change. */
std::string CausticsViewer::DescribeSettings() const
{
  std::ostringstream text;
  const int n = this->Pass->GetLightBufferResolution();
  text << "technique: " << this->Technique << (this->CausticsOn ? "" : " (caustics off)") << "\n"
       << "photons: " << n << " x " << n << " = " << static_cast<long long>(n) * n
       << " per light\n";
  if (auto* layered = vtkCausticsScreenSpacePhotonPass::SafeDownCast(this->Pass))
  {
    text << "layers: " << layered->GetMaximumNumberOfLayers() << "\n";
  }
  if (this->Pass->GetProgressiveFrames() > 1)
  {
    text << "frames averaged: " << this->Pass->GetFramesAveraged() << " of "
         << this->Pass->GetProgressiveFrames() << "\n";
  }
  return text.str();
}

/**
 * The slowest stages the last frame ran (at most OverlayStages), each with its GPU
 * time once measured (timer queries finish a frame or two later) or else its CPU
 * time; never a -1. Nested stages are listed as well as the stage they run in.
 */
std::string CausticsViewer::DescribeTimings() const
{
  std::ostringstream text;
  if (this->FrameMilliseconds >= 0.0)
  {
    text << "frame: " << Milliseconds(this->FrameMilliseconds) << "\n";
  }
  if (!this->CausticsOn)
  {
    return text.str();
  }
  struct Stage
  {
    std::string Name;
    double Milliseconds;
    const char* Clock;
  };
  std::vector<Stage> stages;
  vtkCausticsTimings* timings = this->Pass->GetTimings();
  for (int s = 0; s < timings->GetNumberOfStages(); ++s)
  {
    const double gpu = timings->GetStageGPUMilliseconds(s);
    const double cpu = timings->GetStageCPUMilliseconds(s);
    if (timings->GetStageRan(s) && (gpu >= 0.0 || cpu >= 0.0))
    {
      stages.push_back(
        { timings->GetStageName(s), gpu >= 0.0 ? gpu : cpu, gpu >= 0.0 ? "gpu" : "cpu" });
    }
  }
  std::stable_sort(stages.begin(), stages.end(),
    [](const Stage& a, const Stage& b) { return a.Milliseconds > b.Milliseconds; });
  const std::size_t shown = std::min(stages.size(), OverlayStages);
  for (std::size_t s = 0; s < shown; ++s)
  {
    text << "  " << stages[s].Name << ": " << Milliseconds(stages[s].Milliseconds) << " "
         << stages[s].Clock << "\n";
  }
  if (stages.size() > shown)
  {
    text << "  (" << stages.size() - shown << " faster stages)\n";
  }
  return text.str();
}

void CausticsViewer::Play(const std::string& eventLog)
{
  this->Interactor->Initialize(); // the interactor renders only once enabled
  this->Render();
  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(this->Interactor);
  recorder->ReadFromInputStringOn();
  recorder->SetInputString(eventLog.c_str());
  recorder->Play();
  recorder->SetInteractor(nullptr);
}

void CausticsViewer::WriteScreenshot(const std::string& path)
{
  this->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(this->Window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode())
  {
    throw std::runtime_error("cannot write " + path);
  }
}

bool CausticsViewer::RefineStillFrame()
{
  auto* style = vtkInteractorStyle::SafeDownCast(this->Interactor->GetInteractorStyle());
  const int frames = this->Pass->GetProgressiveFrames();
  if (!this->CausticsOn || frames <= 1 || this->Pass->GetFramesAveraged() >= frames ||
    (style && style->GetState() != VTKIS_NONE))
  {
    return false;
  }
  this->Render();
  return true;
}

void CausticsViewer::Start()
{
  this->Interactor->Initialize();
  this->Render();
  // A still view refines by itself (--progressive): one more frame per tick.
  vtkNew<vtkCallbackCommand> refine;
  refine->SetClientData(this);
  refine->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<CausticsViewer*>(data)->RefineStillFrame(); });
  this->Interactor->AddObserver(vtkCommand::TimerEvent, refine);
  if (this->Pass->GetProgressiveFrames() > 1)
  {
    this->Interactor->CreateRepeatingTimer(30);
  }
  this->Interactor->Start();
}

void CausticsViewer::Render()
{
  this->Window->Render();
}

vtkRenderWindow* CausticsViewer::GetRenderWindow() const
{
  return this->Window;
}

vtkRenderWindowInteractor* CausticsViewer::GetInteractor() const
{
  return this->Interactor;
}

vtkCausticsRenderPass* CausticsViewer::GetPass() const
{
  return this->Pass;
}
}
