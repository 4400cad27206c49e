// vtkCausticsErrorMetrics on synthetic images whose metrics are known in closed
// form: scaled and offset images, shifted Gaussian peaks, masks, pixel areas, NaN
// pixels and every kind of input the metrics must refuse.
#include "vtkCausticsErrorMetrics.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>

namespace
{
const char* Irradiance = "CausticIrradiance";
const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

using PixelFunction = std::function<double(int x, int y, int c)>;

/** Adds a double array filled from f(x, y, component) to an image. */
void AddArray(vtkImageData* image, const char* name, int components, const PixelFunction& f)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1]);
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      for (int c = 0; c < components; ++c)
      {
        array->SetComponent(static_cast<vtkIdType>(y) * dims[0] + x, c, f(x, y, c));
      }
    }
  }
  image->GetPointData()->AddArray(array);
}

vtkSmartPointer<vtkImageData> MakeImage(
  int width, int height, int components, const PixelFunction& f, const char* name = Irradiance)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  AddArray(image, name, components, f);
  return image;
}

/** Gaussian spot of the given peak value centred on pixel (cx, cy). */
PixelFunction Gaussian(double cx, double cy, double sigma, double peak)
{
  return [=](int x, int y, int)
  { return peak * std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (2.0 * sigma * sigma)); };
}

/** A caustic-like RGB image: coloured Gaussian on a dim background. */
double Caustic(int x, int y, int c)
{
  const double channelPeak[3] = { 2.0, 1.0, 0.5 };
  return 0.1 + Gaussian(20, 30, 3.0, channelPeak[c])(x, y, c);
}

/** Sum of squares of every value of an array (for the expected RMSE). */
double SumOfSquares(vtkImageData* image, const char* name)
{
  vtkDataArray* array = image->GetPointData()->GetArray(name);
  double sum = 0.0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      sum += array->GetComponent(i, c) * array->GetComponent(i, c);
    }
  }
  return sum;
}
}

// t = 1.1 r: ||t - r|| = 0.1 ||r|| and every flux grows by 1.1, whatever r is.
TEST(ErrorMetrics, ScaledImageGivesRelativeErrorAndFluxRatio)
{
  auto reference = MakeImage(64, 64, 3, Caustic);
  auto test = MakeImage(64, 64, 3, [](int x, int y, int c) { return 1.1 * Caustic(x, y, c); });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  // Tolerance 1e-12: double rounding of 1.1 r (2^-53 relative per value) summed over
  // 12288 values stays below 1e-12 relative.
  EXPECT_NEAR(metrics->GetRelativeL2Error(), 0.1, 1e-12);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.1, 1e-12);
  EXPECT_NEAR(metrics->GetRMSE(),
    0.1 * std::sqrt(SumOfSquares(reference, Irradiance) / (64 * 64 * 3)), 1e-12);
  // Largest error at the peak of the red channel: 0.1 x (0.1 + 2.0).
  EXPECT_NEAR(metrics->GetMaxAbsError(), 0.21, 1e-12);
  EXPECT_DOUBLE_EQ(metrics->GetPSNRPeak(), 2.1);
  EXPECT_EQ(metrics->GetPeakPositionError(), 0.0);
  EXPECT_EQ(metrics->GetResult().ReferencePeak[0], 20);
  EXPECT_EQ(metrics->GetResult().ReferencePeak[1], 30);
  EXPECT_EQ(metrics->GetNumberOfComparedPixels(), 64 * 64);
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 0);
  EXPECT_STREQ(metrics->GetLastError(), "");
  const std::string summary = metrics->GetSummary();
  std::cout << summary << "\n"; // quoted in docs/accuracy.md
  EXPECT_EQ(summary.rfind("relL2=0.1 rmse=", 0), 0u) << summary;
  EXPECT_NE(summary.find(" maxAbs=0.21 "), std::string::npos) << summary;
  EXPECT_NE(summary.find(" fluxRatio=1.1 peakErrPx=0 compared=4096 nonFinite=0"), std::string::npos)
    << summary;
}

