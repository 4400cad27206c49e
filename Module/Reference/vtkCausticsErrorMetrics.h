/**
 * @class   vtkCausticsErrorMetrics
 * @brief   Error of a caustics image against a reference: relative L2, RMSE, PSNR, flux, peak.
 *
 * Every GPU caustics technique is judged against the CPU reference renderer
 * (docs/reference.md) with these numbers; docs/accuracy.md gives the formulas.
 * Both images are vtkImageData of the same 2D dimensions; the compared quantity is
 * the point-data array ArrayName (1 or 3 components, e.g. irradiance in W/m^2) of
 * each. Optional arrays of the reference select the pixels (MaskArrayName) and
 * weight the flux sums (AreaArrayName, m^2 of receiver seen by each pixel).
 *
 * Compute(test, reference):
 * 1. checks the inputs: both images, equal dimensions, the arrays present with 1
 *    or 3 components and one tuple per pixel, a finite reference, a finite
 *    non-negative area and a finite mask; anything else fails with an error naming
 *    the problem (GetLastError());
 * 2. selects the compared pixels P: mask value != 0 (every pixel without a mask)
 *    and every channel of the test pixel finite. Masked test pixels with a NaN or
 *    Inf are counted (GetNumberOfNonFinitePixels()), left out of every metric and
 *    reported with a warning; an empty P is an error;
 * 3. accumulates over P and all channels c: sum (t - r)^2, sum r^2, max |t - r|,
 *    max |r| and the fluxes sum A * t, sum A * r (A = 1 without an area array);
 * 4. derives relative L2 = ||t - r|| / ||r||, RMSE = sqrt(sum (t - r)^2 / (|P| C)),
 *    PSNR = 20 log10(max |r| / RMSE) in dB and the flux ratio; a reference that is
 *    zero over P (no relative error exists) is an error;
 * 5. finds each image's caustic peak: the luminance (Rec. 709 weights for RGB) is
 *    summed over a (2 PeakFilterRadius + 1)^2 box of pixels in P, so that a single
 *    hot pixel does not win over a caustic; the peak is the largest box sum, ties
 *    going to the lowest point id (lowest row, then lowest column). The peak
 *    position error is the Euclidean distance between the two peaks in pixels.
 *
 * After a failed Compute() every metric reads NaN, so a test that ignores the
 * return value still fails its comparisons.
 */
#ifndef vtkCausticsErrorMetrics_h
#define vtkCausticsErrorMetrics_h

#include "vtkObject.h"
#include "vtkCausticsReferenceModule.h" // For export macro

#include <limits> // For std::numeric_limits
#include <string> // For std::string

class vtkImageData;

