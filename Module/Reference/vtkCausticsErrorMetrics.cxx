#include "vtkCausticsErrorMetrics.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkCausticsErrorMetrics);

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

/** The arrays of both images once checked, copied to doubles (pixel-major). */
struct Inputs
{
  int Width = 0;
  int Height = 0;
  int Components = 0;
  std::vector<double> Test;
  std::vector<double> Reference;
  std::vector<double> Area; ///< one per pixel; empty = every pixel weighs 1
  /** One per pixel: 1 in the mask; SelectPixels() then clears the NaN/Inf test pixels. */
  std::vector<unsigned char> Compared;
  vtkIdType FirstNonFinite = -1; ///< first masked test pixel with a NaN/Inf
};

std::string Pixel(vtkIdType id, int width)
{
  return "(" + std::to_string(id % width) + ", " + std::to_string(id / width) + ")";
}

std::string Number(double value)
{
  std::ostringstream os;
  os << value;
  return os.str();
}

std::vector<double> Values(vtkDataArray* array)
{
  const int components = array->GetNumberOfComponents();
  std::vector<double> values(static_cast<std::size_t>(array->GetNumberOfTuples()) * components);
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      values[static_cast<std::size_t>(i) * components + c] = array->GetComponent(i, c);
    }
  }
  return values;
}

/** The point-data array `name` of `image` with one tuple per pixel, or an error. */
std::string FindArray(
  vtkImageData* image, const std::string& name, const std::string& which, vtkDataArray*& array)
{
  array = image->GetPointData()->GetArray(name.c_str());
  if (!array)
  {
    return which + " image has no point-data array '" + name + "'";
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    return "array '" + name + "' of the " + which + " image has " +
      std::to_string(array->GetNumberOfTuples()) + " tuples for " +
      std::to_string(image->GetNumberOfPoints()) + " pixels";
  }
  return std::string();
}

/** Both images exist, have the same size, and are non-empty 2D images. */
std::string CheckImages(vtkImageData* test, vtkImageData* reference, int dims[3])
{
  if (!test || !reference)
  {
    return test ? "no reference image" : "no test image";
  }
  int referenceDims[3];
  test->GetDimensions(dims);
  reference->GetDimensions(referenceDims);
  const auto size = [](const int d[3])
  { return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]); };
  if (!std::equal(dims, dims + 3, referenceDims))
  {
    return "test image is " + size(dims) + " pixels but the reference is " + size(referenceDims);
  }
  if (dims[0] < 1 || dims[1] < 1 || dims[2] != 1)
  {
    return "images are " + size(dims) + "; the metrics compare non-empty 2D images";
  }
  return std::string();
}

/** The compared array of both images, with 1 or 3 matching components. */
std::string ReadCompared(
  vtkImageData* test, vtkImageData* reference, const std::string& arrayName, Inputs& in)
{
  if (arrayName.empty())
  {
    return "no array name set";
  }
  vtkDataArray *testArray, *referenceArray;
  std::string problem = FindArray(test, arrayName, "test", testArray);
  if (problem.empty())
  {
    problem = FindArray(reference, arrayName, "reference", referenceArray);
  }
  if (!problem.empty())
  {
    return problem;
  }
  const int components = testArray->GetNumberOfComponents();
  if (components != referenceArray->GetNumberOfComponents())
  {
    return "array '" + arrayName + "' has " + std::to_string(components) +
      " components in the test image but " +
      std::to_string(referenceArray->GetNumberOfComponents()) + " in the reference";
  }
  if (components != 1 && components != 3)
  {
    return "array '" + arrayName + "' has " + std::to_string(components) +
      " components; the metrics compare 1 (scalar) or 3 (RGB)";
  }
  in.Components = components;
  in.Test = Values(testArray);
  in.Reference = Values(referenceArray);
  return std::string();
}

/**
 * The reference's optional 1-component array `what` (mask or area) named `name`:
 * nullptr when no name is set.
 */
std::string FindOptionalScalarArray(
  vtkImageData* reference, const std::string& name, const std::string& what, vtkDataArray*& array)
{
  array = nullptr;
  if (name.empty())
  {
    return std::string();
  }
  const std::string problem = FindArray(reference, name, "reference", array);
  if (!problem.empty())
  {
    return what + ": " + problem;
  }
  if (array->GetNumberOfComponents() != 1)
  {
    return what + " array '" + name + "' has " + std::to_string(array->GetNumberOfComponents()) +
      " components; expected 1";
  }
  return std::string();
}

