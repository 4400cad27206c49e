#include "StressSoak.h"

#include "vtkCausticsBuiltinScene.h"
#include "vtkCausticsMaterial.h"
#include "vtkCausticsRenderPass.h"
#include "vtkCausticsTechniques.h"

#include "vtkActor.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkSphereSource.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace stress
{
namespace
{
/** Resident set size of this process, bytes (/proc/self/statm, second field). */
double ResidentBytes()
{
  std::ifstream statm("/proc/self/statm");
  long long size = 0, resident = 0;
  statm >> size >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

/** One frame's figures. GPU pools are judged one by one: each has its own peak. */
struct Sample
{
  vtkCausticsRenderPass::GraphicsMemory Gpu;
  double Rss = 0.0;
  double Heap = 0.0; ///< bytes malloc has handed out and not got back (glibc mallinfo2)
};

double HeapBytes()
{
  const struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd);
}

vtkSmartPointer<vtkActor> MakeActor(vtkAlgorithm* source, double x, double y, double z)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetPosition(x, y, z);
  return actor;
}

/** The three actors that come and go; the glass sphere is made anew each time. */
struct Visitors
{
  vtkNew<vtkSphereSource> SphereSource;
  vtkNew<vtkCubeSource> BoxSource;
  vtkSmartPointer<vtkActor> Actors[3];

  Visitors()
  {
    this->SphereSource->SetRadius(0.4);
    this->BoxSource->SetXLength(0.6);
    this->BoxSource->SetYLength(0.6);
    this->BoxSource->SetZLength(0.6);
    this->Actors[1] = MakeActor(this->BoxSource, 1.5, 0.3, 1.0);
    this->Actors[2] = MakeActor(this->SphereSource, -1.5, 1.0, -0.5);
    const double n[3] = { 0.155, 0.117, 0.138 }, k[3] = { 4.83, 3.12, 2.15 };
    vtkCausticsMaterial::MakeMirror(this->Actors[2]->GetProperty(), n, k);
  }
  /** Frame `f`: visitor k is in the scene when bit k of f / 2 is set. */
  void Update(vtkRenderer* renderer, int f)
  {
    for (int k = 0; k < 3; ++k)
    {
      const bool wanted = ((f / 2) >> k) & 1;
      const bool present = this->Actors[k] && renderer->HasViewProp(this->Actors[k]);
      if (wanted && !present)
      {
        if (k == 0)
        {
          this->Actors[0] = MakeActor(this->SphereSource, 1.0, 1.5, -1.0);
          vtkCausticsMaterial::MakeGlass(this->Actors[0]->GetProperty(), 1.5);
        }
        renderer->AddActor(this->Actors[k]);
      }
      else if (!wanted && present)
      {
        renderer->RemoveActor(this->Actors[k]);
      }
    }
  }
};

/** "textures/MiB buffers/MiB framebuffers" of one sample. */
std::string Describe(const vtkCausticsRenderPass::GraphicsMemory& m)
{
  const double mib = 1.0 / (1024.0 * 1024.0);
  std::ostringstream text;
  text.precision(4);
  text << m.Textures << " tex/" << m.TextureBytes * mib << " MiB, " << m.Buffers << " buf/"
       << m.BufferBytes * mib << " MiB, " << m.Framebuffers << " fbo";
  return text.str();
}

/** Renders the frames, one sample after each; counts the frames with caustics. */
std::vector<Sample> RenderFrames(vtkRenderWindow* window, vtkOpenGLRenderer* renderer,
  vtkCausticsRenderPass* pass, int frames, bool verbose, int& withCaustics)
{
  const int sizes[4][2] = { { 128, 128 }, { 96, 112 }, { 64, 128 }, { 120, 80 } };
  Visitors visitors;
  std::vector<Sample> samples;
  withCaustics = 0;
  for (int f = 0; f < frames; ++f)
  {
    window->SetSize(sizes[f % 4][0], sizes[f % 4][1]);
    visitors.Update(renderer, f);
    window->Render();
    withCaustics += pass->GetLastFrameHadCaustics() ? 1 : 0;
    const vtkCausticsRenderPass::GraphicsMemory memory = vtkCausticsRenderPass::GetGraphicsMemory();
    // The allocator's free pages back to the system first: RSS is then memory in use
    // plus what lives outside malloc (driver mappings, JIT code), where a leak the heap
    // figure cannot see would show. Without it RSS follows malloc's fragmentation: with
    // smaller first-frame buffers (a cheaper first frame) it filled up to the same
    // plateau only after the warm-up quarter, +24 to +33 MiB with the heap flat.
    malloc_trim(0);
    samples.push_back({ memory, ResidentBytes(), HeapBytes() });
    if (verbose)
    {
      std::cout << "frame " << f << ": " << Describe(memory) << ", RSS "
                << samples.back().Rss / (1024.0 * 1024.0) << " MiB, heap "
                << samples.back().Heap / (1024.0 * 1024.0) << " MiB" << std::endl;
    }
  }
  return samples;
}

Sample Peak(const std::vector<Sample>& samples, std::size_t begin, std::size_t end)
{
  Sample peak;
  for (std::size_t i = begin; i < end; ++i)
  {
    const vtkCausticsRenderPass::GraphicsMemory& m = samples[i].Gpu;
    peak.Gpu.Textures = std::max(peak.Gpu.Textures, m.Textures);
    peak.Gpu.TextureBytes = std::max(peak.Gpu.TextureBytes, m.TextureBytes);
    peak.Gpu.Buffers = std::max(peak.Gpu.Buffers, m.Buffers);
    peak.Gpu.BufferBytes = std::max(peak.Gpu.BufferBytes, m.BufferBytes);
    peak.Gpu.Framebuffers = std::max(peak.Gpu.Framebuffers, m.Framebuffers);
    peak.Rss = std::max(peak.Rss, samples[i].Rss);
    peak.Heap = std::max(peak.Heap, samples[i].Heap);
  }
  return peak;
}

/** Whether every GPU pool of `late` stays within its peak in `warm`. */
bool Within(const vtkCausticsRenderPass::GraphicsMemory& late,
  const vtkCausticsRenderPass::GraphicsMemory& warm)
{
  return late.Textures <= warm.Textures && late.TextureBytes <= warm.TextureBytes &&
    late.Buffers <= warm.Buffers && late.BufferBytes <= warm.BufferBytes &&
    late.Framebuffers <= warm.Framebuffers;
}

/** Checks flatness and prints the figures; true if flat. */
bool Judge(const std::string& technique, const std::vector<Sample>& samples, int withCaustics,
  const vtkCausticsRenderPass::GraphicsMemory& released, double seconds)
{
  const std::size_t n = samples.size();
  const Sample warm = Peak(samples, 0, n / 4), late = Peak(samples, n / 2, n);
  const double mib = 1.0 / (1024.0 * 1024.0);
  std::cout << "soak " << technique << ": " << n << " frames in " << seconds << " s ("
            << withCaustics << " with caustics)\n  GPU first frame: " << Describe(samples[0].Gpu)
            << "\n  GPU peak of the first quarter: " << Describe(warm.Gpu)
            << "\n  GPU peak of the last half: " << Describe(late.Gpu)
            << "\n  RSS MiB: first frame " << samples.front().Rss * mib << ", peak of the first "
            << "quarter " << warm.Rss * mib << ", peak of the last half " << late.Rss * mib
            << ", last frame " << samples.back().Rss * mib << "\n  heap in use MiB: first frame "
            << samples.front().Heap * mib << ", peak of the first quarter " << warm.Heap * mib
            << ", peak of the last half " << late.Heap * mib << ", last frame "
            << samples.back().Heap * mib << "\n  after release: " << released.Objects()
            << " objects, " << released.Bytes() << " bytes" << std::endl;
  bool flat = true;
  auto fail = [&](const char* why)
  {
    std::cout << "FAIL soak " << technique << ": " << why << std::endl;
    flat = false;
  };
  if (!Within(late.Gpu, warm.Gpu))
  {
    fail("GPU objects or bytes grew after the warm-up");
  }
  if (late.Rss - warm.Rss >= MemoryGrowthBound)
  {
    fail("resident memory grew by more than the bound after the warm-up");
  }
  if (late.Heap - warm.Heap >= MemoryGrowthBound)
  {
    fail("the heap in use grew by more than the bound after the warm-up");
  }
  if (warm.Gpu.Objects() == 0 || warm.Gpu.Bytes() == 0)
  {
    fail("the bookkeeping counted nothing while rendering: the checks would be empty");
  }
  if (released.Objects() != 0 || released.Bytes() != 0)
  {
    fail("ReleaseGraphicsResources left GPU objects");
  }
  if (technique != "none" && withCaustics < static_cast<int>(n) / 2)
  {
    fail("fewer than half the frames had caustics: the soak did not exercise the technique");
  }
  return flat;
}

bool SoakOne(const std::string& technique, int frames, bool verbose)
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkOpenGLRenderer> renderer;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsBuiltinScene> scene;
  scene->SetSceneName("ball-lens");
  if (!scene->Populate(renderer))
  {
    std::cout << "FAIL soak " << technique << ": " << scene->GetLastError() << std::endl;
    return false;
  }
  vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
  pass->SetLightBufferResolution(64);
  renderer->SetPass(pass);
  const auto start = std::chrono::steady_clock::now();
  int withCaustics = 0;
  const std::vector<Sample> samples =
    RenderFrames(window, renderer, pass, frames, verbose, withCaustics);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return Judge(
    technique, samples, withCaustics, vtkCausticsRenderPass::GetGraphicsMemory(), seconds);
}
}

bool RunSoak(int frames, const std::string& technique, bool verbose)
{
  if (frames < 64)
  {
    std::cout << "FAIL soak: at least 64 frames (a warm-up of a quarter holds a 16-frame cycle)"
              << std::endl;
    return false;
  }
  const std::vector<std::string> techniques =
    technique.empty() ? vtkCausticsTechniques::GetNames() : std::vector<std::string>{ technique };
  bool flat = true;
  for (const std::string& name : techniques)
  {
    flat = SoakOne(name, frames, verbose) && flat;
  }
  return flat;
}
}
