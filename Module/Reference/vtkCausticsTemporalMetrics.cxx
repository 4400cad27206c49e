#include "vtkCausticsTemporalMetrics.h"

#include "vtkCallbackCommand.h"
#include "vtkCausticsErrorMetrics.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCausticsTemporalMetrics);

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/** The array `name` of `image` as doubles (pixel-major), or empty when not named/present. */
std::vector<double> Read(vtkImageData* image, const std::string& name)
{
  vtkDataArray* array = name.empty() ? nullptr : image->GetPointData()->GetArray(name.c_str());
  std::vector<double> values;
  if (!array)
  {
    return values;
  }
  const int components = array->GetNumberOfComponents();
  values.resize(static_cast<std::size_t>(array->GetNumberOfTuples()) * components);
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      values[static_cast<std::size_t>(i) * components + c] = array->GetComponent(i, c);
    }
  }
  return values;
}

/**
 * Mean and standard deviation (divisor n - ddof) of values[k][i] over frames k in
 * [begin, end), shifted by the first frame's value so that a constant gives exactly 0.
 */
std::pair<double, double> Moments(
  const std::vector<std::vector<double>>& values, std::size_t i, int begin, int end, int ddof)
{
  const double shift = values[begin][i];
  double sum = 0.0, squares = 0.0;
  for (int k = begin; k < end; ++k)
  {
    const double d = values[k][i] - shift;
    sum += d;
    squares += d * d;
  }
  const int n = end - begin;
  const double mean = sum / n;
  const double variance = std::max(0.0, (squares - n * mean * mean) / (n - ddof));
  return { shift + mean, std::sqrt(variance) };
}

/** Sums over the values of one class of pixel-segments (static or moving). */
struct Sums
{
  double Weighted = 0.0; // sum w s / m (flicker numerator)
  double Weight = 0.0;   // sum w
  double SquaredError = 0.0;
  double SquaredReference = 0.0;
  vtkIdType Values = 0;
};

/** The frames added so far (values pixel-major, channels inner), checked by the metrics. */
struct FrameData
{
  int Dimensions[3] = { 0, 0, 0 };
  int Components = 0;
  std::vector<std::vector<double>> Test, Reference, Area; // per frame
  std::vector<unsigned char> Masked;         // per pixel: masked in every reference frame
  std::vector<unsigned char> Finite;         // per pixel: finite in every test frame
  std::vector<double> RelativeL2, FluxRatio; // per frame

  std::size_t Pixels() const { return this->Masked.size(); }
  int Count() const { return static_cast<int>(this->Test.size()); }
};

/** A segment of frames [Begin, End), whose flicker window starts at Settled. */
struct Segment
{
  int Begin, Settled, End;
};

/** Step 3: every channel of pixel p has a reference within the tolerance over the segment. */
bool IsStatic(const FrameData& s, std::size_t p, const Segment& segment, double tolerance)
{
  for (int c = 0; c < s.Components; ++c)
  {
    const auto reference =
      Moments(s.Reference, p * s.Components + c, segment.Begin, segment.End, 0);
    if (!(reference.second <= tolerance * reference.first))
    {
      return false;
    }
  }
  return true;
}

/** Step 5: the flicker term of value i (of pixel p) over the segment's settled frames. */
void AddFlicker(
  const FrameData& s, std::size_t p, std::size_t i, const Segment& segment, Sums& sums)
{
  const int n = segment.End - segment.Settled;
  if (n < 2)
  {
    return;
  }
  double w = 0.0; // the reference's mean flux at the pixel
  for (int k = segment.Settled; k < segment.End; ++k)
  {
    w += (s.Area[k].empty() ? 1.0 : s.Area[k][p]) * s.Reference[k][i] / n;
  }
  const auto test = Moments(s.Test, i, segment.Settled, segment.End, 1);
  const double rbar = Moments(s.Reference, i, segment.Settled, segment.End, 0).first;
  if (w > 0.0)
  {
    sums.Weighted += w * test.second / (test.first > 0.0 ? test.first : rbar);
    sums.Weight += w;
  }
}

/** Step 6: the squared error and reference of value i over every frame of the segment. */
void AddMovingError(const FrameData& s, std::size_t i, const Segment& segment, Sums& sums)
{
  for (int k = segment.Begin; k < segment.End; ++k)
  {
    const double difference = s.Test[k][i] - s.Reference[k][i];
    sums.SquaredError += difference * difference;
    sums.SquaredReference += s.Reference[k][i] * s.Reference[k][i];
  }
}
}

struct vtkCausticsTemporalMetrics::Frames : FrameData
{
};

vtkCausticsTemporalMetrics::vtkCausticsTemporalMetrics()
  : Sequence(new Frames)
{
}

vtkCausticsTemporalMetrics::~vtkCausticsTemporalMetrics() = default;

void vtkCausticsTemporalMetrics::Reset()
{
  this->Sequence.reset(new Frames);
  this->Metrics = Result();
  this->LastError.clear();
}

int vtkCausticsTemporalMetrics::GetNumberOfFrames() const
{
  return this->Sequence->Count();
}

