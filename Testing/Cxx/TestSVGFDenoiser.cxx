// The SVGF denoising stage (vtkCausticsSVGFDenoiser, vtkCausticsRenderPass::SetDenoise,
// 002_97e66a5090de9b07.txt §3.3) on a caustic that is noisy per frame: the CPU
// reference's photon tracer with a fresh seed every frame (a few thousand photons),
// as cpu-progressive traces it. It flickers less and is no farther from the truth
// than the raw estimate, follows a step of the ball within a few frames without a
// ghost, carries no history over a camera cut or a resize, keeps the flux of a still
// input and never spreads a NaN. Figures: docs/denoising.md.
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsCascadedPhotonPass.h"
#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSVGFDenoiser.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsTimings.h"

#include "vtkActor.h"
#include "vtkAssembly.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkTransform.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace
{
// Bounds just past the figures reached (in the comments; docs/denoising.md).
constexpr double FLICKER_BALL = 8.5;  // 8.62x less flicker than the raw estimate
constexpr double L2_BALL = 0.21;      // 0.199 of the raw estimate's relative L2
constexpr double FLICKER_RING = 8.5;  // 8.72x
constexpr double L2_RING = 0.46;      // 0.444
constexpr double HISTORY_GAIN = 0.55; // 0.521 of SVGF's own choice's L2 (0.0966 against 0.185)
constexpr std::size_t STEP_LAG = 1;   // 0 frames to settle after the step
constexpr double STEP_AFTER = 0.50;   // at most 0.483 of the raw estimate's error after it
constexpr double MOVING = 0.56;       // at most 0.541 of the raw estimate's error, moving
constexpr double FLUX = 1e-4;         // denoised over raw flux: 0.999997
// Per-actor motion (FollowsActorsThatMove), against the still sequence's denoised figures;
// in brackets what the same test gave without following the actors / following every
// actor whatever lights it:
constexpr double RIGID_FLICKER = 1.06; // moving with its light: flicker 1.038 of still's (1.97)
constexpr double RIGID_L2 = 1.0;       // relative L2 0.993 of still's (4.87)
constexpr double SLIDE_FLICKER = 1.65; // floor sliding under the caustic: 1.614 ((2.01))
// An actor appears: 1.044x the error before (dropping all: 3.68x). The box stands on the
// floor: since the reference's estimate holds up to a receiver's end (docs/reference.md)
// the floor along its foot counts the light the splats lose there (1.011x before).
constexpr double APPEAR = 1.06;
constexpr double SLIDE_L2 = 1.58;      // worst frame's relative L2 1.553 of still's mean ((8.79))
}

namespace
{
/**
 * A technique that is noisy per frame: the reference's photon tracer (Embree, the
 * kernel estimate of cpu-progressive) with `Seed` then Seed + 1, ... one estimate of
 * `Photons` photons per frame. Optionally writes NaN and +Inf into some texels.
 */
class NoisyPhotonPass : public vtkCausticsRenderPass
{
public:
  static NoisyPhotonPass* New();
  vtkTypeMacro(NoisyPhotonPass, vtkCausticsRenderPass);

  unsigned int Seed = 1;
  bool FreshSeeds = true; // else the same estimate every frame
  vtkIdType Photons = 4096;
  bool Poison = false; // NaN and +Inf in a block of the caustic

  /** Whether the last frame was denoised: a failed denoiser leaves the raw input, which
   * some of these tests would otherwise pass on. */
  bool LastFrameDenoised() const { return this->GetFrameResult().Denoised; }

protected:
  NoisyPhotonPass()
  {
    this->Tracer->UseCacheOff();
    this->Tracer->CameraSeesRefractorsOff(); // the opaque surfaces, as the G-buffer
  }
  ~NoisyPhotonPass() override = default;

  CausticNeeds GetCausticNeeds() override
  {
    CausticNeeds needs;
    needs.LightBuffers = false;
    return needs;
  }

