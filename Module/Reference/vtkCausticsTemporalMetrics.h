/**
 * @class   vtkCausticsTemporalMetrics
 * @brief   Temporal stability of a caustics image sequence against a reference sequence.
 *
 * Real-time caustics are judged by how they behave over frames as much as by one
 * frame's error: flicker where nothing moves, wrong or smeared light where something
 * does, and lag or ghosting after a cut. Given a technique's frames and the reference
 * frames of the same animation (e.g. caustic irradiance, W/m^2), this class measures
 * all of them; docs/benchmarks.md ("Temporal stability") gives the formulas, and
 * caustics-bench --animate uses it. Frames are added one at a time (AddFrame), then
 * Compute() derives:
 * 1. per frame k: vtkCausticsErrorMetrics of the frame against its reference (the
 *    frame's own mask and areas): relative L2 e_k and flux ratio;
 * 2. the receiver pixels P: masked in every reference frame and finite in every test
 *    frame (a pixel with a NaN/Inf test value in any frame is counted and left out);
 * 3. segments: frames [0, c) and [c, K) for a cut at CutFrame c (one segment
 *    [0, K) without a cut). In each segment a pixel is static when, in every
 *    channel, the reference's temporal standard deviation over the segment is at most
 *    StaticTolerance times its temporal mean, and moving otherwise;
 * 4. after a cut: the steady error E = median of e_k over the last half of [c, K)
 *    (its last ceil((K - c) / 2) frames); the lag L = the fewest frames after the cut
 *    from which on every e_k <= (1 + SettleTolerance) E; the ghosting G = mean of
 *    e_k over the settling frames [c, c + max(L, 1)) divided by E (1: the first
 *    frame after the cut is as good as the steady ones; +inf when E = 0 < the mean);
 * 5. the flicker: over the static pixels of each segment, from its settled frames
 *    on ([0, c) and [c + L, K)), the technique's per-value temporal relative standard
 *    deviation s / m (s: sample standard deviation over the frames, m: their mean; s
 *    over the reference's mean where m <= 0), flux-weighted: F = sum w s / m / sum w
 *    with w = A rbar (A: pixel area, rbar: the reference's temporal mean). Segments
 *    with fewer than 2 settled frames are left out; NaN when no static light remains;
 * 6. the moving error: over the moving pixels of each segment and all its frames,
 *    the relative L2 sqrt(sum (t - r)^2 / sum r^2); NaN when nothing moves.
 * A constant sequence has zero flicker; a sequence with relative noise of standard
 * deviation sigma has flicker sigma; a technique that shows the previous state for
 * k frames after a cut has lag k (Testing/Cxx/TestTemporalMetrics.cxx).
 *
 * Bad input (images the per-frame metrics refuse, frames of another size, fewer
 * than 2 frames, a cut outside [1, K - 1]) fails with one error naming the problem;
 * every result then reads NaN (lag -1).
 */
#ifndef vtkCausticsTemporalMetrics_h
#define vtkCausticsTemporalMetrics_h

#include "vtkCausticsReferenceModule.h" // For export macro
#include "vtkObject.h"

#include <limits> // For std::numeric_limits
#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkImageData;

