#include "vtkCausticsTimings.h"

#include "vtkCommand.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderTimer.h"

#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iterator>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

vtkStandardNewMacro(vtkCausticsTimings);

namespace
{
using Clock = std::chrono::steady_clock;
constexpr int Counters = vtkCausticsTimings::NUMBER_OF_WORK_COUNTERS;

/** The pipeline statistics query target of each counter, in WorkCounter order. */
const GLenum CounterTargets[Counters] = { GL_SAMPLES_PASSED, GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
  GL_COMPUTE_SHADER_INVOCATIONS_ARB, GL_PRIMITIVES_SUBMITTED_ARB,
  GL_VERTEX_SHADER_INVOCATIONS_ARB };
const char* CounterNames[Counters] = { "fragments", "fragment shader invocations",
  "compute invocations", "primitives", "vertices" };

struct Stage
{
  std::string Name;
  // Two query pairs so a frame can be issued while the previous one finishes.
  std::unique_ptr<vtkOpenGLRenderTimer> Timers[2];
  bool Pending[2] = { false, false };
  int Current = 0;
  bool Ran = false;
  bool CPUOnly = false; // started without timer queries this frame
  double GPU = -1.0;
  double CPU = 0.0;
  Clock::time_point CPUStart;
  // Work counts of the stage's last run (CountWork); Run tells the runs apart.
  bool Counted = false;
  int Run = 0;
  long long Work[Counters] = { -1, -1, -1, -1, -1 };
};

/**
 * One interval of a frame between two counted stage boundaries: its queries (one
 * per counter) and the stage runs open during it, which its counts are added to.
 */
struct Segment
{
  GLuint Queries[Counters] = {};
  std::vector<std::pair<std::size_t, int>> Owners; // stage index, run
};
}

struct vtkCausticsTimings::Internals
{
  Clock::time_point FrameStart = Clock::now();
  double LastFrameMilliseconds = -1.0;
  std::string ProgressStage;

  std::vector<Stage> Stages;
  // Work counting: the counted stages open now (outermost first), the pool of
  // segments (reused from frame to frame) and how many this frame used.
  std::vector<std::size_t> Open;
  std::vector<Segment> Segments;
  std::size_t UsedSegments = 0;
  bool SegmentActive = false;
  int HasStatistics = -1; // unknown until the first counted stage has a context

  std::size_t Find(const char* name)
  {
    for (std::size_t i = 0; i < this->Stages.size(); ++i)
    {
      if (this->Stages[i].Name == name)
      {
        return i;
      }
    }
    this->Stages.emplace_back();
    Stage& stage = this->Stages.back();
    stage.Name = name;
    stage.Timers[0].reset(new vtkOpenGLRenderTimer);
    stage.Timers[1].reset(new vtkOpenGLRenderTimer);
    return this->Stages.size() - 1;
  }

  static void Collect(Stage& stage, bool wait)
  {
    for (int k = 0; k < 2; ++k)
    {
      if (!stage.Pending[k])
      {
        continue;
      }
      if (wait)
      {
        glFlush();
        while (!stage.Timers[k]->Ready())
        {
          std::this_thread::yield();
        }
      }
      if (stage.Timers[k]->Ready())
      {
        stage.GPU = stage.Timers[k]->GetElapsedMilliseconds();
        stage.Pending[k] = false;
      }
    }
  }

