#include "CausticsBenchTemporal.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsProgressivePhotonPass.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace caustics_bench
{
vtkSmartPointer<vtkCausticsReferenceRenderer> MakeReference(vtkRenderer* renderer, int size,
  double photons, double kernelPixels, unsigned int seed, bool cache)
{
  auto reference = vtkSmartPointer<vtkCausticsReferenceRenderer>::New();
  reference->SetInputRenderer(renderer);
  reference->SetImageSize(size, size);
  reference->SetPhotonsPerLight(static_cast<vtkIdType>(photons));
  if (kernelPixels > 0.0)
  {
    reference->SetKernelRadiusPixels(kernelPixels);
  }
  else
  {
    reference->PixelFootprintEstimateOn(); // --reference-kernel pixel
  }
  reference->SetSeed(seed);
  reference->SetUseCache(cache);
  // The techniques output the irradiance at each pixel's nearest opaque surface
  // (the pool's floor under the water, the floor behind the ball): compare with
  // the reference's irradiance at the same points.
  reference->CameraSeesRefractorsOff();
  return reference;
}

vtkSmartPointer<vtkImageData> ReadCausticIrradiance(vtkCausticsRenderPass* pass, int size)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  if (pass->GetLastFrameHadCaustics())
  {
    if (!pass->ReadBuffer("CausticIrradiance", image))
    {
      throw std::runtime_error("the caustic irradiance could not be read back");
    }
    return image;
  }
  image->SetDimensions(size, size, 1);
  vtkNew<vtkFloatArray> zero;
  zero->SetName("CausticIrradiance");
  zero->SetNumberOfComponents(3);
  zero->SetNumberOfTuples(static_cast<vtkIdType>(size) * size);
  zero->Fill(0.0);
  image->GetPointData()->AddArray(zero);
  return image;
}

std::vector<TemporalVariant> MakeTemporalVariants()
{
  return {
    { "screen-space", "default", [](vtkCausticsRenderPass*) {} },
    { "caustic-maps", "default", [](vtkCausticsRenderPass*) {} },
    // Accumulates while nothing changes and restarts on any change: its lag after a cut.
    { "cpu-progressive", "default", [](vtkCausticsRenderPass*) {} },
    // One estimate of LightBufferResolution^2 photons per frame, a new seed each
    // frame: no accumulation, so no lag, and the noise of one frame, still or moving.
    { "cpu-progressive", "progressive=off",
      [](vtkCausticsRenderPass* pass)
      {
        auto* cpu = vtkCausticsProgressivePhotonPass::SafeDownCast(pass);
        if (!cpu)
        {
          throw std::runtime_error(std::string("cpu-progressive is a ") + pass->GetClassName());
        }
        cpu->ProgressiveOff();
      } },
    // The SVGF stage (docs/denoising.md) on each technique: whether it smears motion
    // shows in the lag and ghosting columns.
    { "screen-space", "denoised", [](vtkCausticsRenderPass* p) { p->DenoiseOn(); } },
    { "caustic-maps", "denoised", [](vtkCausticsRenderPass* p) { p->DenoiseOn(); } },
    { "cpu-progressive", "progressive=off,denoised",
      [](vtkCausticsRenderPass* p)
      {
        if (auto* cpu = vtkCausticsProgressivePhotonPass::SafeDownCast(p))
        {
          cpu->ProgressiveOff();
        }
        p->DenoiseOn();
      } },
    // Cascaded photon tracing (paper 002) is denoised by default (its section 3.3);
    // raw, each frame is a fresh jittered estimate.
    { "cascaded", "default (denoised)", [](vtkCausticsRenderPass*) {} },
    { "cascaded", "denoise=off", [](vtkCausticsRenderPass* p) { p->DenoiseOff(); } },
  };
}

std::vector<TemporalVariant> TemporalVariantsOf(const std::string& technique)
{
  std::vector<TemporalVariant> variants;
  for (const auto& variant : MakeTemporalVariants())
  {
    if (variant.Technique == technique)
    {
      variants.push_back(variant);
    }
  }
  if (variants.empty())
  {
    variants.push_back({ technique, "default", [](vtkCausticsRenderPass*) {} });
  }
  return variants;
}