// The same with float arrays, as the renderers write them.
TEST(ErrorMetrics, ScaledFloatImage)
{
  auto reference = vtkSmartPointer<vtkImageData>::New();
  auto test = vtkSmartPointer<vtkImageData>::New();
  reference->SetDimensions(32, 32, 1);
  test->SetDimensions(32, 32, 1);
  vtkNew<vtkFloatArray> r, t;
  for (vtkFloatArray* array : { r.Get(), t.Get() })
  {
    array->SetName(Irradiance);
    array->SetNumberOfComponents(1);
  }
  for (int i = 0; i < 32 * 32; ++i)
  {
    const float value = static_cast<float>(Caustic(i % 32, i / 32, 0));
    r->InsertNextValue(value);
    t->InsertNextValue(1.1f * value);
  }
  reference->GetPointData()->AddArray(r);
  test->GetPointData()->AddArray(t);
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  // 1.1f and the float product each round by at most 2^-24 relative, so t is
  // 1.1 r (1 + e) with |e| <= 2^-23 = 1.2e-7: the flux ratio is within 1.2e-7 of
  // 1.1 relative, and the difference 0.1 r within 1.1 x 1.2e-7 / 0.1 = 1.3e-6.
  EXPECT_NEAR(metrics->GetRelativeL2Error(), 0.1, 0.1 * 1.3e-6);
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.1, 1.1 * 1.2e-7);
}

// t = r + 0.02 everywhere: RMSE = max error = 0.02, PSNR = 20 log10(2 / 0.02) = 40 dB.
TEST(ErrorMetrics, ConstantOffsetGivesRMSEAndPSNR)
{
  auto reference = MakeImage(48, 40, 1, Gaussian(24, 20, 4.0, 2.0));
  auto test = MakeImage(
    48, 40, 1, [](int x, int y, int c) { return Gaussian(24, 20, 4.0, 2.0)(x, y, c) + 0.02; });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  // (r + 0.02) - r is exact to one rounding of a value <= 2.02 (4.4e-16), i.e.
  // 2.2e-14 of 0.02; 1e-12 leaves room for the sums.
  EXPECT_NEAR(metrics->GetRMSE(), 0.02, 0.02 * 1e-12);
  EXPECT_NEAR(metrics->GetMaxAbsError(), 0.02, 0.02 * 1e-12);
  EXPECT_DOUBLE_EQ(metrics->GetPSNRPeak(), 2.0);
  EXPECT_NEAR(metrics->GetPSNR(), 40.0, 1e-9);

  // Identical images: no error, infinite PSNR.
  ASSERT_TRUE(metrics->Compute(reference, reference));
  EXPECT_EQ(metrics->GetRelativeL2Error(), 0.0);
  EXPECT_EQ(metrics->GetRMSE(), 0.0);
  EXPECT_EQ(metrics->GetPSNR(), Inf);
  EXPECT_EQ(metrics->GetFluxRatio(), 1.0);
}

// The caustic moves by (3, 4) pixels: the peaks are 5 pixels apart.
TEST(ErrorMetrics, ShiftedGaussianGivesPeakError)
{
  auto reference = MakeImage(64, 64, 3, Gaussian(20, 30, 3.0, 1.0));
  auto test = MakeImage(64, 64, 3, Gaussian(23, 34, 3.0, 1.0));
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  const auto& result = metrics->GetResult();
  EXPECT_EQ(result.ReferencePeak[0], 20);
  EXPECT_EQ(result.ReferencePeak[1], 30);
  EXPECT_EQ(result.TestPeak[0], 23);
  EXPECT_EQ(result.TestPeak[1], 34);
  EXPECT_DOUBLE_EQ(metrics->GetPeakPositionError(), 5.0);
  // Same energy, moved: the flux ratio is 1 up to the tails cut by the image border,
  // at least 20 px = 6.7 sigma away: erfc(20 / (3 sqrt 2)) / 2 = 1.2e-11 of the spot.
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.0, 1e-10);
}