  /** GL 4.6, or GL_ARB_pipeline_statistics_query: asked once, in the current context. */
  bool CanCount()
  {
    if (this->HasStatistics < 0)
    {
      GLint major = 0, minor = 0, extensions = 0;
      glGetIntegerv(GL_MAJOR_VERSION, &major);
      glGetIntegerv(GL_MINOR_VERSION, &minor);
      glGetIntegerv(GL_NUM_EXTENSIONS, &extensions);
      this->HasStatistics = major * 10 + minor >= 46 ? 1 : 0;
      for (GLint i = 0; i < extensions && !this->HasStatistics; ++i)
      {
        const char* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i));
        this->HasStatistics = name && std::string(name) == "GL_ARB_pipeline_statistics_query";
      }
    }
    return this->HasStatistics == 1;
  }

  /** Starts a segment for the stages open now (none: nothing to count). */
  void OpenSegment()
  {
    if (this->Open.empty())
    {
      return;
    }
    if (this->UsedSegments == this->Segments.size())
    {
      this->Segments.emplace_back(); // the pool grows in the first frames only
      glGenQueries(Counters, this->Segments.back().Queries);
    }
    Segment& segment = this->Segments[this->UsedSegments];
    segment.Owners.clear();
    for (std::size_t i : this->Open)
    {
      segment.Owners.emplace_back(i, this->Stages[i].Run);
    }
    for (int k = 0; k < Counters; ++k)
    {
      glBeginQuery(CounterTargets[k], segment.Queries[k]);
    }
    this->SegmentActive = true;
  }

  void CloseSegment()
  {
    if (!this->SegmentActive)
    {
      return;
    }
    for (int k = 0; k < Counters; ++k)
    {
      glEndQuery(CounterTargets[k]);
    }
    ++this->UsedSegments;
    this->SegmentActive = false;
  }

  void StartCounting(std::size_t index)
  {
    glFinish(); // the stage's CPU time then starts on an idle GPU
    this->CloseSegment();
    Stage& stage = this->Stages[index];
    stage.Counted = true;
    ++stage.Run;
    std::fill(stage.Work, stage.Work + Counters, 0);
    this->Open.push_back(index);
    this->OpenSegment();
  }

  void StopCounting(std::size_t index)
  {
    glFinish(); // ... and ends when its work is done
    this->CloseSegment();
    const auto open = std::find(this->Open.rbegin(), this->Open.rend(), index);
    if (open != this->Open.rend())
    {
      this->Open.erase(std::next(open).base());
    }
    this->OpenSegment();
  }

  /** Waits for the frame's segments and adds each to the stage runs it belongs to. */
  void CollectWork()
  {
    this->CloseSegment();
    for (std::size_t s = 0; s < this->UsedSegments; ++s)
    {
      const Segment& segment = this->Segments[s];
      for (int k = 0; k < Counters; ++k)
      {
        GLuint64 value = 0;
        glGetQueryObjectui64v(segment.Queries[k], GL_QUERY_RESULT, &value);
        for (const auto& owner : segment.Owners)
        {
          Stage& stage = this->Stages[owner.first];
          // A stage that ran again later in the frame keeps its last run's counts.
          stage.Work[k] += stage.Run == owner.second ? static_cast<long long>(value) : 0;
        }
      }
    }
    this->UsedSegments = 0;
    this->Open.clear();
  }
};

vtkCausticsTimings::vtkCausticsTimings()
  : Internal(new Internals)
{
}

vtkCausticsTimings::~vtkCausticsTimings() = default;

void vtkCausticsTimings::BeginFrame()
{
  this->Internal->FrameStart = Clock::now();
  this->Internal->ProgressStage.clear();
  if (this->Internal->UsedSegments > 0 || this->Internal->SegmentActive)
  {
    this->Internal->CollectWork(); // a frame that did not reach EndFrame()
  }
  for (Stage& stage : this->Internal->Stages)
  {
    stage.Ran = false;
    Internals::Collect(stage, false);
  }
}

void vtkCausticsTimings::StartStage(const char* name, bool gpu)
{
  if (!this->Enabled)
  {
    return;
  }
  const std::size_t index = this->Internal->Find(name);
  Stage& stage = this->Internal->Stages[index];
  stage.Ran = true;
  stage.CPUOnly = !gpu;
  stage.Counted = false;
  if (gpu && this->CountWork && this->Internal->CanCount())
  {
    this->Internal->StartCounting(index);
  }
  stage.CPUStart = Clock::now();
  if (!gpu)
  {
    stage.GPU = -1.0; // no GPU time for this frame
    return;
  }
  // Reuse the pair whose result was collected; if both are pending, drop the older.
  int slot = stage.Pending[stage.Current] ? 1 - stage.Current : stage.Current;
  if (stage.Pending[slot])
  {
    Internals::Collect(stage, true);
  }
  stage.Current = slot;
  stage.Timers[slot]->Reset();
  stage.Timers[slot]->Start();
}

void vtkCausticsTimings::StopStage(const char* name)
{
  if (!this->Enabled)
  {
    return;
  }
  const std::size_t index = this->Internal->Find(name);
  Stage& stage = this->Internal->Stages[index];
  if (stage.Counted)
  {
    this->Internal->StopCounting(index);
  }
  if (!stage.CPUOnly)
  {
    stage.Timers[stage.Current]->Stop();
    stage.Pending[stage.Current] = true;
  }
  stage.CPU = std::chrono::duration<double, std::milli>(Clock::now() - stage.CPUStart).count();
  if (this->HasObserver(vtkCommand::ProgressEvent))
  {
    glFinish(); // the stage's work is done, not only issued
    this->Internal->ProgressStage = name;
    const double last = this->Internal->LastFrameMilliseconds;
    const double elapsed =
      std::chrono::duration<double, std::milli>(Clock::now() - this->Internal->FrameStart).count();
    double fraction = last > 0.0 ? std::min(0.99, elapsed / last) : -1.0;
    this->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
  }
}

const char* vtkCausticsTimings::GetProgressStage() const
{
  return this->Internal->ProgressStage.c_str();
}