namespace
{
/** The scene of one sequence as it is posed frame by frame. */
struct Stage
{
  vtkCausticsBuiltinScene* Scene;
  vtkRenderer* Renderer;
};

/**
 * An animated sequence: a built-in scene and how frame k poses it. Frames before the
 * cut move a little each (1/20 s of animation); the cut jumps to a distant pose,
 * held still to the end, so that the lag after it and the flicker of a still scene
 * can be measured.
 */
struct Sequence
{
  const char* Name;
  const char* Scene;
  const char* Description; // for the docs
  std::function<void(const Stage&, int frame, int cut)> Pose;
};

vtkActor* FindActor(vtkRenderer* renderer, const std::string& name)
{
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    if (vtkCausticsMaterial::GetName(actor) == name)
    {
      return actor;
    }
  }
  throw std::runtime_error("the built-in scene has no actor named '" + name + "'");
}

/** Aims the renderer's first (directional) light from elevation/azimuth in degrees. */
void AimLight(vtkRenderer* renderer, double elevation, double azimuth)
{
  vtkLight* light = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  if (!light)
  {
    throw std::runtime_error("the built-in scene has no light");
  }
  const double e = vtkMath::RadiansFromDegrees(elevation);
  const double a = vtkMath::RadiansFromDegrees(azimuth);
  // Position - focal point points to the light (the scene's convention).
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPosition(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
}

const std::vector<Sequence>& Sequences()
{
  static const std::vector<Sequence> sequences = {
    { "pool-waves", "pool",
      "the pool's waves at t = 0.05 k s; at the cut they jump to t = 3 s and freeze",
      [](const Stage& s, int k, int cut) { s.Scene->UpdateTime(k < cut ? 0.05 * k : 3.0); } },
    { "moving-ball", "ball-lens",
      "the glass ball moves 0.1 m a frame along x from x = -0.8 m; at the cut it jumps to "
      "(1.0, 0, -0.6) m and stays",
      [](const Stage& s, int k, int cut)
      {
        vtkActor* ball = FindActor(s.Renderer, "glass ball");
        k < cut ? ball->SetPosition(-0.8 + 0.1 * k, 0.0, 0.0) : ball->SetPosition(1.0, 0.0, -0.6);
      } },
    { "light-sweep", "ring",
      "the light, 20 degrees above the horizon, sweeps 4 degrees of azimuth a frame; at the "
      "cut it jumps to 30 degrees elevation, azimuth 60 degrees, and stays",
      [](const Stage& s, int k, int cut)
      { k < cut ? AimLight(s.Renderer, 20.0, 4.0 * k) : AimLight(s.Renderer, 30.0, 60.0); } },
  };
  return sequences;
}

double Milliseconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

/** The reference of every frame (cached: the held frames after the cut are one file). */
std::vector<vtkSmartPointer<vtkImageData>> RenderReferences(const TemporalSettings& settings,
  const Sequence& sequence, const Stage& stage, TemporalTruth& truth)
{
  std::vector<vtkSmartPointer<vtkImageData>> frames;
  const auto start = std::chrono::steady_clock::now();
  const int cut = settings.Frames / 2;
  for (int k = 0; k < settings.Frames; ++k)
  {
    sequence.Pose(stage, k, cut);
    auto reference = MakeReference(
      stage.Renderer, settings.Size, settings.ReferencePhotons, settings.ReferenceKernel, 1, true);
    if (!reference->Update())
    {
      throw std::runtime_error("the reference failed on sequence '" + std::string(sequence.Name) +
        "', frame " + std::to_string(k) + ": " + reference->GetLastError());
    }
    truth.Rendered += reference->GetLoadedFromCache() ? 0 : 1;
    frames.emplace_back(reference->GetOutput());
  }
  truth.Seconds = Milliseconds(start) / 1000.0;
  return frames;
}

/** Frames of one variant: warm-up at frame 0's pose, then every frame timed and compared. */
void MeasureFrames(const TemporalSettings& settings, const Sequence& sequence, const Stage& stage,
  vtkRenderWindow* window, vtkCausticsRenderPass* pass,
  const std::vector<vtkSmartPointer<vtkImageData>>& truths, TemporalRow& row)
{
  vtkNew<vtkCausticsTemporalMetrics> metrics;
  metrics->SetArrayName("CausticIrradiance");
  metrics->SetMaskArrayName("ReceiverMask");
  metrics->SetAreaArrayName("PixelArea");
  metrics->SetCutFrame(row.Cut);
  sequence.Pose(stage, 0, row.Cut);
  for (int w = 0; w < settings.Warmup; ++w)
  {
    window->Render();
  }
  double total = 0.0;
  for (int k = 0; k < settings.Frames; ++k)
  {
    sequence.Pose(stage, k, row.Cut);
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    row.FrameMilliseconds.push_back(Milliseconds(start));
    total += row.FrameMilliseconds.back();
    // Read back after the timed frame: the render path itself reads nothing back.
    if (!metrics->AddFrame(ReadCausticIrradiance(pass, settings.Size), truths[k]))
    {
      throw std::runtime_error(metrics->GetLastError());
    }
    row.FrameError.push_back(metrics->GetFrameRelativeL2Error(k));
    row.FrameFlux.push_back(metrics->GetFrameFluxRatio(k));
  }
  row.MeanMilliseconds = total / settings.Frames;
  if (!metrics->Compute())
  {
    throw std::runtime_error(metrics->GetLastError());
  }
  row.Metrics = metrics->GetResult();
}

TemporalRow MeasureVariant(const TemporalSettings& settings, const Sequence& sequence,
  const Stage& stage, const TemporalVariant& variant, vtkRenderWindow* window,
  vtkOpenGLRenderer* renderer, const std::vector<vtkSmartPointer<vtkImageData>>& truths,
  caustics_cli::OneLineOutputWindow* messages)
{
  TemporalRow row;
  row.Sequence = sequence.Name;
  row.Technique = variant.Technique;
  row.Variant = variant.Name;
  row.Frames = settings.Frames;
  row.Cut = settings.Frames / 2;
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(variant.Technique);
  renderer->SetPass(pass);
  std::string error;
  try
  {
    variant.Setup(pass);
    if (settings.SmokeResolution > 0)
    {
      pass->SetLightBufferResolution(settings.SmokeResolution);
    }
    MeasureFrames(settings, sequence, stage, window, pass, truths, row);
  }
  catch (const std::exception& e)
  {
    error = e.what();
  }
  const std::string logged = messages->TakeError();
  if (!error.empty() || !logged.empty())
  {
    row.Status = "error: " + (logged.empty() ? error : logged);
    row.Metrics = vtkCausticsTemporalMetrics::Result();
  }
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  messages->TakeError();
  return row;
}

std::string Fixed(double value, int precision)
{
  if (!std::isfinite(value))
  {
    return std::isnan(value) ? "–" : (value > 0 ? "inf" : "-inf");
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(precision) << value;
  return text.str();
}

/** Two significant digits ("0" for exactly 0): flicker spans 0 to 1e-6 to 1e-2. */
std::string Significant(double value)
{
  if (!std::isfinite(value) || value == 0.0)
  {
    return value == 0.0 ? "0" : Fixed(value, 0);
  }
  std::ostringstream text;
  text << std::setprecision(2) << value;
  return text.str();
}

std::string CSVNumber(double value)
{
  std::ostringstream text;
  text << std::setprecision(6) << value;
  return text.str();
}
}

std::vector<std::string> GetSequenceNames()
{
  std::vector<std::string> names;
  for (const auto& sequence : Sequences())
  {
    names.emplace_back(sequence.Name);
  }
  return names;
}

std::vector<TemporalRow> RunTemporal(const TemporalSettings& settings, vtkRenderWindow* window,
  caustics_cli::OneLineOutputWindow* messages, std::vector<TemporalTruth>& truths,
  const std::function<void(const TemporalRow&)>& report)
{
  std::vector<TemporalRow> rows;
  for (const auto& sequence : Sequences())
  {
    if (std::find(settings.Sequences.begin(), settings.Sequences.end(), sequence.Name) ==
      settings.Sequences.end())
    {
      continue;
    }
    vtkNew<vtkOpenGLRenderer> renderer;
    window->AddRenderer(renderer);
    vtkNew<vtkCausticsBuiltinScene> scene;
    scene->SetSceneName(sequence.Scene);
    if (!scene->Populate(renderer))
    {
      throw std::runtime_error(scene->GetLastError());
    }
    // One camera and clipping range for every frame, the reference's and the passes'.
    renderer->ResetCameraClippingRange();
    const Stage stage = { scene, renderer };
    TemporalTruth truth{ sequence.Name, sequence.Scene };
    const auto references = RenderReferences(settings, sequence, stage, truth);
    messages->TakeError();
    truths.push_back(truth);
    std::cout << sequence.Name << ": " << settings.Frames << " reference frames (" << truth.Rendered
              << " rendered, the others cached) in " << Fixed(truth.Seconds, 1) << " s"
              << std::endl;
    for (const auto& technique : settings.Techniques)
    {
      for (const auto& variant : TemporalVariantsOf(technique))
      {
        rows.push_back(MeasureVariant(
          settings, sequence, stage, variant, window, renderer, references, messages));
        report(rows.back());
      }
    }
    window->RemoveRenderer(renderer);
  }
  return rows;
}

std::string MakeTemporalTable(const std::vector<TemporalRow>& rows)
{
  std::ostringstream md;
  md << "| sequence | technique | variant | flicker | moving error | mean rel. L2 | mean flux "
        "ratio | steady error | lag (frames) | ghosting | time / frame |\n";
  md << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const auto& row : rows)
  {
    const auto& m = row.Metrics;
    md << "| " << row.Sequence << " | " << row.Technique
       << (row.Status == "ok" ? "" : " (" + row.Status + ")") << " | " << row.Variant << " | "
       << Significant(m.Flicker) << " | " << Fixed(m.MovingError, 4) << " | "
       << Fixed(m.MeanRelativeL2Error, 4) << " | " << Fixed(m.MeanFluxRatio, 3) << " | "
       << Fixed(m.SteadyError, 4) << " | " << (m.Lag < 0 ? "–" : std::to_string(m.Lag)) << " | "
       << Fixed(m.Ghosting, 2) << " | " << Fixed(row.MeanMilliseconds, 0) << " ms |\n";
  }
  return md.str();
}