// A single hot pixel brighter than the caustic's maximum does not win the 3x3 box
// sum: around the Gaussian's centre it is 1 + 4 e^(-1/18) + 4 e^(-2/18) = 8.36 > 5.
TEST(ErrorMetrics, BoxFilterIgnoresHotPixel)
{
  auto reference = MakeImage(64, 64, 1, Gaussian(20, 30, 3.0, 1.0));
  auto test = MakeImage(64, 64, 1,
    [](int x, int y, int c)
    { return x == 50 && y == 10 ? 5.0 : Gaussian(20, 30, 3.0, 1.0)(x, y, c); });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetPeakPositionError(), 0.0);
  EXPECT_DOUBLE_EQ(metrics->GetMaxAbsError(), 5.0 - Gaussian(20, 30, 3.0, 1.0)(50, 10, 0));

  // Without the filter the hot pixel is the peak: (50, 10) is (30, -20) away.
  metrics->SetPeakFilterRadius(0);
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetResult().TestPeak[0], 50);
  EXPECT_EQ(metrics->GetResult().TestPeak[1], 10);
  EXPECT_DOUBLE_EQ(metrics->GetPeakPositionError(), std::hypot(30.0, 20.0));

  metrics->SetPeakFilterRadius(1000);
  EXPECT_EQ(metrics->GetPeakFilterRadius(), 16);
}

// Two identical plateaus: the one with the lower point id (lower row) is the peak.
TEST(ErrorMetrics, PeakTiesGoToLowestPointId)
{
  const auto square = [](int x, int y, int x0, int y0)
  { return x >= x0 && x < x0 + 5 && y >= y0 && y < y0 + 5; };
  auto test = MakeImage(64, 32, 1,
    [&](int x, int y, int) { return square(x, y, 38, 3) || square(x, y, 8, 18) ? 1.0 : 0.0; });
  auto reference =
    MakeImage(64, 32, 1, [&](int x, int y, int) { return square(x, y, 8, 18) ? 1.0 : 0.0; });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  // Every pixel whose 3x3 box lies inside a square sums to 9; the first of them in
  // point-id order is one pixel in from the square's lower-left corner.
  EXPECT_EQ(metrics->GetResult().TestPeak[0], 39);
  EXPECT_EQ(metrics->GetResult().TestPeak[1], 4);
  EXPECT_EQ(metrics->GetResult().ReferencePeak[0], 9);
  EXPECT_EQ(metrics->GetResult().ReferencePeak[1], 19);
  EXPECT_DOUBLE_EQ(metrics->GetPeakPositionError(), std::hypot(30.0, 15.0));
}

// The mask (on the reference) removes the left half, where the test image is wrong.
TEST(ErrorMetrics, MaskExcludesPixels)
{
  const auto ramp = [](int x, int y, int) { return 1.0 + 0.1 * x + 0.01 * y; };
  auto reference = MakeImage(64, 64, 1, ramp);
  auto test = MakeImage(
    64, 64, 1, [&](int x, int y, int c) { return x < 32 ? ramp(x, y, c) + 100.0 : ramp(x, y, c); });
  AddArray(reference, "ReceiverMask", 1, [](int x, int, int) { return x >= 32 ? 1.0 : 0.0; });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_GT(metrics->GetRelativeL2Error(), 1.0);
  EXPECT_GT(metrics->GetPeakPositionError(), 0.0);

  metrics->SetMaskArrayName("ReceiverMask");
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetNumberOfComparedPixels(), 32 * 64);
  EXPECT_EQ(metrics->GetRelativeL2Error(), 0.0);
  EXPECT_EQ(metrics->GetMaxAbsError(), 0.0);
  EXPECT_EQ(metrics->GetFluxRatio(), 1.0);
  EXPECT_EQ(metrics->GetPeakPositionError(), 0.0);
  EXPECT_GE(metrics->GetResult().TestPeak[0], 32);
  // The PSNR peak is the reference's maximum inside the mask: 1 + 6.3 + 0.63.
  EXPECT_DOUBLE_EQ(metrics->GetPSNRPeak(), ramp(63, 63, 0));

  // Peaks are masked pixels too: with a one-column mask, the box sums of the two
  // neighbouring columns equal the column's own, and column 39 would win the tie.
  AddArray(reference, "ReceiverMask", 1, [](int x, int, int) { return x == 40 ? 1.0 : 0.0; });
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetResult().TestPeak[0], 40);
  EXPECT_EQ(metrics->GetResult().ReferencePeak[0], 40);
  EXPECT_EQ(metrics->GetResult().ReferencePeak[1], 62);
}

