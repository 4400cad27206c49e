/**
 * @class   vtkCausticsTimings
 * @brief   GPU (timer queries) and CPU wall time of each named caustics stage.
 *
 * A pass brackets each stage with StartStage()/StopStage(). GPU times come from
 * vtkOpenGLRenderTimer (GL timestamp queries). By default results are collected
 * without stalling: a stage's time is that of the most recent frame whose queries
 * are complete (usually the previous one). With Synchronous on (the CLI, the
 * benchmark, tests), EndFrame() waits for the queries so the times are this frame's.
 * Stages keep the order in which they were first started.
 *
 * With CountWork on (the benchmark; off by default, it costs), each stage also
 * counts the GPU work it did with pipeline statistics queries
 * (GL_ARB_pipeline_statistics_query, core in GL 4.6: fragment and compute shader
 * invocations, primitives submitted, vertex shader invocations) and an occlusion
 * query (fragments written, i.e. not discarded: with no depth test, a splat's or a
 * traced line's fragments). Mesa's llvmpipe (22.3) counts fragment shader
 * invocations as 16 per 4x4 block it shades, so throughputs use fragments
 * written, primitives and compute invocations; caustics-ceilings checks the
 * counts against what it drew. Stages nest (a
 * technique's stages run inside "caustic irradiance"), but a query of one target
 * cannot be active twice, so the frame is cut into segments at every counted
 * StartStage/StopStage: one set of queries per segment, added to every stage open
 * during it. A stage's counts therefore include those of the stages nested in it,
 * as its times do. The query objects are pooled and reused from frame to frame.
 * While counting, EndFrame() waits for the counts, and every stage boundary waits
 * for the GPU (glFinish) so that a stage's CPU time is the wall time of its
 * execution on any implementation: the denominator of its throughput. A counted
 * stage must not run occlusion or pipeline statistics queries of its own (a target
 * cannot be active twice); no caustics stage does, but VTK's depth peeling with an
 * occlusion ratio would, inside "vtk delegate".
 */
#ifndef vtkCausticsTimings_h
#define vtkCausticsTimings_h

#include "vtkObject.h"
#include "vtkRenderingCausticsModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class VTKRENDERINGCAUSTICS_EXPORT vtkCausticsTimings : public vtkObject
{
public:
  static vtkCausticsTimings* New();
  vtkTypeMacro(vtkCausticsTimings, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Wait for this frame's GPU times in EndFrame(). Default off. */
  vtkSetMacro(Synchronous, bool);
  vtkGetMacro(Synchronous, bool);
  vtkBooleanMacro(Synchronous, bool);
  ///@}

  ///@{
  /** Collect timings at all. Default on. */
  vtkSetMacro(Enabled, bool);
  vtkGetMacro(Enabled, bool);
  vtkBooleanMacro(Enabled, bool);
  ///@}

  ///@{
  /**
   * Count each stage's GPU work (pipeline statistics queries; see the class
   * documentation). Default off: the queries, and the waits they need, cost.
   */
  vtkSetMacro(CountWork, bool);
  vtkGetMacro(CountWork, bool);
  vtkBooleanMacro(CountWork, bool);
  ///@}

  /** The work counted per stage with CountWork on. */
  enum WorkCounter
  {
    FRAGMENTS_WRITTEN,           // fragments that passed every test (GL_SAMPLES_PASSED)
    FRAGMENT_SHADER_INVOCATIONS, // fragments shaded, as the implementation counts them
    COMPUTE_SHADER_INVOCATIONS,  // compute shader invocations (threads, not work groups)
    PRIMITIVES_SUBMITTED,        // points, lines, triangles drawn
    VERTEX_SHADER_INVOCATIONS,   // vertices shaded
    NUMBER_OF_WORK_COUNTERS
  };

  /** Short name of a counter ("fragments", "compute invocations", ...), "" if out of range. */
  static const char* GetWorkCounterName(int counter);

  /**
   * Work of stage i in the last frame (its last run when it ran more than once, as
   * its times), nested stages included; -1 when it was not counted (CountWork off,
   * a CPU-only stage, or no pipeline statistics queries in this context).
   */
  long long GetStageWork(int i, int counter) const;

  /** Marks the start of a frame: stages not started this frame report "skipped". */
  void BeginFrame();
  /**
   * Starts the named stage. With gpu false only its CPU time is taken (no timer
   * queries: they cost tens of microseconds per frame on some drivers), e.g. for
   * the VTK delegate of a frame that skips every caustics stage; its GPU time is
   * then -1 for this frame.
   */
  void StartStage(const char* name, bool gpu = true);
  void StopStage(const char* name);
  /** Ends the frame; collects finished queries (waits for them when Synchronous). */
  void EndFrame();

  int GetNumberOfStages() const;
  const char* GetStageName(int i) const;
  /** GPU time in ms of stage i, or -1 while not yet available. */
  double GetStageGPUMilliseconds(int i) const;
  /** CPU wall time in ms spent between StartStage and StopStage (issue, not execution). */
  double GetStageCPUMilliseconds(int i) const;
  /** True when stage i ran in the last frame. */
  bool GetStageRan(int i) const;
  /** True when stage i ran in the last frame with timer queries (not CPU only). */
  bool GetStageTimedOnGPU(int i) const;
  /** GPU time in ms of the named stage, -1 if unknown or skipped. */
  double GetGPUMilliseconds(const char* name) const;
  /** Sum of the GPU times of the stages that ran in the last frame. */
  double GetTotalGPUMilliseconds() const;

  /** One line per stage: name, GPU ms, CPU ms (or "skipped"). */
  std::string GetReport() const;

  /**
   * Progress of the frame, for observers of vtkCommand::ProgressEvent on this
   * object (call data: a double). Only while someone observes, each StopStage()
   * waits for the GPU (glFinish) and reports the wall time since BeginFrame() over
   * the last whole frame's, at most 0.99, or -1 in a first frame (not known yet);
   * EndFrame() reports 1. GetProgressStage() names the stage just finished.
   */
  const char* GetProgressStage() const;
  /** Wall time in ms of the last frame from BeginFrame() to EndFrame(); -1 before one. */
  double GetLastFrameMilliseconds() const;

  /** Frees the GL queries. */
  void ReleaseGraphicsResources();

protected:
  vtkCausticsTimings();
  ~vtkCausticsTimings() override;

  bool Synchronous = false;
  bool Enabled = true;
  bool CountWork = false;

private:
  vtkCausticsTimings(const vtkCausticsTimings&) = delete;
  void operator=(const vtkCausticsTimings&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#ifndef __VTK_WRAP__
namespace caustics
{
/**
 * Where a helper stage (the layered depth image, the line tracer, the distance
 * impostors) reports its steps: the pass's timings, or none, and a prefix for the
 * steps' names ("refractor layers " + "depth peeling"). Set by the helper's
 * SetTimings(); the steps are nested in the pass's own stage.
 */
struct StageSteps
{
  vtkCausticsTimings* Timings = nullptr;
  std::string Prefix;

  void Start(const std::string& step) const
  {
    if (this->Timings)
    {
      this->Timings->StartStage((this->Prefix + step).c_str());
    }
  }
  void Stop(const std::string& step) const
  {
    if (this->Timings)
    {
      this->Timings->StopStage((this->Prefix + step).c_str());
    }
  }
  /** Runs `work` (returning bool) as the step `step`. */
  template <typename Work>
  bool Timed(const std::string& step, Work work) const
  {
    this->Start(step);
    const bool ok = work();
    this->Stop(step);
    return ok;
  }
};
}
#endif

#endif