  bool RenderCausticIrradiance(const FrameInputs& in) override
  {
    this->Tracer->SetScene(*in.Scene);
    this->Tracer->SetImageSize(in.Width, in.Height);
    this->Tracer->SetPhotonsPerLight(this->Photons);
    this->Tracer->SetSeed(this->FreshSeeds ? this->Seed++ : this->Seed);
    if (!this->Tracer->Update())
    {
      ADD_FAILURE() << "the tracer failed: " << this->Tracer->GetLastError();
      return false;
    }
    vtkDataArray* e = this->Tracer->GetOutput()->GetPointData()->GetArray("CausticIrradiance");
    const vtkIdType pixels = static_cast<vtkIdType>(in.Width) * in.Height;
    this->Texels.assign(4 * pixels, 0.0f);
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->Texels[4 * p + c] = static_cast<float>(e->GetComponent(p, c));
      }
    }
    if (this->Poison)
    {
      for (int j = in.Height / 2 - 2; j < in.Height / 2 + 2; ++j)
      {
        for (int i = in.Width / 2 - 2; i < in.Width / 2 + 2; ++i)
        {
          this->Texels[4 * (j * in.Width + i)] = (i + j) % 2
            ? std::numeric_limits<float>::quiet_NaN()
            : std::numeric_limits<float>::infinity();
        }
      }
    }
    glTextureSubImage2D(in.CausticIrradiance->GetHandle(), 0, 0, 0, in.Width, in.Height, GL_RGBA,
      GL_FLOAT, this->Texels.data());
    return true;
  }

private:
  vtkNew<vtkCausticsReferenceRenderer> Tracer;
  std::vector<float> Texels;
};
vtkStandardNewMacro(NoisyPhotonPass);

/** One image: RGB per pixel. */
using Image = std::vector<double>;

struct Frame
{
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCausticsBuiltinScene> Scene;
  vtkNew<NoisyPhotonPass> Pass;
  int Size;

  explicit Frame(int size, const char* scene = "ball-lens")
    : Size(size)
  {
    this->Scene->SetSceneName(scene);
    EXPECT_TRUE(this->Scene->Populate(this->Renderer));
    this->Pass->DenoiseOn();
    this->Pass->KeepBuffersOn();
    this->Renderer->SetPass(this->Pass);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
  }
  ~Frame()
  {
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }

  Image Read(const char* name)
  {
    vtkNew<vtkImageData> image;
    EXPECT_TRUE(this->Pass->ReadBuffer(name, image));
    vtkDataArray* a = image->GetPointData()->GetArray(0);
    Image rgb(3 * a->GetNumberOfTuples());
    for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb[3 * p + c] = a->GetComponent(p, c);
      }
    }
    return rgb;
  }
  Image Denoised()
  {
    EXPECT_TRUE(this->Pass->LastFrameDenoised()) << "the denoiser did not run";
    return this->Read("CausticIrradiance");
  }
  Image Raw() { return this->Read("RawCausticIrradiance"); }

  /** The scene's refractor (the ball lens). */
  vtkActor* Ball()
  {
    vtkPropCollection* props = this->Renderer->GetViewProps();
    props->InitTraversal();
    while (vtkProp* prop = props->GetNextProp())
    {
      auto* actor = vtkActor::SafeDownCast(prop);
      if (actor && vtkCausticsMaterial::Classify(actor, 0.3) == vtkCausticsMaterial::ROLE_REFRACTOR)
      {
        return actor;
      }
    }
    return nullptr;
  }
};

/** The truth of the frame's scene: the reference's estimate from a million photons. */
struct Truth
{
  Image E;
  std::vector<double> Area; // m^2 of receiver per pixel (0 off receivers)

  Truth(vtkRenderer* renderer, int size, vtkIdType photons = 1000000, double kernelPixels = 2.0)
  {
    vtkNew<vtkCausticsReferenceRenderer> reference;
    reference->SetInputRenderer(renderer);
    reference->SetImageSize(size, size);
    reference->SetPhotonsPerLight(photons);
    reference->SetKernelRadiusPixels(kernelPixels);
    reference->CameraSeesRefractorsOff();
    EXPECT_TRUE(reference->Update()) << reference->GetLastError();
    vtkPointData* pd = reference->GetOutput()->GetPointData();
    vtkDataArray* e = pd->GetArray("CausticIrradiance");
    vtkDataArray* mask = pd->GetArray("ReceiverMask");
    vtkDataArray* area = pd->GetArray("PixelArea");
    const vtkIdType pixels = e->GetNumberOfTuples();
    this->E.resize(3 * pixels);
    this->Area.resize(pixels);
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->E[3 * p + c] = e->GetComponent(p, c);
      }
      this->Area[p] = mask->GetComponent(p, 0) > 0.5 ? area->GetComponent(p, 0) : 0.0;
    }
  }

  /** Relative L2 of `image` against the truth over receiver pixels. */
  double RelativeL2(const Image& image) const
  {
    double error = 0.0, norm = 0.0;
    for (std::size_t p = 0; p < this->Area.size(); ++p)
    {
      if (this->Area[p] > 0.0)
      {
        for (int c = 0; c < 3; ++c)
        {
          const double d = image[3 * p + c] - this->E[3 * p + c];
          error += d * d;
          norm += this->E[3 * p + c] * this->E[3 * p + c];
        }
      }
    }
    return std::sqrt(error / norm);
  }

  /** Flux (W, summed over channels) of `image` on the receivers. */
  double Flux(const Image& image) const
  {
    double flux = 0.0;
    for (std::size_t p = 0; p < this->Area.size(); ++p)
    {
      flux += this->Area[p] * (image[3 * p] + image[3 * p + 1] + image[3 * p + 2]);
    }
    return flux;
  }
};