std::string DescribeSequences(const TemporalSettings& settings)
{
  std::ostringstream md;
  for (const auto& sequence : Sequences())
  {
    if (std::find(settings.Sequences.begin(), settings.Sequences.end(), sequence.Name) !=
      settings.Sequences.end())
    {
      md << "- `" << sequence.Name << "` (scene `" << sequence.Scene << "`): frame k = 0.."
         << settings.Frames - 1 << ", cut at frame " << settings.Frames / 2 << ": "
         << sequence.Description << ".\n";
    }
  }
  return md.str();
}

std::string WriteTemporalCSV(const std::string& folder, const std::vector<TemporalRow>& rows)
{
  const std::string path = folder + "/temporal.csv", framesPath = folder + "/temporal-frames.csv";
  std::ofstream out(path), frames(framesPath);
  out << "sequence,technique,variant,frames,cut,flicker,moving_error,mean_rel_l2,mean_flux_ratio,"
         "steady_error,lag_frames,ghosting,static_values,moving_values,nonfinite_px,mean_ms,"
         "status\n";
  frames << "sequence,technique,variant,frame,wall_ms,rel_l2,flux_ratio\n";
  for (const auto& row : rows)
  {
    const auto& m = row.Metrics;
    std::string status = row.Status;
    std::replace(status.begin(), status.end(), ',', ';');
    out << row.Sequence << ',' << row.Technique << ',' << row.Variant << ',' << row.Frames << ','
        << row.Cut << ',' << CSVNumber(m.Flicker) << ',' << CSVNumber(m.MovingError) << ','
        << CSVNumber(m.MeanRelativeL2Error) << ',' << CSVNumber(m.MeanFluxRatio) << ','
        << CSVNumber(m.SteadyError) << ',' << m.Lag << ',' << CSVNumber(m.Ghosting) << ','
        << m.StaticValues << ',' << m.MovingValues << ',' << m.NonFinitePixels << ','
        << CSVNumber(row.MeanMilliseconds) << ',' << status << '\n';
    for (std::size_t k = 0; k < row.FrameError.size(); ++k)
    {
      frames << row.Sequence << ',' << row.Technique << ',' << row.Variant << ',' << k << ','
             << CSVNumber(row.FrameMilliseconds[k]) << ',' << CSVNumber(row.FrameError[k]) << ','
             << CSVNumber(row.FrameFlux[k]) << '\n';
    }
  }
  if (!out || !frames)
  {
    throw std::runtime_error("cannot write " + path);
  }
  return path;
}
}