/** The mask, if named: pixels where it is non-zero are compared. */
std::string ReadMask(vtkImageData* reference, const std::string& maskName, Inputs& in)
{
  vtkDataArray* mask;
  const std::string problem = FindOptionalScalarArray(reference, maskName, "mask", mask);
  if (!mask || !problem.empty())
  {
    return problem;
  }
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(in.Compared.size()); ++i)
  {
    const double value = mask->GetComponent(i, 0);
    if (!std::isfinite(value))
    {
      return "mask array '" + maskName + "' is NaN/Inf at pixel " + Pixel(i, in.Width);
    }
    in.Compared[i] = value != 0.0;
  }
  return std::string();
}

/** The pixel areas, if named: finite and >= 0 wherever compared. */
std::string ReadArea(vtkImageData* reference, const std::string& areaName, Inputs& in)
{
  vtkDataArray* area;
  const std::string problem = FindOptionalScalarArray(reference, areaName, "area", area);
  if (!area || !problem.empty())
  {
    return problem;
  }
  in.Area = Values(area);
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(in.Compared.size()); ++i)
  {
    // Only masked pixels enter the flux: background pixels may have no finite area.
    if (in.Compared[i] && !(std::isfinite(in.Area[i]) && in.Area[i] >= 0.0))
    {
      return "area array '" + areaName + "' is " + Number(in.Area[i]) + " at pixel " +
        Pixel(i, in.Width) + "; areas must be finite and >= 0";
    }
  }
  return std::string();
}

/** A reference must be finite wherever it is compared. */
std::string CheckReferenceFinite(const std::string& arrayName, const Inputs& in)
{
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(in.Compared.size()); ++i)
  {
    for (int c = 0; c < in.Components; ++c)
    {
      const double value = in.Reference[static_cast<std::size_t>(i) * in.Components + c];
      if (in.Compared[i] && !std::isfinite(value))
      {
        return "reference '" + arrayName + "' is NaN/Inf at pixel " + Pixel(i, in.Width) +
          "; a reference must be finite";
      }
    }
  }
  return std::string();
}

/** Step 1: checks both images and reads the compared, mask and area arrays. */
std::string ReadInputs(vtkImageData* test, vtkImageData* reference, const std::string& arrayName,
  const std::string& maskName, const std::string& areaName, Inputs& in)
{
  int dims[3];
  std::string problem = CheckImages(test, reference, dims);
  if (problem.empty())
  {
    problem = ReadCompared(test, reference, arrayName, in);
  }
  if (!problem.empty())
  {
    return problem;
  }
  in.Width = dims[0];
  in.Height = dims[1];
  in.Compared.assign(static_cast<std::size_t>(reference->GetNumberOfPoints()), 1);
  problem = ReadMask(reference, maskName, in);
  if (problem.empty())
  {
    problem = ReadArea(reference, areaName, in);
  }
  return problem.empty() ? CheckReferenceFinite(arrayName, in) : problem;
}

/** Step 2: drops masked pixels whose test value is not finite, counting them. */
std::string SelectPixels(
  const std::string& maskName, Inputs& in, vtkCausticsErrorMetrics::Result& r)
{
  vtkIdType masked = 0;
  for (std::size_t i = 0; i < in.Compared.size(); ++i)
  {
    if (!in.Compared[i])
    {
      continue;
    }
    ++masked;
    const double* t = &in.Test[i * in.Components];
    if (!std::all_of(t, t + in.Components, [](double v) { return std::isfinite(v); }))
    {
      in.Compared[i] = 0;
      if (r.NonFinitePixels++ == 0)
      {
        in.FirstNonFinite = static_cast<vtkIdType>(i);
      }
    }
  }
  r.ComparedPixels = masked - r.NonFinitePixels;
  if (masked == 0)
  {
    return "mask '" + maskName + "' selects no pixels";
  }
  if (r.ComparedPixels == 0)
  {
    return "all " + std::to_string(masked) + " masked pixels of the test image are NaN/Inf";
  }
  return std::string();
}