/**
 * Flicker: the temporal standard deviation of each receiver pixel over the frames,
 * RMS over the pixels, relative to the mean over frames and pixels.
 */
double Flicker(const std::vector<Image>& frames, const Truth& truth)
{
  double variance = 0.0, mean = 0.0;
  std::size_t count = 0;
  for (std::size_t p = 0; p < truth.Area.size(); ++p)
  {
    if (truth.Area[p] <= 0.0)
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      double sum = 0.0, sum2 = 0.0;
      for (const Image& f : frames)
      {
        sum += f[3 * p + c];
        sum2 += f[3 * p + c] * f[3 * p + c];
      }
      const double m = sum / frames.size();
      variance += std::max(sum2 / frames.size() - m * m, 0.0);
      mean += m;
      ++count;
    }
  }
  return std::sqrt(variance / count) / (mean / count);
}

bool AllFinite(const Image& image)
{
  return std::all_of(image.begin(), image.end(), [](double x) { return std::isfinite(x); });
}
}

/** Flicker and relative L2 of 32 frames of a still scene, raw and denoised. */
struct StillFigures
{
  double RawFlicker = 0.0, DenoisedFlicker = 0.0, RawL2 = 0.0, DenoisedL2 = 0.0;

  StillFigures(const char* scene, int size, vtkIdType photons, int historyIteration = 0)
  {
    Frame f(size, scene);
    f.Pass->Photons = photons;
    f.Pass->GetDenoiser()->SetHistoryIteration(historyIteration);
    std::vector<Image> raw, denoised;
    for (int frame = 0; frame < 32; ++frame)
    {
      f.Window->Render();
      EXPECT_TRUE(f.Pass->GetLastFrameHadCaustics());
      raw.push_back(f.Raw());
      denoised.push_back(f.Denoised());
    }
    const Truth truth(f.Renderer, size);
    for (int frame = 0; frame < 32; ++frame)
    {
      this->RawL2 += truth.RelativeL2(raw[frame]) / 32.0;
      this->DenoisedL2 += truth.RelativeL2(denoised[frame]) / 32.0;
    }
    // The flicker once the history is there (the last 24 frames).
    this->RawFlicker = Flicker({ raw.begin() + 8, raw.end() }, truth);
    this->DenoisedFlicker = Flicker({ denoised.begin() + 8, denoised.end() }, truth);
    std::cout << scene << ", history from iteration " << historyIteration << ": flicker raw "
              << this->RawFlicker << ", denoised " << this->DenoisedFlicker << " ("
              << this->RawFlicker / this->DenoisedFlicker
              << "x less); relative L2 over 32 frames raw " << this->RawL2 << ", denoised "
              << this->DenoisedL2 << " (" << this->DenoisedL2 / this->RawL2 << " of it)\n";
  }
};

// 32 frames of the ball lens, 4096 photons each at 128^2: the denoised caustic
// flickers far less than the raw estimate and is closer to the truth than it, on
// average over the 32 frames.
TEST(SVGFDenoiser, StillBallLensFlickersLessAndStaysAccurate)
{
  const StillFigures figures("ball-lens", 128, 4096);
  EXPECT_GE(figures.RawFlicker / figures.DenoisedFlicker, FLICKER_BALL);
  EXPECT_LE(figures.DenoisedL2, L2_BALL * figures.RawL2);
}