// Pixel areas weight the flux sums only: right half 3x the area and 2x the value.
TEST(ErrorMetrics, AreasWeightTheFlux)
{
  auto reference = MakeImage(8, 4, 1, [](int, int, int) { return 1.0; });
  auto test = MakeImage(8, 4, 1, [](int x, int, int) { return x < 4 ? 1.0 : 2.0; });
  AddArray(reference, "PixelArea", 1, [](int x, int, int) { return x < 4 ? 1.0 : 3.0; });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetFluxRatio(), 48.0 / 32.0); // unweighted: 16 x 1 + 16 x 2 over 32

  metrics->SetAreaArrayName("PixelArea");
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetReferenceFlux(), 16 * 1.0 + 16 * 3.0);
  EXPECT_EQ(metrics->GetTestFlux(), 16 * 1.0 + 16 * 3.0 * 2.0);
  EXPECT_EQ(metrics->GetFluxRatio(), 112.0 / 64.0);
  // Areas do not weight the per-pixel errors: 16 of 32 pixels are off by 1.
  EXPECT_EQ(metrics->GetRMSE(), std::sqrt(0.5));

  // Background pixels outside the mask may have any area; masked ones may not.
  AddArray(reference, "ReceiverMask", 1, [](int x, int, int) { return x > 0 ? 1.0 : 0.0; });
  AddArray(reference, "PixelArea", 1, [](int x, int, int) { return x == 0 ? NaN : 1.0; });
  metrics->SetMaskArrayName("ReceiverMask");
  EXPECT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  AddArray(
    reference, "PixelArea", 1, [](int x, int y, int) { return x == 5 && y == 2 ? -1.0 : 1.0; });
  vtkNew<vtkTest::ErrorObserver> observer;
  metrics->AddObserver(vtkCommand::ErrorEvent, observer);
  EXPECT_FALSE(metrics->Compute(test, reference));
  EXPECT_NE(
    observer->GetErrorMessage().find("'PixelArea' is -1 at pixel (5, 2)"), std::string::npos)
    << observer->GetErrorMessage();
}

// NaN/Inf test pixels are counted, reported and kept out of every metric.
TEST(ErrorMetrics, NonFinitePixelsAreCounted)
{
  // The reference may be NaN outside the mask (e.g. background): it is never read there.
  auto reference =
    MakeImage(16, 16, 3, [](int x, int y, int) { return x == 0 && y == 5 ? NaN : 1.0; });
  auto test = MakeImage(16, 16, 3,
    [](int x, int y, int c)
    {
      if (x == 0 && y == 0)
      {
        return NaN; // outside the mask: not compared, not counted
      }
      if ((x == 3 && y == 3) || (x == 7 && y == 9 && c == 1) || (x == 15 && y == 15 && c == 2))
      {
        return NaN;
      }
      return x == 4 && y == 12 && c == 0 ? -Inf : 1.1;
    });
  AddArray(reference, "ReceiverMask", 1, [](int x, int, int) { return x > 0 ? 1.0 : 0.0; });
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetMaskArrayName("ReceiverMask");
  vtkNew<vtkTest::ErrorObserver> observer;
  metrics->AddObserver(vtkCommand::WarningEvent, observer);
  ASSERT_TRUE(metrics->Compute(test, reference)) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 4);
  EXPECT_EQ(metrics->GetNumberOfComparedPixels(), 15 * 16 - 4);
  EXPECT_NEAR(metrics->GetRelativeL2Error(), 0.1, 1e-12); // the 1.1 from the other pixels
  EXPECT_NEAR(metrics->GetFluxRatio(), 1.1, 1e-12);
  EXPECT_NE(observer->GetWarningMessage().find("4 masked pixels of the test image have NaN/Inf"),
    std::string::npos)
    << observer->GetWarningMessage();
  EXPECT_NE(observer->GetWarningMessage().find("(first at (3, 3))"), std::string::npos);
  EXPECT_NE(metrics->GetSummary().find("compared=236 nonFinite=4"), std::string::npos)
    << metrics->GetSummary();

  // Nothing finite left to compare: an error, with the count still reported.
  auto broken = MakeImage(16, 16, 3, [](int, int, int) { return NaN; });
  metrics->AddObserver(vtkCommand::ErrorEvent, observer);
  EXPECT_FALSE(metrics->Compute(broken, reference));
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 15 * 16);
  EXPECT_TRUE(std::isnan(metrics->GetRelativeL2Error()));
  EXPECT_STREQ(metrics->GetLastError(), "all 240 masked pixels of the test image are NaN/Inf");
}