class VTKCAUSTICSREFERENCE_EXPORT vtkCausticsErrorMetrics : public vtkObject
{
public:
  static vtkCausticsErrorMetrics* New();
  vtkTypeMacro(vtkCausticsErrorMetrics, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Point-data array compared in both images (1 or 3 components; the metrics are
   * in its unit). Default "CausticIrradiance" (W/m^2).
   */
  vtkSetStdStringFromCharMacro(ArrayName);
  vtkGetCharFromStdStringMacro(ArrayName);
  ///@}

  ///@{
  /**
   * Point-data array of the reference image selecting the compared pixels (1
   * component, non-zero = compared), e.g. "ReceiverMask". Default "" (all pixels).
   */
  vtkSetStdStringFromCharMacro(MaskArrayName);
  vtkGetCharFromStdStringMacro(MaskArrayName);
  ///@}

  ///@{
  /**
   * Point-data array of the reference image with the area each pixel covers (1
   * component, m^2, finite and >= 0 over the mask), e.g. "PixelArea". It weights
   * only the flux sums. Default "" (every pixel weighs 1).
   */
  vtkSetStdStringFromCharMacro(AreaArrayName);
  vtkGetCharFromStdStringMacro(AreaArrayName);
  ///@}

  ///@{
  /**
   * Half-width in pixels of the box filter applied to the luminance before the
   * caustic peak is located: the box is (2 r + 1) pixels wide. 0 takes the raw
   * maximum. Default 1 (3x3).
   */
  vtkSetClampMacro(PeakFilterRadius, int, 0, 16);
  vtkGetMacro(PeakFilterRadius, int);
  ///@}

  /**
   * Compares test with reference (steps in the class description). Returns false,
   * with vtkErrorMacro and GetLastError(), when the inputs cannot be compared.
   */
  bool Compute(vtkImageData* test, vtkImageData* reference);

  /** Why the last Compute() failed; empty after a success. */
  vtkGetCharFromStdStringMacro(LastError);

  ///@{
  /**
   * Results of the last Compute(), over the compared pixels P and all C channels
   * (t: test, r: reference, A: area). NaN before the first Compute() and after a
   * failed one, whose pixel counts say how far it got.
   * - RelativeL2Error: sqrt(sum (t - r)^2 / sum r^2), dimensionless;
   * - RMSE: sqrt(sum (t - r)^2 / (|P| C)), unit of the array;
   * - MaxAbsError: max |t - r|, unit of the array;
   * - PSNR: 20 log10(PSNRPeak / RMSE) in dB, +inf when RMSE is 0;
   * - PSNRPeak: max |r|, the reference's maximum for the non-negative quantities
   *   compared here;
   * - TestFlux, ReferenceFlux: sum A t and sum A r (W for irradiance in W/m^2 and
   *   areas in m^2); FluxRatio: their ratio, NaN when the reference flux is 0;
   * - PeakPositionError: distance in pixels between the two caustic peaks;
   * - NumberOfComparedPixels: |P|, masked pixels whose test values are all finite;
   * - NumberOfNonFinitePixels: masked pixels with NaN or Inf in a test channel.
   */
  double GetRelativeL2Error() const;
  double GetRMSE() const;
  double GetMaxAbsError() const;
  double GetPSNR() const;
  double GetPSNRPeak() const;
  double GetTestFlux() const;
  double GetReferenceFlux() const;
  double GetFluxRatio() const;
  double GetPeakPositionError() const;
  vtkIdType GetNumberOfComparedPixels() const;
  vtkIdType GetNumberOfNonFinitePixels() const;
  ///@}

  /**
   * One line for logs and CSV: "relL2=... rmse=... maxAbs=... psnrDb=...
   * fluxRatio=... peakErrPx=... compared=... nonFinite=...", or "error: ..." after
   * a failed Compute().
   */
  std::string GetSummary() const;

  /**
   * Adds (or replaces) a 1-component unsigned char array maskName on image: 1 where
   * the 1-component array sourceArray is finite and within [minValue, maxValue], 0
   * elsewhere. E.g. a receiver mask from a role or depth array. Returns false, with
   * an error naming the problem, when the image or a suitable source array is missing.
   */
  static bool AddRangeMask(vtkImageData* image, const char* sourceArray, double minValue,
    double maxValue, const char* maskName);

#ifndef __VTK_WRAP__
  /** All results of one Compute(), as the getters above report them. */
  struct Result
  {
    double RelativeL2Error = std::numeric_limits<double>::quiet_NaN();
    double RMSE = std::numeric_limits<double>::quiet_NaN();
    double MaxAbsError = std::numeric_limits<double>::quiet_NaN();
    double PSNR = std::numeric_limits<double>::quiet_NaN(); ///< dB
    double PSNRPeak = std::numeric_limits<double>::quiet_NaN();
    double TestFlux = std::numeric_limits<double>::quiet_NaN();
    double ReferenceFlux = std::numeric_limits<double>::quiet_NaN();
    double FluxRatio = std::numeric_limits<double>::quiet_NaN();
    double PeakPositionError = std::numeric_limits<double>::quiet_NaN(); ///< pixels
    int TestPeak[2] = { -1, -1 };      ///< (column, row) of the test image's caustic peak
    int ReferencePeak[2] = { -1, -1 }; ///< (column, row) of the reference's caustic peak
    vtkIdType ComparedPixels = 0;
    vtkIdType NonFinitePixels = 0;
  };

  /** The results of the last Compute(). */
  const Result& GetResult() const
  {
    return this->Metrics;
  }
#endif

protected:
  vtkCausticsErrorMetrics();
  ~vtkCausticsErrorMetrics() override;

  std::string ArrayName = "CausticIrradiance";
  std::string MaskArrayName;
  std::string AreaArrayName;
  int PeakFilterRadius = 1;
  std::string LastError;

private:
  vtkCausticsErrorMetrics(const vtkCausticsErrorMetrics&) = delete;
  void operator=(const vtkCausticsErrorMetrics&) = delete;

  /** Records the error, reports it with vtkErrorMacro and returns false. */
  bool Fail(const std::string& message);

#ifndef __VTK_WRAP__
  Result Metrics;
#endif
};

#endif