// The same on the ring's nephroid, a mirror caustic with a sharp cusp, seen past
// the mirror (the opaque G-buffer holds it beside the receiver).
TEST(SVGFDenoiser, StillRingFlickersLessAndStaysAccurate)
{
  const StillFigures figures("ring", 128, 4096);
  EXPECT_GE(figures.RawFlicker / figures.DenoisedFlicker, FLICKER_RING);
  EXPECT_LE(figures.DenoisedL2, L2_RING * figures.RawL2);
}

// Why the history is the unfiltered colour (HistoryIteration 0), not the first
// a-trous iteration's output as in SVGF (1): that feeds the blur back every frame,
// and the sharp nephroid ends up much farther from the truth.
TEST(SVGFDenoiser, UnfilteredHistoryIsLessBiased)
{
  const StillFigures svgf("ring", 128, 4096, 1);
  const StillFigures unfiltered("ring", 128, 4096, 0);
  EXPECT_LE(unfiltered.DenoisedL2, HISTORY_GAIN * svgf.DenoisedL2);
}

// The ball jumps sideways after 8 frames: the denoised caustic is at once (at most 4
// frames were asked) as close to the new truth as the raw estimate is on average,
// and stays there (no ghost of the old caustic).
TEST(SVGFDenoiser, FollowsAStepWithoutAGhost)
{
  const int size = 128;
  Frame f(size);
  for (int frame = 0; frame < 8; ++frame)
  {
    f.Window->Render();
  }
  vtkActor* ball = f.Ball();
  ASSERT_NE(ball, nullptr);
  ball->AddPosition(0.6, 0.0, 0.3);
  std::vector<Image> raw, denoised;
  for (int frame = 0; frame < 12; ++frame)
  {
    f.Window->Render();
    raw.push_back(f.Raw());
    denoised.push_back(f.Denoised());
  }
  const Truth truth(f.Renderer, size);
  double rawL2 = 0.0;
  std::vector<double> errors;
  for (std::size_t frame = 0; frame < raw.size(); ++frame)
  {
    rawL2 += truth.RelativeL2(raw[frame]) / raw.size();
    errors.push_back(truth.RelativeL2(denoised[frame]));
  }
  // Settled: from this frame on, never worse than the raw estimate's mean error.
  std::size_t lag = errors.size();
  while (lag > 0 && errors[lag - 1] <= rawL2)
  {
    --lag;
  }
  double after = 0.0;
  for (std::size_t frame = lag; frame < errors.size(); ++frame)
  {
    after = std::max(after, errors[frame]);
  }
  std::cout << "after the step: raw relative L2 " << rawL2 << "; denoised, frame by frame:";
  for (double e : errors)
  {
    std::cout << " " << e;
  }
  std::cout << "; settled after " << lag << " frames, then at most " << after << "\n";
  EXPECT_LE(lag, STEP_LAG);
  EXPECT_LE(after, STEP_AFTER * rawL2);
}

// The ball glides 5 cm a frame over the floor for 16 frames: in each of the last
// four frames the denoised caustic is closer to that frame's truth than the raw
// estimate is on average (it lags the moving light by no ghost).
TEST(SVGFDenoiser, FollowsAMovingBall)
{
  const int size = 128;
  Frame f(size);
  vtkActor* ball = f.Ball();
  ASSERT_NE(ball, nullptr);
  double rawL2 = 0.0, worst = 0.0;
  for (int frame = 0; frame < 16; ++frame)
  {
    ball->AddPosition(0.05, 0.0, 0.0);
    f.Window->Render();
    if (frame >= 12)
    {
      const Truth truth(f.Renderer, size, 250000);
      rawL2 += truth.RelativeL2(f.Raw()) / 4.0;
      worst = std::max(worst, truth.RelativeL2(f.Denoised()));
    }
  }
  std::cout << "moving ball: raw relative L2 " << rawL2 << ", denoised at most " << worst << " ("
            << worst / rawL2 << " of it)\n";
  EXPECT_LE(worst, MOVING * rawL2);
}