// Everything that cannot be compared fails with vtkErrorMacro, the same message in
// GetLastError(), and NaN metrics.
TEST(ErrorMetrics, RejectsBadInput)
{
  vtkNew<vtkCausticsErrorMetrics> metrics;
  vtkNew<vtkTest::ErrorObserver> observer;
  metrics->AddObserver(vtkCommand::ErrorEvent, observer);
  const auto expectFailure =
    [&](vtkImageData* test, vtkImageData* reference, const std::string& expected)
  {
    observer->Clear();
    EXPECT_FALSE(metrics->Compute(test, reference)) << expected;
    const std::string error = metrics->GetLastError();
    EXPECT_NE(error.find(expected), std::string::npos) << error;
    EXPECT_NE(observer->GetErrorMessage().find(error), std::string::npos)
      << observer->GetErrorMessage();
    EXPECT_TRUE(std::isnan(metrics->GetRelativeL2Error()));
    EXPECT_TRUE(std::isnan(metrics->GetPeakPositionError()));
    EXPECT_EQ(metrics->GetSummary(), "error: " + error);
  };
  auto good = MakeImage(32, 32, 3, Caustic);
  expectFailure(nullptr, good, "no test image");
  expectFailure(good, nullptr, "no reference image");
  expectFailure(MakeImage(64, 64, 3, Caustic), good,
    "test image is 64x64x1 pixels but the reference is 32x32x1");
  expectFailure(good, MakeImage(32, 32, 3, Caustic, "Other"),
    "reference image has no point-data array 'CausticIrradiance'");
  expectFailure(MakeImage(32, 32, 3, Caustic, "Other"), good,
    "test image has no point-data array 'CausticIrradiance'");
  expectFailure(MakeImage(32, 32, 1, Caustic), good,
    "'CausticIrradiance' has 1 components in the test image but 3 in the reference");
  auto rgba = MakeImage(32, 32, 4, [](int, int, int) { return 1.0; });
  expectFailure(rgba, rgba, "has 4 components; the metrics compare 1 (scalar) or 3 (RGB)");
  auto wrongCount = MakeImage(32, 32, 3, Caustic);
  wrongCount->GetPointData()->GetArray(Irradiance)->SetNumberOfTuples(100);
  expectFailure(wrongCount, good, "'CausticIrradiance' of the test image has 100 tuples for 1024");
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetDimensions(8, 8, 2);
  AddArray(volume, Irradiance, 1, [](int, int, int) { return 1.0; });
  expectFailure(volume, volume, "the metrics compare non-empty 2D images");
  auto nanReference = MakeImage(32, 32, 3,
    [](int x, int y, int c) { return x == 7 && y == 2 && c == 2 ? NaN : Caustic(x, y, c); });
  expectFailure(good, nanReference, "reference 'CausticIrradiance' is NaN/Inf at pixel (7, 2)");
  auto black = MakeImage(32, 32, 3, [](int, int, int) { return 0.0; });
  expectFailure(good, black, "is zero over all 1024 compared pixels");

  metrics->SetMaskArrayName("ReceiverMask");
  expectFailure(good, good, "mask: reference image has no point-data array 'ReceiverMask'");
  auto masked = MakeImage(32, 32, 3, Caustic);
  AddArray(masked, "ReceiverMask", 1, [](int, int, int) { return 0.0; });
  expectFailure(good, masked, "mask 'ReceiverMask' selects no pixels");
  AddArray(masked, "ReceiverMask", 2, [](int, int, int) { return 1.0; });
  expectFailure(good, masked, "mask array 'ReceiverMask' has 2 components; expected 1");
  AddArray(
    masked, "ReceiverMask", 1, [](int x, int y, int) { return x == 1 && y == 3 ? NaN : 1.0; });
  expectFailure(good, masked, "mask array 'ReceiverMask' is NaN/Inf at pixel (1, 3)");
  metrics->SetMaskArrayName("");
  metrics->SetAreaArrayName("PixelArea");
  expectFailure(good, good, "area: reference image has no point-data array 'PixelArea'");
  metrics->SetAreaArrayName("");
  metrics->SetArrayName("");
  expectFailure(good, good, "no array name set");

  // A good comparison afterwards clears the error.
  metrics->SetArrayName(Irradiance);
  EXPECT_TRUE(metrics->Compute(good, good));
  EXPECT_STREQ(metrics->GetLastError(), "");
}