bool vtkCausticsTemporalMetrics::AddFrame(vtkImageData* test, vtkImageData* reference)
{
  this->LastError.clear();
  vtkNew<vtkCausticsErrorMetrics> frame;
  frame->SetArrayName(this->ArrayName.c_str());
  frame->SetMaskArrayName(this->MaskArrayName.c_str());
  frame->SetAreaArrayName(this->AreaArrayName.c_str());
  // Its error comes back as this object's one error; masked NaN/Inf test pixels are
  // counted and reported once by Compute(), not per frame.
  vtkNew<vtkCallbackCommand> quiet;
  frame->AddObserver(vtkCommand::WarningEvent, quiet);
  frame->AddObserver(vtkCommand::ErrorEvent, quiet);
  const int k = this->Sequence->Count();
  if (!frame->Compute(test, reference))
  {
    return this->Fail("frame " + std::to_string(k) + ": " + frame->GetLastError());
  }
  Frames& s = *this->Sequence;
  int dims[3];
  test->GetDimensions(dims);
  const std::vector<double> t = Read(test, this->ArrayName);
  const int components = static_cast<int>(t.size() / test->GetNumberOfPoints());
  if (k == 0)
  {
    std::copy(dims, dims + 3, s.Dimensions);
    s.Components = components;
    s.Masked.assign(static_cast<std::size_t>(test->GetNumberOfPoints()), 1);
    s.Finite.assign(s.Masked.size(), 1);
  }
  else if (!std::equal(dims, dims + 3, s.Dimensions) || components != s.Components)
  {
    return this->Fail("frame " + std::to_string(k) + " is " + std::to_string(dims[0]) + "x" +
      std::to_string(dims[1]) + " with " + std::to_string(components) +
      " components; the first frame is " + std::to_string(s.Dimensions[0]) + "x" +
      std::to_string(s.Dimensions[1]) + " with " + std::to_string(s.Components));
  }
  const std::vector<double> mask = Read(reference, this->MaskArrayName);
  for (std::size_t p = 0; p < s.Pixels(); ++p)
  {
    const double* v = &t[p * components];
    const bool finite = std::all_of(v, v + components, [](double x) { return std::isfinite(x); });
    s.Finite[p] = s.Finite[p] && finite;
    s.Masked[p] = s.Masked[p] && (mask.empty() || mask[p] != 0.0);
  }
  s.Test.push_back(t);
  s.Reference.push_back(Read(reference, this->ArrayName));
  s.Area.push_back(Read(reference, this->AreaArrayName));
  s.RelativeL2.push_back(frame->GetRelativeL2Error());
  s.FluxRatio.push_back(frame->GetFluxRatio());
  return true;
}

bool vtkCausticsTemporalMetrics::Compute()
{
  this->Metrics = Result();
  this->LastError.clear();
  const Frames& s = *this->Sequence;
  const int frames = s.Count();
  if (frames < 2)
  {
    return this->Fail("temporal metrics need at least 2 frames, got " + std::to_string(frames));
  }
  if (this->CutFrame != -1 && (this->CutFrame < 1 || this->CutFrame > frames - 1))
  {
    return this->Fail("cut frame " + std::to_string(this->CutFrame) + " is outside [1, " +
      std::to_string(frames - 1) + "] (-1: no cut)");
  }
  Result& r = this->Metrics;
  double error = 0.0, flux = 0.0;
  for (int k = 0; k < frames; ++k)
  {
    error += s.RelativeL2[k];
    flux += s.FluxRatio[k];
  }
  r.MeanRelativeL2Error = error / frames;
  r.MeanFluxRatio = flux / frames;
  this->ComputeLag();
  this->ComputeSegments();
  return true;
}

void vtkCausticsTemporalMetrics::ComputeLag()
{
  const Frames& s = *this->Sequence;
  const int cut = this->CutFrame, frames = s.Count();
  Result& r = this->Metrics;
  if (cut < 0)
  {
    return;
  }
  const int after = frames - cut;
  r.SteadyError =
    Median(std::vector<double>(s.RelativeL2.begin() + cut + after / 2, s.RelativeL2.end()));
  const double settled = (1.0 + this->SettleTolerance) * r.SteadyError;
  r.Lag = 0;
  for (int k = frames - 1; k >= cut; --k)
  {
    if (!(s.RelativeL2[k] <= settled))
    {
      r.Lag = k - cut + 1;
      break;
    }
  }
  const int settling = std::max(r.Lag, 1);
  double sum = 0.0;
  for (int k = cut; k < cut + settling; ++k)
  {
    sum += s.RelativeL2[k];
  }
  const double mean = sum / settling;
  r.Ghosting = r.SteadyError > 0.0 ? mean / r.SteadyError
    : mean > 0.0                   ? std::numeric_limits<double>::infinity()
                                   : 1.0;
}