// A camera cut (a view of other receivers), an explicit reset and a resize: the
// first denoised frame after each is the frame a fresh denoiser makes of the same
// input, and finite.
TEST(SVGFDenoiser, CarriesNoHistoryOverACutAResetOrAResize)
{
  const int size = 96;
  Frame f(size);
  // A top view of the floor beside the caustic, then of the caustic: no pixel of
  // the second view shows what the first showed.
  auto topView = [](vtkRenderer* renderer, double x)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(x, 6.0, 0.0);
    camera->SetFocalPoint(x, 0.0, 0.0);
    camera->SetViewUp(0.0, 0.0, -1.0);
    camera->SetViewAngle(20.0);
    renderer->ResetCameraClippingRange();
  };
  topView(f.Renderer, -3.0);
  for (int frame = 0; frame < 6; ++frame)
  {
    f.Window->Render();
  }
  // The next frame of `f` against a fresh pass's first frame of the same input.
  auto compare = [&](const char* what, int width, int height, bool cpuKnows)
  {
    Frame fresh(size);
    topView(fresh.Renderer, 0.0);
    fresh.Window->SetSize(width, height);
    fresh.Pass->Seed = f.Pass->Seed;
    f.Window->Render();
    fresh.Window->Render();
    ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics()) << what;
    ASSERT_TRUE(fresh.Pass->GetLastFrameHadCaustics()) << what;
    const Image a = f.Denoised(), b = fresh.Denoised();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(AllFinite(a)) << what;
    double total = 0.0, difference = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      total += std::abs(b[i]);
      difference = std::max(difference, std::abs(a[i] - b[i]));
    }
    EXPECT_GT(total, 0.0) << what << ": the view shows the caustic";
    EXPECT_EQ(difference, 0.0) << what << ": the same as a fresh start";
    // A cut is found on the GPU (too few pixels reproject): the CPU knows no reason.
    EXPECT_EQ(f.Pass->GetDenoiser()->GetFramesSinceReset() == 1, cpuKnows) << what;
  };
  topView(f.Renderer, 0.0);
  compare("camera cut", size, size, false);

  for (int frame = 0; frame < 4; ++frame)
  {
    f.Window->Render();
  }
  f.Pass->ResetDenoiserHistory();
  compare("reset", size, size, true);

  for (int frame = 0; frame < 4; ++frame)
  {
    f.Window->Render();
  }
  f.Window->SetSize(80, 72);
  compare("resize", 80, 72, true);
}

// A still input (the same estimate every frame): after 16 frames the denoised flux
// on the receivers is the input's (1 % was asked).
TEST(SVGFDenoiser, KeepsTheFluxOfAStillInput)
{
  const int size = 128;
  Frame f(size);
  f.Pass->FreshSeeds = false;
  f.Pass->Photons = 65536;
  for (int frame = 0; frame < 16; ++frame)
  {
    f.Window->Render();
  }
  const Truth truth(f.Renderer, size);
  const double raw = truth.Flux(f.Raw()), denoised = truth.Flux(f.Denoised());
  std::cout << "flux raw " << raw << " W, denoised " << denoised << " W (ratio " << denoised / raw
            << ")\n";
  EXPECT_GT(raw, 0.0);
  EXPECT_NEAR(denoised / raw, 1.0, FLUX);
}

// NaN and +Inf texels in the input: every denoised pixel stays finite, over frames.
TEST(SVGFDenoiser, NeverSpreadsNaN)
{
  const int size = 96;
  Frame f(size);
  f.Pass->Poison = true;
  for (int frame = 0; frame < 6; ++frame)
  {
    f.Window->Render();
    if (frame == 0)
    {
      vtkNew<vtkImageData> mask;
      ASSERT_TRUE(f.Pass->ReadBuffer("ReceiverMask", mask));
      const vtkIdType centre = (size / 2) * size + size / 2;
      ASSERT_EQ(mask->GetPointData()->GetArray(0)->GetComponent(centre, 0), 1.0)
        << "the poisoned texels are on a receiver";
    }
    const Image raw = f.Raw(), denoised = f.Denoised();
    EXPECT_FALSE(AllFinite(raw)) << "the input has them";
    EXPECT_TRUE(AllFinite(denoised)) << "frame " << frame;
    EXPECT_TRUE(std::all_of(denoised.begin(), denoised.end(), [](double x) { return x >= 0.0; }));
  }
}


namespace
{
/**
 * A rigid motion of a ball-lens frame, frame after frame: every actor (as its user
 * matrix), and with `all` the light and the camera too; else only the receiver (the
 * floor), under a still ball and light.
 */
struct RigidMotion
{
  Frame& F;
  bool All;
  double LightPosition[3], LightFocal[3];
  double Eye[3], Focal[3], Up[3];
  vtkSmartPointer<vtkAssembly> Group; // with `grouped`: every actor, moved as one