double vtkCausticsTimings::GetLastFrameMilliseconds() const
{
  return this->Internal->LastFrameMilliseconds;
}

void vtkCausticsTimings::EndFrame()
{
  this->Internal->LastFrameMilliseconds =
    std::chrono::duration<double, std::milli>(Clock::now() - this->Internal->FrameStart).count();
  if (this->HasObserver(vtkCommand::ProgressEvent))
  {
    this->Internal->ProgressStage.clear();
    double done = 1.0;
    this->InvokeEvent(vtkCommand::ProgressEvent, &done);
  }
  if (this->Internal->UsedSegments > 0 || this->Internal->SegmentActive)
  {
    this->Internal->CollectWork();
  }
  for (Stage& stage : this->Internal->Stages)
  {
    if (stage.Ran)
    {
      Internals::Collect(stage, this->Synchronous);
    }
  }
}

int vtkCausticsTimings::GetNumberOfStages() const
{
  return static_cast<int>(this->Internal->Stages.size());
}

const char* vtkCausticsTimings::GetStageName(int i) const
{
  return i >= 0 && i < this->GetNumberOfStages() ? this->Internal->Stages[i].Name.c_str() : "";
}

double vtkCausticsTimings::GetStageGPUMilliseconds(int i) const
{
  return i >= 0 && i < this->GetNumberOfStages() ? this->Internal->Stages[i].GPU : -1.0;
}

double vtkCausticsTimings::GetStageCPUMilliseconds(int i) const
{
  return i >= 0 && i < this->GetNumberOfStages() ? this->Internal->Stages[i].CPU : 0.0;
}

bool vtkCausticsTimings::GetStageRan(int i) const
{
  return i >= 0 && i < this->GetNumberOfStages() && this->Internal->Stages[i].Ran;
}

bool vtkCausticsTimings::GetStageTimedOnGPU(int i) const
{
  return this->GetStageRan(i) && !this->Internal->Stages[i].CPUOnly;
}

const char* vtkCausticsTimings::GetWorkCounterName(int counter)
{
  return counter >= 0 && counter < Counters ? CounterNames[counter] : "";
}

long long vtkCausticsTimings::GetStageWork(int i, int counter) const
{
  if (!this->GetStageRan(i) || counter < 0 || counter >= Counters)
  {
    return -1;
  }
  const Stage& stage = this->Internal->Stages[i];
  return stage.Counted ? stage.Work[counter] : -1;
}

double vtkCausticsTimings::GetGPUMilliseconds(const char* name) const
{
  for (const Stage& stage : this->Internal->Stages)
  {
    if (stage.Name == name)
    {
      return stage.Ran ? stage.GPU : -1.0;
    }
  }
  return -1.0;
}

double vtkCausticsTimings::GetTotalGPUMilliseconds() const
{
  double total = 0.0;
  for (const Stage& stage : this->Internal->Stages)
  {
    total += stage.Ran && stage.GPU > 0.0 ? stage.GPU : 0.0;
  }
  return total;
}

std::string vtkCausticsTimings::GetReport() const
{
  std::ostringstream report;
  report << std::fixed << std::setprecision(3);
  for (const Stage& stage : this->Internal->Stages)
  {
    report << "  " << std::left << std::setw(28) << stage.Name;
    if (!stage.Ran)
    {
      report << "skipped\n";
    }
    else if (stage.CPUOnly)
    {
      report << "gpu not timed cpu " << stage.CPU << " ms\n";
    }
    else if (stage.GPU < 0.0)
    {
      report << "gpu pending   cpu " << stage.CPU << " ms\n";
    }
    else
    {
      report << "gpu " << std::setw(9) << stage.GPU << " ms   cpu " << stage.CPU << " ms\n";
    }
  }
  return report.str();
}

void vtkCausticsTimings::ReleaseGraphicsResources()
{
  auto& in = *this->Internal;
  in.CloseSegment();
  for (Segment& segment : in.Segments)
  {
    glDeleteQueries(Counters, segment.Queries);
  }
  in.Segments.clear();
  in.UsedSegments = 0;
  in.Open.clear();
  in.HasStatistics = -1;
  for (Stage& stage : this->Internal->Stages)
  {
    for (int k = 0; k < 2; ++k)
    {
      stage.Timers[k]->ReleaseGraphicsResources();
      stage.Pending[k] = false;
    }
  }
}

void vtkCausticsTimings::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Enabled: " << this->Enabled << "\n";
  os << indent << "Synchronous: " << this->Synchronous << "\n";
  os << indent << "CountWork: " << this->CountWork << "\n";
  os << indent << "Stages:\n" << this->GetReport();
}
