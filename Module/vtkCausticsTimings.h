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

  /** Frees the GL queries. */
  void ReleaseGraphicsResources();

protected:
  vtkCausticsTimings();
  ~vtkCausticsTimings() override;

  bool Synchronous = false;
  bool Enabled = true;

private:
  vtkCausticsTimings(const vtkCausticsTimings&) = delete;
  void operator=(const vtkCausticsTimings&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