  RigidMotion(Frame& f, bool all, bool grouped = false)
    : F(f)
    , All(all)
  {
    if (grouped)
    {
      this->Group = vtkSmartPointer<vtkAssembly>::New();
      std::vector<vtkActor*> actors;
      vtkPropCollection* props = f.Renderer->GetViewProps();
      props->InitTraversal();
      while (vtkProp* prop = props->GetNextProp())
      {
        if (auto* actor = vtkActor::SafeDownCast(prop))
        {
          actors.push_back(actor);
        }
      }
      for (vtkActor* actor : actors)
      {
        this->Group->AddPart(actor);
        f.Renderer->RemoveActor(actor);
      }
      f.Renderer->AddActor(this->Group);
    }
    vtkLight* light = Light();
    light->GetPosition(this->LightPosition);
    light->GetFocalPoint(this->LightFocal);
    vtkCamera* camera = f.Renderer->GetActiveCamera();
    camera->GetPosition(this->Eye);
    camera->GetFocalPoint(this->Focal);
    camera->GetViewUp(this->Up);
  }

  vtkLight* Light()
  {
    vtkLightCollection* lights = this->F.Renderer->GetLights();
    lights->InitTraversal();
    return lights->GetNextItem();
  }

  /** Frame k: translated by k `step` (m) after turning k `degrees` about the vertical axis. */
  void Place(int k, const double step[3], double degrees)
  {
    vtkNew<vtkTransform> motion;
    motion->Translate(k * step[0], k * step[1], k * step[2]);
    motion->RotateY(k * degrees);
    if (this->Group)
    {
      this->Group->SetUserMatrix(motion->GetMatrix());
    }
    vtkPropCollection* props = this->F.Renderer->GetViewProps();
    props->InitTraversal();
    while (vtkProp* prop = props->GetNextProp())
    {
      auto* actor = vtkActor::SafeDownCast(prop);
      if (!this->Group && actor &&
        (this->All ||
          vtkCausticsMaterial::Classify(actor, 0.3) == vtkCausticsMaterial::ROLE_RECEIVER))
      {
        actor->SetUserMatrix(motion->GetMatrix());
      }
    }
    if (!this->All)
    {
      return;
    }
    double x[3];
    vtkLight* light = Light();
    motion->TransformPoint(this->LightPosition, x);
    light->SetPosition(x);
    motion->TransformPoint(this->LightFocal, x);
    light->SetFocalPoint(x);
    vtkCamera* camera = this->F.Renderer->GetActiveCamera();
    motion->TransformPoint(this->Eye, x);
    camera->SetPosition(x);
    motion->TransformPoint(this->Focal, x);
    camera->SetFocalPoint(x);
    motion->TransformVector(this->Up, x);
    camera->SetViewUp(x);
  }
};

/** Raw and denoised frames of a sequence and their figures against one truth. */
struct Sequence
{
  std::vector<Image> Raw, Denoised;

  /** Flicker (frames `from` on) and mean relative L2 (frames `from` on), raw or denoised. */
  double FlickerOf(bool denoised, const Truth& truth, std::size_t from) const
  {
    const std::vector<Image>& frames = denoised ? this->Denoised : this->Raw;
    return Flicker({ frames.begin() + from, frames.end() }, truth);
  }
  double L2Of(bool denoised, const Truth& truth, std::size_t from) const
  {
    const std::vector<Image>& frames = denoised ? this->Denoised : this->Raw;
    double sum = 0.0;
    for (std::size_t k = from; k < frames.size(); ++k)
    {
      sum += truth.RelativeL2(frames[k]) / (frames.size() - from);
    }
    return sum;
  }
  double WorstL2(const Truth& truth, std::size_t from) const
  {
    double worst = 0.0;
    for (std::size_t k = from; k < this->Denoised.size(); ++k)
    {
      worst = std::max(worst, truth.RelativeL2(this->Denoised[k]));
    }
    return worst;
  }
};
}