/** Steps 3 and 4: the error sums over the compared pixels and the metrics derived from them. */
std::string Accumulate(
  const std::string& arrayName, const Inputs& in, vtkCausticsErrorMetrics::Result& r)
{
  double squaredError = 0.0, squaredReference = 0.0, maxError = 0.0, peak = 0.0;
  double testFlux = 0.0, referenceFlux = 0.0;
  for (std::size_t i = 0; i < in.Compared.size(); ++i)
  {
    if (!in.Compared[i])
    {
      continue;
    }
    const double area = in.Area.empty() ? 1.0 : in.Area[i];
    for (int c = 0; c < in.Components; ++c)
    {
      const double t = in.Test[i * in.Components + c];
      const double ref = in.Reference[i * in.Components + c];
      const double error = t - ref;
      squaredError += error * error;
      squaredReference += ref * ref;
      maxError = std::max(maxError, std::abs(error));
      peak = std::max(peak, std::abs(ref));
      testFlux += area * t;
      referenceFlux += area * ref;
    }
  }
  if (squaredReference == 0.0)
  {
    return "reference '" + arrayName + "' is zero over all " + std::to_string(r.ComparedPixels) +
      " compared pixels; relative errors are undefined";
  }
  const double values = static_cast<double>(r.ComparedPixels) * in.Components;
  r.RelativeL2Error = std::sqrt(squaredError / squaredReference);
  r.RMSE = std::sqrt(squaredError / values);
  r.MaxAbsError = maxError;
  r.PSNRPeak = peak;
  r.PSNR =
    r.RMSE > 0.0 ? 20.0 * std::log10(peak / r.RMSE) : std::numeric_limits<double>::infinity();
  r.TestFlux = testFlux;
  r.ReferenceFlux = referenceFlux;
  r.FluxRatio = referenceFlux != 0.0 ? testFlux / referenceFlux : NaN;
  return std::string();
}

/**
 * Step 5: the compared pixel with the largest box sum of luminance; the first in
 * point-id order wins a tie. Sums run in the same order for every pixel, so equal
 * neighbourhoods give bit-identical sums.
 */
void LocatePeak(const Inputs& in, const std::vector<double>& values, int radius, int peak[2])
{
  // Rec. 709 / sRGB luminance of linear RGB.
  const double weights[3] = { 0.2126, 0.7152, 0.0722 };
  std::vector<double> luminance(in.Compared.size(), 0.0);
  for (std::size_t i = 0; i < luminance.size(); ++i)
  {
    if (in.Compared[i])
    {
      const double* v = &values[i * in.Components];
      luminance[i] =
        in.Components == 1 ? v[0] : weights[0] * v[0] + weights[1] * v[1] + weights[2] * v[2];
    }
  }
  double best = -std::numeric_limits<double>::infinity();
  for (int y = 0; y < in.Height; ++y)
  {
    for (int x = 0; x < in.Width; ++x)
    {
      if (!in.Compared[static_cast<std::size_t>(y) * in.Width + x])
      {
        continue;
      }
      double sum = 0.0;
      for (int j = std::max(0, y - radius); j <= std::min(in.Height - 1, y + radius); ++j)
      {
        for (int i = std::max(0, x - radius); i <= std::min(in.Width - 1, x + radius); ++i)
        {
          sum += luminance[static_cast<std::size_t>(j) * in.Width + i];
        }
      }
      if (sum > best || peak[0] < 0)
      {
        best = sum;
        peak[0] = x;
        peak[1] = y;
      }
    }
  }
}
}

vtkCausticsErrorMetrics::vtkCausticsErrorMetrics() = default;
vtkCausticsErrorMetrics::~vtkCausticsErrorMetrics() = default;

void vtkCausticsErrorMetrics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ArrayName: " << this->ArrayName << "\n";
  os << indent
     << "MaskArrayName: " << (this->MaskArrayName.empty() ? "(none)" : this->MaskArrayName) << "\n";
  os << indent
     << "AreaArrayName: " << (this->AreaArrayName.empty() ? "(none)" : this->AreaArrayName) << "\n";
  os << indent << "PeakFilterRadius: " << this->PeakFilterRadius << "\n";
  os << indent << "Result: " << this->GetSummary() << "\n";
}

bool vtkCausticsErrorMetrics::Compute(vtkImageData* test, vtkImageData* reference)
{
  Result& r = this->Metrics;
  r = Result();
  this->LastError.clear();
  Inputs in;
  std::string problem =
    ReadInputs(test, reference, this->ArrayName, this->MaskArrayName, this->AreaArrayName, in);
  if (problem.empty())
  {
    problem = SelectPixels(this->MaskArrayName, in, r);
  }
  if (problem.empty())
  {
    problem = Accumulate(this->ArrayName, in, r);
  }
  if (!problem.empty())
  {
    return this->Fail(problem);
  }
  if (r.NonFinitePixels > 0)
  {
    vtkWarningMacro(<< r.NonFinitePixels << " masked pixels of the test image have NaN/Inf in '"
                    << this->ArrayName << "' (first at " << Pixel(in.FirstNonFinite, in.Width)
                    << "); they are left out of every metric");
  }
  if (std::isnan(r.FluxRatio))
  {
    vtkWarningMacro(<< "the reference flux over the compared pixels is 0; no flux ratio");
  }
  LocatePeak(in, in.Test, this->PeakFilterRadius, r.TestPeak);
  LocatePeak(in, in.Reference, this->PeakFilterRadius, r.ReferencePeak);
  r.PeakPositionError =
    std::hypot(r.TestPeak[0] - r.ReferencePeak[0], r.TestPeak[1] - r.ReferencePeak[1]);
  return true;
}

