#include "vtkCausticsTimings.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderTimer.h"

#include "vtk_glew.h"

#include <chrono>
#include <iomanip>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

vtkStandardNewMacro(vtkCausticsTimings);

namespace
{
using Clock = std::chrono::steady_clock;

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
};
}

struct vtkCausticsTimings::Internals
{
  std::vector<Stage> Stages;

  Stage& Find(const char* name)
  {
    for (Stage& stage : this->Stages)
    {
      if (stage.Name == name)
      {
        return stage;
      }
    }
    this->Stages.emplace_back();
    Stage& stage = this->Stages.back();
    stage.Name = name;
    stage.Timers[0].reset(new vtkOpenGLRenderTimer);
    stage.Timers[1].reset(new vtkOpenGLRenderTimer);
    return stage;
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
};

vtkCausticsTimings::vtkCausticsTimings()
  : Internal(new Internals)
{
}

vtkCausticsTimings::~vtkCausticsTimings() = default;

void vtkCausticsTimings::BeginFrame()
{
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
  Stage& stage = this->Internal->Find(name);
  stage.Ran = true;
  stage.CPUOnly = !gpu;
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
  Stage& stage = this->Internal->Find(name);
  if (!stage.CPUOnly)
  {
    stage.Timers[stage.Current]->Stop();
    stage.Pending[stage.Current] = true;
  }
  stage.CPU = std::chrono::duration<double, std::milli>(Clock::now() - stage.CPUStart).count();
}

void vtkCausticsTimings::EndFrame()
{
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
  os << indent << "Stages:\n" << this->GetReport();
}