// Per-actor motion vectors. Three sequences of 16 frames of the ball lens at 96^2,
// with the same seeds, and one truth: the image's truth is the same in every frame of
// each. (1) Still. (2) Everything (floor, ball, light, camera) moves as one rigid body,
// 0.15 m up, 5 cm sideways and 3 degrees about the vertical a frame: the receiver
// keeps its history (followed with its actor's matrices, since what lights it made
// the same motion, which also tells the denoiser that the light on it is unchanged),
// so the caustic flickers about as little as the still one and is as accurate;
// without motion vectors the floor failed the same-surface test every frame (it rose
// 0.15 m, past the 0.1 m tolerance) and kept no history. (3) The floor alone slides
// 5 cm a frame under the still ball and light: its caustic stays where it is in the
// world, and so does the reprojection (following the floor would drag the caustic's
// history along with it): no smear. A moving receiver counts as a change of the light
// (it may shadow others), so the colour test runs and costs some flicker there.
// (4) As (2), with the floor and the ball parts of one vtkAssembly that moves: the
// motion is the assembly path's matrix, not the actors' own (which stay still);
// taking the actors' own, as before, gave flicker 1.97x and relative L2 4.87x the
// still sequence's (the motion failed the vertex check: no history).
TEST(SVGFDenoiser, FollowsActorsThatMove)
{
  const int size = 96, frames = 16, settled = 6, runs = 4;
  const double up[3] = { 0.05, 0.15, 0.0 }, slide[3] = { 0.05, 0.0, 0.0 }, none[3] = { 0, 0, 0 };
  Sequence sequences[runs];
  std::unique_ptr<Truth> truth;
  for (int run = 0; run < runs; ++run)
  {
    Frame f(size);
    RigidMotion motion(f, run != 2, run == 3);
    const bool rigid = run == 1 || run == 3;
    for (int k = 0; k < frames; ++k)
    {
      motion.Place(k, run == 0 ? none : rigid ? up : slide, rigid ? 3.0 : 0.0);
      f.Window->Render();
      ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics());
      sequences[run].Raw.push_back(f.Raw());
      sequences[run].Denoised.push_back(f.Denoised());
    }
    if (run == 0)
    {
      truth.reset(new Truth(f.Renderer, size));
    }
  }
  const char* names[runs] = { "still", "moving with its light", "floor sliding under the caustic",
    "moving with its light, as one assembly" };
  double flicker[runs], l2[runs], rawL2[runs];
  for (int run = 0; run < runs; ++run)
  {
    const Sequence& s = sequences[run];
    flicker[run] = s.FlickerOf(true, *truth, settled);
    l2[run] = s.L2Of(true, *truth, settled);
    rawL2[run] = s.L2Of(false, *truth, settled);
    std::cout << names[run] << ": flicker raw " << s.FlickerOf(false, *truth, settled)
              << ", denoised " << flicker[run] << "; relative L2 raw " << rawL2[run]
              << ", denoised " << l2[run] << " (worst frame " << s.WorstL2(*truth, settled)
              << ")\n";
  }
  std::cout << "against the still sequence: moving with its light, flicker "
            << flicker[1] / flicker[0] << ", relative L2 " << l2[1] / l2[0]
            << "; floor sliding, flicker " << flicker[2] / flicker[0] << ", worst frame "
            << sequences[2].WorstL2(*truth, settled) / l2[0] << "; as one assembly, flicker "
            << flicker[3] / flicker[0] << ", relative L2 " << l2[3] / l2[0] << "\n";
  EXPECT_LE(flicker[1], RIGID_FLICKER * flicker[0]);
  EXPECT_LE(l2[1], RIGID_L2 * l2[0]);
  EXPECT_LE(flicker[3], RIGID_FLICKER * flicker[0]);
  EXPECT_LE(l2[3], RIGID_L2 * l2[0]);
  EXPECT_LE(flicker[2], SLIDE_FLICKER * flicker[0]);
  EXPECT_LE(sequences[2].WorstL2(*truth, settled), SLIDE_L2 * l2[0]);
}