class VTKCAUSTICSREFERENCE_EXPORT vtkCausticsTemporalMetrics : public vtkObject
{
public:
  static vtkCausticsTemporalMetrics* New();
  vtkTypeMacro(vtkCausticsTemporalMetrics, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Arrays as in vtkCausticsErrorMetrics: the compared point-data array (default
   * "CausticIrradiance", W/m^2), the reference's receiver mask and its pixel areas
   * (m^2; they weight the flux and the flicker). Defaults "" (every pixel, weight 1).
   * Set them before the first AddFrame().
   */
  vtkSetStdStringFromCharMacro(ArrayName);
  vtkGetCharFromStdStringMacro(ArrayName);
  vtkSetStdStringFromCharMacro(MaskArrayName);
  vtkGetCharFromStdStringMacro(MaskArrayName);
  vtkSetStdStringFromCharMacro(AreaArrayName);
  vtkGetCharFromStdStringMacro(AreaArrayName);
  ///@}

  ///@{
  /**
   * Index of the first frame after a cut (a jump of the scene), in [1, frames - 1];
   * -1: no cut (no lag or ghosting). Default -1.
   */
  vtkSetMacro(CutFrame, int);
  vtkGetMacro(CutFrame, int);
  ///@}

  ///@{
  /**
   * A pixel is static in a segment when the reference's temporal standard deviation
   * there is at most this fraction of its temporal mean, in [0, 1]. Default 0.01.
   */
  vtkSetClampMacro(StaticTolerance, double, 0.0, 1.0);
  vtkGetMacro(StaticTolerance, double);
  ///@}

  ///@{
  /**
   * The error after a cut has settled once it stays within (1 + this) times the
   * steady error, in [0, 10]. Default 0.1.
   */
  vtkSetClampMacro(SettleTolerance, double, 0.0, 10.0);
  vtkGetMacro(SettleTolerance, double);
  ///@}

  /** Forgets every frame (the settings stay). */
  void Reset();

  /**
   * Adds the next frame: the technique's image and the reference's. Returns false,
   * with an error naming the problem, when vtkCausticsErrorMetrics cannot compare
   * them or their size differs from the first frame's; the frame is then not added.
   */
  bool AddFrame(vtkImageData* test, vtkImageData* reference);

  /** Frames added since the last Reset(). */
  int GetNumberOfFrames() const;

  /** Derives the temporal metrics (class description). False, with an error, on bad input. */
  bool Compute();

  /** Why the last AddFrame() or Compute() failed; empty after a success. */
  vtkGetCharFromStdStringMacro(LastError);

  ///@{
  /** Per-frame results (step 1) of frame k, NaN outside [0, frames). */
  double GetFrameRelativeL2Error(int k) const;
  double GetFrameFluxRatio(int k) const;
  ///@}

  ///@{
  /**
   * Results of the last Compute() (class description); NaN (lag -1) before it, after
   * a failed one, and where undefined (no cut: lag, steady error and ghosting).
   * - Flicker: flux-weighted temporal relative standard deviation where static;
   * - MovingError: relative L2 over the moving pixels and their frames;
   * - MeanRelativeL2Error, MeanFluxRatio: means of the per-frame results;
   * - SteadyError: E, the median per-frame error over the last half after the cut;
   * - Lag: frames after the cut until the error settles (0: at once);
   * - Ghosting: mean error of the settling frames over E;
   * - StaticValues / MovingValues: pixel-segment values (pixel x channel x segment)
   *   classified static / moving; NonFinitePixels: pixels left out for NaN/Inf.
   */
  double GetFlicker() const;
  double GetMovingError() const;
  double GetMeanRelativeL2Error() const;
  double GetMeanFluxRatio() const;
  double GetSteadyError() const;
  int GetLag() const;
  double GetGhosting() const;
  vtkIdType GetNumberOfStaticValues() const;
  vtkIdType GetNumberOfMovingValues() const;
  vtkIdType GetNumberOfNonFinitePixels() const;
  ///@}

  /** One line: "flicker=... movingErr=... meanRelL2=... lag=... ghosting=...", or "error: ...". */
  std::string GetSummary() const;

#ifndef __VTK_WRAP__
  /** All results of one Compute(), as the getters report them. */
  struct Result
  {
    double Flicker = std::numeric_limits<double>::quiet_NaN();
    double MovingError = std::numeric_limits<double>::quiet_NaN();
    double MeanRelativeL2Error = std::numeric_limits<double>::quiet_NaN();
    double MeanFluxRatio = std::numeric_limits<double>::quiet_NaN();
    double SteadyError = std::numeric_limits<double>::quiet_NaN();
    int Lag = -1; ///< frames
    double Ghosting = std::numeric_limits<double>::quiet_NaN();
    vtkIdType StaticValues = 0;
    vtkIdType MovingValues = 0;
    vtkIdType NonFinitePixels = 0;
  };

  /** The results of the last Compute(). */
  const Result& GetResult() const
  {
    return this->Metrics;
  }
#endif

protected:
  vtkCausticsTemporalMetrics();
  ~vtkCausticsTemporalMetrics() override;

  std::string ArrayName = "CausticIrradiance";
  std::string MaskArrayName;
  std::string AreaArrayName;
  int CutFrame = -1;
  double StaticTolerance = 0.01;
  double SettleTolerance = 0.1;
  std::string LastError;

private:
  vtkCausticsTemporalMetrics(const vtkCausticsTemporalMetrics&) = delete;
  void operator=(const vtkCausticsTemporalMetrics&) = delete;

  /** Records the error, reports it with vtkErrorMacro and returns false. */
  bool Fail(const std::string& message);
  /** Steps 4-6 on the checked frames. */
  void ComputeLag();
  void ComputeSegments();

  struct Frames;
  std::unique_ptr<Frames> Sequence;
#ifndef __VTK_WRAP__
  Result Metrics;
#endif
};

#endif
