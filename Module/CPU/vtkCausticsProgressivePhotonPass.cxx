#include "vtkCausticsProgressivePhotonPass.h"

#include "vtkCausticsGLUtilities.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsTechniques.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCausticsProgressivePhotonPass);

namespace
{
/** Running mean of one RGB image (3 floats per pixel). */
struct RunningMean
{
  std::vector<float> Mean;

  void Reset(std::size_t pixels) { this->Mean.assign(3 * pixels, 0.0f); }

  /** Adds frame `count` (1 for the first) of `array` (3 components per pixel). */
  void Add(vtkDataArray* array, int count)
  {
    const vtkIdType pixels = static_cast<vtkIdType>(this->Mean.size() / 3);
    if (!array || array->GetNumberOfTuples() != pixels || array->GetNumberOfComponents() < 3)
    {
      return;
    }
    const float weight = 1.0f / static_cast<float>(count);
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        float& mean = this->Mean[3 * p + c];
        mean += (static_cast<float>(array->GetComponent(p, c)) - mean) * weight;
      }
    }
  }
};

/**
 * The scene without the triangles the reference refuses: those with a vertex whose
 * position or normal is not finite (the extractor has warned of them already; the
 * GPU passes leave them out as the rasterizer does). Returns false when there are
 * none, `clean` untouched.
 */
bool LeaveOutBrokenTriangles(const caustics::SceneData& scene, caustics::SceneData& clean)
{
  auto broken = [](const caustics::Mesh& mesh, std::uint32_t v)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::size_t i = 3 * static_cast<std::size_t>(v) + k;
      if (i >= mesh.positions.size() || i >= mesh.normals.size() ||
        !std::isfinite(mesh.positions[i]) || !std::isfinite(mesh.normals[i]))
      {
        return true;
      }
    }
    return false;
  };
  const bool any = std::any_of(scene.Meshes.begin(), scene.Meshes.end(),
    [](const caustics::Mesh& mesh)
    {
      return !std::all_of(mesh.positions.begin(), mesh.positions.end(),
               [](float x) { return std::isfinite(x); }) ||
        !std::all_of(
          mesh.normals.begin(), mesh.normals.end(), [](float x) { return std::isfinite(x); });
    });
  if (!any)
  {
    return false;
  }
  clean = scene;
  for (caustics::Mesh& mesh : clean.Meshes)
  {
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    {
      if (!broken(mesh, mesh.indices[t]) && !broken(mesh, mesh.indices[t + 1]) &&
        !broken(mesh, mesh.indices[t + 2]))
      {
        kept.insert(kept.end(), mesh.indices.begin() + t, mesh.indices.begin() + t + 3);
      }
    }
    mesh.indices.swap(kept);
    // Vertices no triangle uses any more must still be finite for the reference.
    for (float& x : mesh.positions)
    {
      x = std::isfinite(x) ? x : 0.0f;
    }
    for (float& x : mesh.normals)
    {
      x = std::isfinite(x) ? x : 0.0f;
    }
  }
  return true;
}

/**
 * Writes an RGB image into a width x height RGBA32F texture (alpha 0), through
 * `rgba`, a staging buffer kept between frames (resized only with the image).
 */