// Where the denoiser's error on the pool and the ring comes from (docs/benchmarks.md,
// "Reading the temporal results"): the cascaded technique at 128^2, 16 still frames,
// the last one against a 2 M photon truth with the reference's kernel of 2 pixel
// footprints (its default) and of 1 (the benchmark's): raw, the raw mean of the 16
// frames (what a perfect temporal filter reaches), the denoiser, its temporal part
// alone (no a-trous) and with 1 and 2 a-trous iterations; and each one's error after
// 1, 2, 3, 4, 6, 8, 12 and 16 frames from a fresh start. Not run by default:
// --gtest_also_run_disabled_tests --gtest_filter='*ErrorByPart*'.
TEST(SVGFDenoiser, DISABLED_ErrorByPart)
{
  const int size = 128, frames = 16;
  for (const char* scene : { "pool", "ring" })
  {
    std::unique_ptr<Truth> truth, sharp;
    const int iterations[] = { -1, 5, 0, 1, 2 }; // -1: not denoised
    for (int atrous : iterations)
    {
      vtkNew<vtkOpenGLRenderer> renderer;
      vtkNew<vtkRenderWindow> window;
      vtkNew<vtkCausticsBuiltinScene> builtin;
      vtkNew<vtkCausticsCascadedPhotonPass> pass;
      builtin->SetSceneName(scene);
      ASSERT_TRUE(builtin->Populate(renderer));
      pass->SetDenoise(atrous >= 0);
      pass->GetDenoiser()->SetAtrousIterations(std::max(atrous, 0));
      pass->KeepBuffersOn();
      renderer->SetPass(pass);
      window->SetOffScreenRendering(1);
      window->SetMultiSamples(0);
      window->SetSize(size, size);
      window->AddRenderer(renderer);
      Image mean, last;
      std::vector<Image> all;
      for (int k = 0; k < frames; ++k)
      {
        window->Render();
        vtkNew<vtkImageData> image;
        ASSERT_TRUE(pass->ReadBuffer("CausticIrradiance", image));
        vtkDataArray* a = image->GetPointData()->GetArray(0);
        last.assign(3 * a->GetNumberOfTuples(), 0.0);
        mean.resize(last.size(), 0.0);
        for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
        {
          for (int c = 0; c < 3; ++c)
          {
            last[3 * p + c] = a->GetComponent(p, c);
            mean[3 * p + c] += last[3 * p + c] / frames;
          }
        }
        all.push_back(last);
      }
      if (!truth)
      {
        truth.reset(new Truth(renderer, size, 2000000));
        sharp.reset(new Truth(renderer, size, 2000000, 1.0));
      }
      auto report = [&](const std::string& what, const Image& image)
      {
        std::cout << scene << ", " << what << ": relative L2 " << truth->RelativeL2(image)
                  << " (kernel 2 px), " << sharp->RelativeL2(image)
                  << " (1 px); flux ratio " << truth->Flux(image) / truth->Flux(truth->E)
                  << "\n";
      };
      if (atrous < 0)
      {
        report("raw, the last frame", last);
        report("raw, the mean of 16 frames", mean);
      }
      else
      {
        report("denoised, " + std::to_string(atrous) + " a-trous iterations", last);
      }
      std::cout << "  frame by frame (1 px):";
      for (int k : { 0, 1, 2, 3, 5, 7, 11, 15 })
      {
        std::cout << " " << k + 1 << ": " << sharp->RelativeL2(all[k]);
      }
      std::cout << "\n";
      renderer->SetPass(nullptr);
      pass->ReleaseGraphicsResources(window);
    }
  }
}

// An actor that appears (a diffuse box beside the caustic, out of its light) gets no
// history, and the others keep theirs: the frame after it appears is about as close to
// the truth as the one before, where dropping every history (what a change of the
// scene's structure did before per-actor motion) makes it much worse.
TEST(SVGFDenoiser, KeepsTheHistoryWhenAnActorAppears)
{
  const int size = 96;
  double before[2], after[2];
  std::unique_ptr<Truth> truth;
  for (int run = 0; run < 2; ++run)
  {
    Frame f(size);
    vtkNew<vtkCubeSource> cube;
    cube->SetCenter(-2.0, 0.25, 2.0);
    cube->SetXLength(0.5);
    cube->SetYLength(0.5);
    cube->SetZLength(0.5);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cube->GetOutputPort());
    vtkNew<vtkActor> box;
    box->SetMapper(mapper);
    std::vector<Image> denoised;
    for (int k = 0; k < 9; ++k)
    {
      if (k == 8)
      {
        f.Renderer->AddActor(box);
        if (run == 1)
        {
          f.Pass->ResetDenoiserHistory(); // as a change of structure did
        }
      }
      f.Window->Render();
      denoised.push_back(f.Denoised());
    }
    if (!truth)
    {
      truth.reset(new Truth(f.Renderer, size));
    }
    before[run] = truth->RelativeL2(denoised[7]);
    after[run] = truth->RelativeL2(denoised[8]);
  }
  std::cout << "an actor appears: relative L2 " << before[0] << " before, " << after[0]
            << " after (" << after[0] / before[0] << "x); dropping every history: "
            << after[1] << " (" << after[1] / before[1] << "x)\n";
  EXPECT_LE(after[0], APPEAR * before[0]);
}