bool vtkCausticsErrorMetrics::Fail(const std::string& message)
{
  // The counts stay: they say how far the comparison got.
  Result failed;
  failed.ComparedPixels = this->Metrics.ComparedPixels;
  failed.NonFinitePixels = this->Metrics.NonFinitePixels;
  this->Metrics = failed;
  this->LastError = message;
  vtkErrorMacro(<< message);
  return false;
}

double vtkCausticsErrorMetrics::GetRelativeL2Error() const
{
  return this->Metrics.RelativeL2Error;
}

double vtkCausticsErrorMetrics::GetRMSE() const
{
  return this->Metrics.RMSE;
}

double vtkCausticsErrorMetrics::GetMaxAbsError() const
{
  return this->Metrics.MaxAbsError;
}

double vtkCausticsErrorMetrics::GetPSNR() const
{
  return this->Metrics.PSNR;
}

double vtkCausticsErrorMetrics::GetPSNRPeak() const
{
  return this->Metrics.PSNRPeak;
}

double vtkCausticsErrorMetrics::GetTestFlux() const
{
  return this->Metrics.TestFlux;
}

double vtkCausticsErrorMetrics::GetReferenceFlux() const
{
  return this->Metrics.ReferenceFlux;
}

double vtkCausticsErrorMetrics::GetFluxRatio() const
{
  return this->Metrics.FluxRatio;
}

double vtkCausticsErrorMetrics::GetPeakPositionError() const
{
  return this->Metrics.PeakPositionError;
}

vtkIdType vtkCausticsErrorMetrics::GetNumberOfComparedPixels() const
{
  return this->Metrics.ComparedPixels;
}

vtkIdType vtkCausticsErrorMetrics::GetNumberOfNonFinitePixels() const
{
  return this->Metrics.NonFinitePixels;
}

std::string vtkCausticsErrorMetrics::GetSummary() const
{
  if (!this->LastError.empty())
  {
    return "error: " + this->LastError;
  }
  const Result& r = this->Metrics;
  char line[320];
  std::snprintf(line, sizeof(line),
    "relL2=%.6g rmse=%.6g maxAbs=%.6g psnrDb=%.6g fluxRatio=%.6g peakErrPx=%.6g compared=%lld "
    "nonFinite=%lld",
    r.RelativeL2Error, r.RMSE, r.MaxAbsError, r.PSNR, r.FluxRatio, r.PeakPositionError,
    static_cast<long long>(r.ComparedPixels), static_cast<long long>(r.NonFinitePixels));
  return line;
}

bool vtkCausticsErrorMetrics::AddRangeMask(vtkImageData* image, const char* sourceArray,
  double minValue, double maxValue, const char* maskName)
{
  vtkDataArray* source =
    image && sourceArray ? image->GetPointData()->GetArray(sourceArray) : nullptr;
  std::string problem;
  if (!image || !maskName || !*maskName)
  {
    problem = image ? "no mask name" : "no image";
  }
  else if (!source || source->GetNumberOfComponents() != 1 ||
    source->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    problem = std::string("image has no 1-component point-data array '") +
      (sourceArray ? sourceArray : "(null)") + "' with one value per pixel";
  }
  else if (!(minValue <= maxValue))
  {
    problem = "empty range [" + Number(minValue) + ", " + Number(maxValue) + "]";
  }
  if (!problem.empty())
  {
    vtkErrorWithObjectMacro(image, << "vtkCausticsErrorMetrics::AddRangeMask: " << problem);
    return false;
  }
  vtkNew<vtkUnsignedCharArray> mask;
  mask->SetName(maskName);
  mask->SetNumberOfValues(source->GetNumberOfTuples());
  for (vtkIdType i = 0; i < source->GetNumberOfTuples(); ++i)
  {
    const double value = source->GetComponent(i, 0);
    mask->SetValue(i, std::isfinite(value) && value >= minValue && value <= maxValue);
  }
  image->GetPointData()->RemoveArray(maskName);
  image->GetPointData()->AddArray(mask);
  return true;
}