void Upload(const std::vector<float>& rgb, int width, int height, vtkTextureObject* target,
  std::vector<float>& rgba)
{
  rgba.assign(4 * static_cast<std::size_t>(width) * height, 0.0f);
  for (std::size_t p = 0; 3 * p + 2 < rgb.size() && 4 * p + 3 < rgba.size(); ++p)
  {
    rgba[4 * p] = rgb[3 * p];
    rgba[4 * p + 1] = rgb[3 * p + 1];
    rgba[4 * p + 2] = rgb[3 * p + 2];
  }
  glTextureSubImage2D(
    target->GetHandle(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
}
}

struct vtkCausticsProgressivePhotonPass::Internals
{
  vtkNew<vtkCausticsReferenceRenderer> Tracer;
  std::string SceneKey;  // the accumulated scene's hash
  std::string FailedKey; // a scene the tracer refused (said once; not retried)
  caustics::SceneData Clean; // the snapshot without broken triangles, when it has some
  int Frames = 0;
  long long Photons = 0;
  unsigned int Estimates = 0; // estimates traced since construction: never reset
  int Width = 0, Height = 0;
  RunningMean Caustic;
  RunningMean Volume;
  bool HasVolume = false;
  std::vector<float> Staging; // the RGBA texels uploaded each frame
};

vtkCausticsProgressivePhotonPass::vtkCausticsProgressivePhotonPass()
  : Internal(new Internals)
{
  vtkCausticsReferenceRenderer* tracer = this->Internal->Tracer;
  tracer->UseCacheOff();            // a frame's estimate is never worth keeping
  tracer->CameraSeesRefractorsOff(); // irradiance on the opaque surfaces, as the GPU passes
  this->SetSpecularShadows(true);   // its photons replace the light specular actors block
  this->SetRefractionTracing(true); // the base pass's camera view of glass and mirrors
}

vtkCausticsProgressivePhotonPass::~vtkCausticsProgressivePhotonPass() = default;

void vtkCausticsProgressivePhotonPass::RegisterTechnique()
{
  vtkCausticsTechniques::Register("cpu-progressive",
    "the CPU reference's Embree photon tracer, accumulated over frames while nothing moves "
    "(for machines without a GPU; docs/technique-cpu-progressive.md)",
    [] { return vtkSmartPointer<vtkCausticsProgressivePhotonPass>::New(); });
}

vtkCausticsRenderPass::CausticNeeds vtkCausticsProgressivePhotonPass::GetCausticNeeds()
{
  CausticNeeds needs;
  needs.LitSpecular = true;   // a light must reach a specular actor
  needs.LightBuffers = false; // photons are traced on the CPU
  return needs;
}

int vtkCausticsProgressivePhotonPass::GetNumberOfAccumulatedFrames() const
{
  return this->Internal->Frames;
}

long long vtkCausticsProgressivePhotonPass::GetNumberOfAccumulatedPhotons() const
{
  return this->Internal->Photons;
}

void vtkCausticsProgressivePhotonPass::Restart()
{
  this->Internal->SceneKey.clear();
  this->Internal->Frames = 0;
  this->Internal->Photons = 0;
}

bool vtkCausticsProgressivePhotonPass::RenderCausticIrradiance(const FrameInputs& in)
{
  auto& s = *this->Internal;
  if (!this->Accumulate(in))
  {
    return false;
  }
  this->StartStage("cpu upload");
  Upload(s.Caustic.Mean, in.Width, in.Height, in.CausticIrradiance, s.Staging);
  this->StopStage("cpu upload");
  return true;
}

bool vtkCausticsProgressivePhotonPass::Accumulate(const FrameInputs& in)
{
  auto& s = *this->Internal;
  vtkCausticsReferenceRenderer* tracer = s.Tracer;
  const long long photons =
    static_cast<long long>(this->GetLightBufferResolution()) * this->GetLightBufferResolution();
  tracer->SetPhotonsPerLight(photons);
  tracer->SetNumberOfThreads(this->NumberOfThreads);
  tracer->SetKernelRadiusPixels(this->KernelRadiusPixels);
  tracer->SetSeed(1);
  const caustics::SceneData& scene = *in.Scene;
  const bool scattering = scene.Participating.enabled &&
    scene.Participating.sigmaS[0] + scene.Participating.sigmaS[1] + scene.Participating.sigmaS[2] >
      0.0;
  tracer->SetVolumePhotonsPerLight(scattering ? photons : 0);
  // Any change of what the estimate depends on (the seed aside) starts it again.
  const std::string key = vtkCausticsReferenceRenderer::ComputeCacheKey(scene, tracer->GetSettings());
  if (key != s.SceneKey || in.Width != s.Width || in.Height != s.Height || !this->Progressive)
  {
    s.SceneKey = key;
    s.Width = in.Width;
    s.Height = in.Height;
    s.Frames = 0;
    s.Photons = 0;
    const std::size_t pixels = static_cast<std::size_t>(in.Width) * in.Height;
    s.Caustic.Reset(pixels);
    s.Volume.Reset(pixels);
  }
  s.HasVolume = scattering;
  if (s.Frames >= this->MaximumFrames)
  {
    return true; // converged as far as asked: the estimate stays
  }
  if (key == s.FailedKey)
  {
    return false; // refused before, with its reason: no caustics until it changes
  }
  this->StartStage("cpu photon tracing");
  // A new seed for every estimate, so that frames are independent (not
  // progressive, one estimate is shown per frame and a still scene must flicker
  // as that estimate does) and an accumulation never reuses one. The seeds start
  // past the reference renderer's own (1 for ground truths, 2 for the benchmark's
  // ladder), whose photons with the same index would otherwise be the same.
  constexpr unsigned int FirstSeed = 1000;
  tracer->SetSeed(FirstSeed + s.Estimates++);
  tracer->SetScene(LeaveOutBrokenTriangles(scene, s.Clean) ? s.Clean : scene);
  tracer->SetImageSize(in.Width, in.Height);
  const bool traced = tracer->Update(); // on failure the tracer reports why, once
  this->StopStage("cpu photon tracing");
  if (!traced)
  {
    s.FailedKey = key;
    return false;
  }
  ++s.Frames;
  s.Photons += tracer->GetNumberOfPhotonsEmitted() / std::max<std::size_t>(scene.Lights.size(), 1);
  vtkPointData* output = tracer->GetOutput()->GetPointData();
  s.Caustic.Add(output->GetArray("CausticIrradiance"), s.Frames);
  if (scattering)
  {
    s.Volume.Add(output->GetArray("VolumeCausticRadiance"), s.Frames);
  }
  return true;
}

bool vtkCausticsProgressivePhotonPass::RenderVolumeRadiance(
  const FrameInputs& in, vtkTextureObject* target)
{
  auto& s = *this->Internal;
  if (!s.HasVolume || s.Frames == 0)
  {
    return false;
  }
  caustics::gl::EnsureTexture(target, in.Window, in.Width, in.Height, GL_RGBA32F);
  Upload(s.Volume.Mean, in.Width, in.Height, target, s.Staging);
  return true;
}

void vtkCausticsProgressivePhotonPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumFrames: " << this->MaximumFrames << "\n";
  os << indent << "Progressive: " << this->Progressive << "\n";
  os << indent << "KernelRadiusPixels: " << this->KernelRadiusPixels << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "AccumulatedFrames: " << this->Internal->Frames << "\n";
  os << indent << "AccumulatedPhotons: " << this->Internal->Photons << " per light\n";
}