// Masks from a role or depth array: finite values inside [min, max] are kept.
TEST(ErrorMetrics, AddRangeMask)
{
  const double roles[] = { 0, 1, 2, NaN, 1, 1.5 };
  auto image = MakeImage(
    6, 1, 1, [&](int x, int, int) { return roles[x]; }, "Role");
  ASSERT_TRUE(vtkCausticsErrorMetrics::AddRangeMask(image, "Role", 1.0, 1.0, "ReceiverMask"));
  vtkDataArray* mask = image->GetPointData()->GetArray("ReceiverMask");
  ASSERT_TRUE(mask);
  const double expected[] = { 0, 1, 0, 0, 1, 0 };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_EQ(mask->GetComponent(i, 0), expected[i]) << "pixel " << i;
  }
  // Replacing, not appending: the same name again leaves one array.
  const int arrays = image->GetPointData()->GetNumberOfArrays();
  ASSERT_TRUE(vtkCausticsErrorMetrics::AddRangeMask(image, "Role", 1.0, 2.0, "ReceiverMask"));
  EXPECT_EQ(image->GetPointData()->GetNumberOfArrays(), arrays);
  EXPECT_EQ(image->GetPointData()->GetArray("ReceiverMask")->GetComponent(5, 0), 1.0);

  vtkNew<vtkTest::ErrorObserver> observer;
  image->AddObserver(vtkCommand::ErrorEvent, observer);
  EXPECT_FALSE(vtkCausticsErrorMetrics::AddRangeMask(image, "Depth", 0.0, 1.0, "ReceiverMask"));
  EXPECT_NE(
    observer->GetErrorMessage().find("no 1-component point-data array 'Depth'"), std::string::npos)
    << observer->GetErrorMessage();
  observer->Clear();
  EXPECT_FALSE(vtkCausticsErrorMetrics::AddRangeMask(image, "Role", 2.0, 1.0, "ReceiverMask"));
  EXPECT_NE(observer->GetErrorMessage().find("empty range"), std::string::npos);
  observer->Clear();
  EXPECT_FALSE(vtkCausticsErrorMetrics::AddRangeMask(image, "Role", 0.0, 1.0, ""));
  EXPECT_NE(observer->GetErrorMessage().find("no mask name"), std::string::npos);
}

TEST(ErrorMetrics, PrintSelf)
{
  vtkNew<vtkCausticsErrorMetrics> metrics;
  metrics->SetMaskArrayName("ReceiverMask");
  std::ostringstream os;
  metrics->Print(os);
  EXPECT_NE(os.str().find("ArrayName: CausticIrradiance"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("MaskArrayName: ReceiverMask"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("AreaArrayName: (none)"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("PeakFilterRadius: 1"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("relL2=nan"), std::string::npos) << os.str();
}