void vtkCausticsTemporalMetrics::ComputeSegments()
{
  const Frames& s = *this->Sequence;
  const int frames = s.Count(), cut = this->CutFrame;
  Result& r = this->Metrics;
  std::vector<Segment> segments;
  if (cut < 0)
  {
    segments.push_back({ 0, 0, frames });
  }
  else
  {
    segments.push_back({ 0, 0, cut });
    segments.push_back({ cut, cut + r.Lag, frames });
  }
  Sums still, moving;
  for (std::size_t p = 0; p < s.Pixels(); ++p)
  {
    if (!s.Masked[p] || !s.Finite[p])
    {
      r.NonFinitePixels += s.Masked[p] ? 1 : 0;
      continue;
    }
    for (const Segment& segment : segments)
    {
      const bool isStatic = IsStatic(s, p, segment, this->StaticTolerance);
      (isStatic ? still : moving).Values += s.Components;
      for (int c = 0; c < s.Components; ++c)
      {
        const std::size_t i = p * s.Components + c;
        isStatic ? AddFlicker(s, p, i, segment, still) : AddMovingError(s, i, segment, moving);
      }
    }
  }
  if (r.NonFinitePixels > 0)
  {
    vtkWarningMacro(<< r.NonFinitePixels << " receiver pixels have NaN/Inf in '" << this->ArrayName
                    << "' in some frame; they are left out of the temporal metrics");
  }
  r.StaticValues = still.Values;
  r.MovingValues = moving.Values;
  r.Flicker = still.Weight > 0.0 ? still.Weighted / still.Weight : NaN;
  r.MovingError =
    moving.SquaredReference > 0.0 ? std::sqrt(moving.SquaredError / moving.SquaredReference) : NaN;
}

bool vtkCausticsTemporalMetrics::Fail(const std::string& message)
{
  this->Metrics = Result();
  this->LastError = message;
  vtkErrorMacro(<< message);
  return false;
}

double vtkCausticsTemporalMetrics::GetFrameRelativeL2Error(int k) const
{
  return k >= 0 && k < this->Sequence->Count() ? this->Sequence->RelativeL2[k] : NaN;
}

double vtkCausticsTemporalMetrics::GetFrameFluxRatio(int k) const
{
  return k >= 0 && k < this->Sequence->Count() ? this->Sequence->FluxRatio[k] : NaN;
}

double vtkCausticsTemporalMetrics::GetFlicker() const
{
  return this->Metrics.Flicker;
}

double vtkCausticsTemporalMetrics::GetMovingError() const
{
  return this->Metrics.MovingError;
}

double vtkCausticsTemporalMetrics::GetMeanRelativeL2Error() const
{
  return this->Metrics.MeanRelativeL2Error;
}

double vtkCausticsTemporalMetrics::GetMeanFluxRatio() const
{
  return this->Metrics.MeanFluxRatio;
}

double vtkCausticsTemporalMetrics::GetSteadyError() const
{
  return this->Metrics.SteadyError;
}

int vtkCausticsTemporalMetrics::GetLag() const
{
  return this->Metrics.Lag;
}

double vtkCausticsTemporalMetrics::GetGhosting() const
{
  return this->Metrics.Ghosting;
}

vtkIdType vtkCausticsTemporalMetrics::GetNumberOfStaticValues() const
{
  return this->Metrics.StaticValues;
}

vtkIdType vtkCausticsTemporalMetrics::GetNumberOfMovingValues() const
{
  return this->Metrics.MovingValues;
}

vtkIdType vtkCausticsTemporalMetrics::GetNumberOfNonFinitePixels() const
{
  return this->Metrics.NonFinitePixels;
}

std::string vtkCausticsTemporalMetrics::GetSummary() const
{
  if (!this->LastError.empty())
  {
    return "error: " + this->LastError;
  }
  const Result& r = this->Metrics;
  char line[320];
  std::snprintf(line, sizeof(line),
    "flicker=%.6g movingErr=%.6g meanRelL2=%.6g meanFlux=%.6g steadyErr=%.6g lag=%d "
    "ghosting=%.6g static=%lld moving=%lld nonFinite=%lld",
    r.Flicker, r.MovingError, r.MeanRelativeL2Error, r.MeanFluxRatio, r.SteadyError, r.Lag,
    r.Ghosting, static_cast<long long>(r.StaticValues), static_cast<long long>(r.MovingValues),
    static_cast<long long>(r.NonFinitePixels));
  return line;
}

void vtkCausticsTemporalMetrics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ArrayName: " << this->ArrayName << "\n";
  os << indent
     << "MaskArrayName: " << (this->MaskArrayName.empty() ? "(none)" : this->MaskArrayName) << "\n";
  os << indent
     << "AreaArrayName: " << (this->AreaArrayName.empty() ? "(none)" : this->AreaArrayName) << "\n";
  os << indent << "CutFrame: " << this->CutFrame << "\n";
  os << indent << "StaticTolerance: " << this->StaticTolerance << "\n";
  os << indent << "SettleTolerance: " << this->SettleTolerance << "\n";
  os << indent << "Frames: " << this->GetNumberOfFrames() << "\n";
  os << indent << "Result: " << this->GetSummary() << "\n";
}
