// vtkCausticsTemporalMetrics on synthetic sequences whose answers are known in closed
// form: a constant sequence (no flicker), relative noise of a known standard deviation
// (that flicker), a step shown k frames late after a cut (lag k), a moving spot shown
// one frame late (its moving error), NaN pixels and input it must refuse.
#include "vtkCausticsTemporalMetrics.h"

#include "vtkDoubleArray.h"
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
#include <vector>

namespace
{
const char* Irradiance = "CausticIrradiance";
const double NaN = std::numeric_limits<double>::quiet_NaN();
const int Size = 32;

using PixelFunction = std::function<double(int x, int y)>;

void AddArray(vtkImageData* image, const char* name, const PixelFunction& f)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(Size * Size);
  for (int y = 0; y < Size; ++y)
  {
    for (int x = 0; x < Size; ++x)
    {
      array->SetValue(y * Size + x, f(x, y));
    }
  }
  image->GetPointData()->AddArray(array);
}

vtkSmartPointer<vtkImageData> MakeImage(const PixelFunction& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Size, Size, 1);
  AddArray(image, Irradiance, f);
  return image;
}

/** A caustic-like spot of peak 2 W/m^2 centred on (cx, cy) over `background`. */
PixelFunction Spot(double cx, double cy, double background = 0.0)
{
  return [=](int x, int y)
  { return background + 2.0 * std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / 8.0); };
}

/** ||a - b|| / ||b|| over every pixel. */
double RelativeL2(const PixelFunction& a, const PixelFunction& b)
{
  double error = 0.0, norm = 0.0;
  for (int y = 0; y < Size; ++y)
  {
    for (int x = 0; x < Size; ++x)
    {
      error += (a(x, y) - b(x, y)) * (a(x, y) - b(x, y));
      norm += b(x, y) * b(x, y);
    }
  }
  return std::sqrt(error / norm);
}

/**
 * frames x pixels of deterministic values with, per pixel, mean exactly 0 and sample
 * standard deviation exactly 1 (up to rounding).
 */
std::vector<std::vector<double>> StandardizedNoise(int frames)
{
  std::vector<std::vector<double>> z(frames, std::vector<double>(Size * Size));
  for (int p = 0; p < Size * Size; ++p)
  {
    double mean = 0.0, squares = 0.0;
    for (int k = 0; k < frames; ++k)
    {
      z[k][p] = std::sin(2.1 * k + 0.37 * p) + 0.5 * std::cos(1.3 * k * (p % 7 + 1));
      mean += z[k][p] / frames;
    }
    for (int k = 0; k < frames; ++k)
    {
      squares += (z[k][p] - mean) * (z[k][p] - mean);
    }
    const double deviation = std::sqrt(squares / (frames - 1));
    for (int k = 0; k < frames; ++k)
    {
      z[k][p] = (z[k][p] - mean) / deviation;
    }
  }
  return z;
}
}

// Nothing moves and the technique shows the same image every frame: zero flicker,
// nothing moving, and its one error in every frame.
TEST(TemporalMetrics, ConstantSequenceHasNoFlicker)
{
  vtkNew<vtkCausticsTemporalMetrics> metrics;
  auto reference = MakeImage(Spot(12, 20, 0.1));
  auto test = MakeImage([](int x, int y) { return 1.1 * Spot(12, 20, 0.1)(x, y); });
  for (int k = 0; k < 8; ++k)
  {
    ASSERT_TRUE(metrics->AddFrame(test, reference)) << metrics->GetLastError();
  }
  ASSERT_TRUE(metrics->Compute()) << metrics->GetLastError();
  std::cout << metrics->GetSummary() << "\n";
  EXPECT_EQ(metrics->GetFlicker(), 0.0);
  EXPECT_TRUE(std::isnan(metrics->GetMovingError()));
  EXPECT_EQ(metrics->GetNumberOfStaticValues(), Size * Size);
  EXPECT_EQ(metrics->GetNumberOfMovingValues(), 0);
  EXPECT_NEAR(metrics->GetMeanRelativeL2Error(), 0.1, 1e-12);
  EXPECT_NEAR(metrics->GetMeanFluxRatio(), 1.1, 1e-12);
  EXPECT_EQ(metrics->GetLag(), -1); // no cut
  EXPECT_TRUE(std::isnan(metrics->GetGhosting()));
}

// t_k = r (1 + sigma z_k) with z of mean 0 and standard deviation 1 at every pixel:
// each pixel's temporal relative standard deviation is sigma, so the flux-weighted
// flicker is sigma whatever the weights; with sigma 0.02 on the left half and 0.08
// on the right it is their mean weighted by area x reference.
TEST(TemporalMetrics, RelativeNoiseGivesItsFlicker)
{
  const int frames = 12;
  const auto z = StandardizedNoise(frames);
  const PixelFunction truth = Spot(20, 10, 0.05);
  const PixelFunction area = [](int x, int y) { return 1e-4 * (1.0 + 0.1 * x + 0.03 * y); };
  const PixelFunction sigma = [](int x, int) { return x < Size / 2 ? 0.02 : 0.08; };
  for (bool uniform : { true, false })
  {
    vtkNew<vtkCausticsTemporalMetrics> metrics;
    metrics->SetAreaArrayName("PixelArea");
    for (int k = 0; k < frames; ++k)
    {
      auto reference = MakeImage(truth);
      AddArray(reference, "PixelArea", area);
      auto test = MakeImage([&](int x, int y)
        { return truth(x, y) * (1.0 + (uniform ? 0.05 : sigma(x, y)) * z[k][y * Size + x]); });
      ASSERT_TRUE(metrics->AddFrame(test, reference)) << metrics->GetLastError();
    }
    ASSERT_TRUE(metrics->Compute()) << metrics->GetLastError();
    double expected = 0.05;
    if (!uniform)
    {
      double weighted = 0.0, weight = 0.0;
      for (int y = 0; y < Size; ++y)
      {
        for (int x = 0; x < Size; ++x)
        {
          weighted += area(x, y) * truth(x, y) * sigma(x, y);
          weight += area(x, y) * truth(x, y);
        }
      }
      expected = weighted / weight;
    }
    std::cout << metrics->GetSummary() << "\n";
    // 1e-12: rounding of the standardization and the sums (about 1e-15 per value).
    EXPECT_NEAR(metrics->GetFlicker(), expected, 1e-12);
    EXPECT_EQ(metrics->GetNumberOfMovingValues(), 0);
  }
}

// The reference jumps from spot A to spot B at the cut; the technique (10 % too bright
// throughout) shows A for k more frames. The per-frame error is 0.1 except in those k
// frames, so the lag is k and the ghosting is ||1.1 A - B|| / ||B|| / 0.1; both
// segments are still, and the technique is constant in its settled frames: no flicker.
TEST(TemporalMetrics, DelayedStepGivesLag)
{
  // Steady error: the median of frames 14..19, after every delay tried.
  const int frames = 20, cut = 8;
  const PixelFunction a = Spot(8, 8), b = Spot(22, 20);
  const PixelFunction brighterA = [&](int x, int y) { return 1.1 * a(x, y); };
  const PixelFunction brighterB = [&](int x, int y) { return 1.1 * b(x, y); };
  const double ghost = RelativeL2(brighterA, b);
  for (int delay : { 0, 1, 3, 6 })
  {
    vtkNew<vtkCausticsTemporalMetrics> metrics;
    metrics->SetCutFrame(cut);
    for (int k = 0; k < frames; ++k)
    {
      auto reference = MakeImage(k < cut ? a : b);
      auto test = MakeImage(k < cut + delay ? brighterA : brighterB);
      ASSERT_TRUE(metrics->AddFrame(test, reference)) << metrics->GetLastError();
    }
    ASSERT_TRUE(metrics->Compute()) << metrics->GetLastError();
    std::cout << "delay " << delay << ": " << metrics->GetSummary() << "\n";
    EXPECT_EQ(metrics->GetLag(), delay);
    EXPECT_NEAR(metrics->GetSteadyError(), 0.1, 1e-12);
    EXPECT_NEAR(metrics->GetGhosting(), delay ? ghost / 0.1 : 1.0, 1e-9);
    EXPECT_NEAR(metrics->GetFrameRelativeL2Error(cut), delay ? ghost : 0.1, 1e-12);
    EXPECT_EQ(metrics->GetFlicker(), 0.0);
    EXPECT_EQ(metrics->GetNumberOfStaticValues(), 2 * Size * Size);
  }
}

// A spot moving 2 pixels a frame: every pixel's reference varies (relatively) by far
// more than the static tolerance, so every pixel is moving. Exact: moving error 0.
// One frame late: sqrt(sum (r_{k-1} - r_k)^2 / sum r_k^2) over every pixel and frame.
// Smeared (the temporal mean every frame, as a denoiser that blurs motion): its own
// closed form, and no flicker credit since nothing is static.
TEST(TemporalMetrics, MovingSpotGivesMovingError)
{
  const int frames = 8;
  auto truth = [](int k) { return Spot(6 + 2.0 * k, 16); };
  auto smeared = [&](int x, int y)
  {
    double sum = 0.0;
    for (int k = 0; k < frames; ++k)
    {
      sum += truth(k)(x, y) / frames;
    }
    return sum;
  };
  for (int mode : { 0, 1, 2 }) // exact, one frame late, smeared
  {
    vtkNew<vtkCausticsTemporalMetrics> metrics;
    double error = 0.0, norm = 0.0;
    for (int k = 0; k < frames; ++k)
    {
      const PixelFunction shown = mode == 0 ? truth(k)
        : mode == 1                         ? truth(std::max(k - 1, 0))
                                            : smeared;
      ASSERT_TRUE(metrics->AddFrame(MakeImage(shown), MakeImage(truth(k))));
      for (int p = 0; p < Size * Size; ++p)
      {
        const double t = shown(p % Size, p / Size), r = truth(k)(p % Size, p / Size);
        error += (t - r) * (t - r);
        norm += r * r;
      }
    }
    ASSERT_TRUE(metrics->Compute()) << metrics->GetLastError();
    std::cout << "mode " << mode << ": " << metrics->GetSummary() << "\n";
    EXPECT_EQ(metrics->GetNumberOfMovingValues(), Size * Size);
    EXPECT_TRUE(std::isnan(metrics->GetFlicker()));
    EXPECT_NEAR(metrics->GetMovingError(), std::sqrt(error / norm), 1e-12);
    if (mode > 0)
    {
      EXPECT_GT(metrics->GetMovingError(), 0.1);
    }
  }
}

// A still spot on the left, a spot moving 1 pixel a frame on the right, the
// technique off by relative noise sigma = 0.03 everywhere: the flicker is that of the
// still pixels only (about sigma: their reference may still vary by up to 1 %), and the
// moving error is the noise's relative L2 over the pixels whose reference changes by
// more than 1 %. Both are computed here independently from the class description.
TEST(TemporalMetrics, StillAndMovingPixelsAreSeparated)
{
  const int frames = 10;
  const double sigma = 0.03;
  const auto z = StandardizedNoise(frames);
  auto truth = [](int k)
  { return [k](int x, int y) { return Spot(8, 16)(x, y) + Spot(20 + k, 16)(x, y); }; };
  vtkNew<vtkCausticsTemporalMetrics> metrics;
  for (int k = 0; k < frames; ++k)
  {
    auto test =
      MakeImage([&](int x, int y) { return truth(k)(x, y) * (1.0 + sigma * z[k][y * Size + x]); });
    ASSERT_TRUE(metrics->AddFrame(test, MakeImage(truth(k))));
  }
  ASSERT_TRUE(metrics->Compute()) << metrics->GetLastError();
  std::cout << metrics->GetSummary() << "\n";
  double error = 0.0, norm = 0.0, weighted = 0.0, weight = 0.0;
  vtkIdType moving = 0;
  for (int p = 0; p < Size * Size; ++p)
  {
    const int x = p % Size, y = p / Size;
    double mean = 0.0, squares = 0.0;
    for (int k = 0; k < frames; ++k)
    {
      mean += truth(k)(x, y) / frames;
    }
    for (int k = 0; k < frames; ++k)
    {
      squares += (truth(k)(x, y) - mean) * (truth(k)(x, y) - mean) / frames;
    }
    if (std::sqrt(squares) <= 0.01 * mean)
    {
      double m = 0.0, deviation = 0.0;
      for (int k = 0; k < frames; ++k)
      {
        m += truth(k)(x, y) * (1.0 + sigma * z[k][p]) / frames;
      }
      for (int k = 0; k < frames; ++k)
      {
        deviation += std::pow(truth(k)(x, y) * (1.0 + sigma * z[k][p]) - m, 2) / (frames - 1);
      }
      weighted += mean * std::sqrt(deviation) / m;
      weight += mean;
    }
    else
    {
      ++moving;
      for (int k = 0; k < frames; ++k)
      {
        error += std::pow(sigma * z[k][p] * truth(k)(x, y), 2);
        norm += std::pow(truth(k)(x, y), 2);
      }
    }
  }
  EXPECT_EQ(metrics->GetNumberOfMovingValues(), moving);
  EXPECT_EQ(metrics->GetNumberOfStaticValues(), Size * Size - moving);
  EXPECT_GT(moving, 100);
  EXPECT_GT(Size * Size - moving, 100);
  EXPECT_NEAR(metrics->GetFlicker(), weighted / weight, 1e-12);
  EXPECT_NEAR(metrics->GetFlicker(), sigma, 1e-4);
  EXPECT_NEAR(metrics->GetMovingError(), std::sqrt(error / norm), 1e-12);
}

// A receiver pixel that is NaN in one frame is counted, reported once, and left out;
// masked-out pixels are neither compared nor counted.
TEST(TemporalMetrics, NonFinitePixelsAreLeftOut)
{
  vtkNew<vtkCausticsTemporalMetrics> metrics;
  metrics->SetMaskArrayName("ReceiverMask");
  vtkNew<vtkTest::ErrorObserver> observer;
  metrics->AddObserver(vtkCommand::WarningEvent, observer);
  for (int k = 0; k < 4; ++k)
  {
    auto reference = MakeImage(Spot(16, 16, 0.1));
    AddArray(reference, "ReceiverMask", [](int x, int) { return x > 0 ? 1.0 : 0.0; });
    auto test = MakeImage([k](int x, int y)
      { return (k == 2 && x == 5 && y == 5) || x == 0 ? NaN : Spot(16, 16, 0.1)(x, y); });
    ASSERT_TRUE(metrics->AddFrame(test, reference)) << metrics->GetLastError();
  }
  ASSERT_TRUE(metrics->Compute()) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetNumberOfNonFinitePixels(), 1);
  EXPECT_EQ(metrics->GetNumberOfStaticValues(), (Size - 1) * Size - 1);
  EXPECT_EQ(metrics->GetFlicker(), 0.0);
  EXPECT_NE(observer->GetWarningMessage().find("1 receiver pixels have NaN/Inf"), std::string::npos)
    << observer->GetWarningMessage();
}

// Input that cannot be measured fails with one error naming it, and NaN results.
TEST(TemporalMetrics, RejectsBadInput)
{
  vtkNew<vtkCausticsTemporalMetrics> metrics;
  vtkNew<vtkTest::ErrorObserver> observer;
  metrics->AddObserver(vtkCommand::ErrorEvent, observer);
  auto image = MakeImage(Spot(16, 16));
  EXPECT_FALSE(metrics->Compute());
  EXPECT_STREQ(metrics->GetLastError(), "temporal metrics need at least 2 frames, got 0");

  ASSERT_TRUE(metrics->AddFrame(image, image));
  auto small = vtkSmartPointer<vtkImageData>::New();
  small->SetDimensions(8, 8, 1);
  EXPECT_FALSE(metrics->AddFrame(small, small));
  EXPECT_NE(std::string(metrics->GetLastError()).find("frame 1: "), std::string::npos)
    << metrics->GetLastError();
  EXPECT_EQ(metrics->GetNumberOfFrames(), 1);
  auto wide = vtkSmartPointer<vtkImageData>::New();
  wide->SetDimensions(Size, 16, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetName(Irradiance);
  values->SetNumberOfTuples(Size * 16);
  values->Fill(1.0);
  wide->GetPointData()->AddArray(values);
  EXPECT_FALSE(metrics->AddFrame(wide, wide));
  EXPECT_NE(
    std::string(metrics->GetLastError()).find("the first frame is 32x32"), std::string::npos)
    << metrics->GetLastError();
  EXPECT_EQ(metrics->GetNumberOfFrames(), 1);

  ASSERT_TRUE(metrics->AddFrame(image, image));
  metrics->SetCutFrame(2);
  EXPECT_FALSE(metrics->Compute());
  EXPECT_STREQ(metrics->GetLastError(), "cut frame 2 is outside [1, 1] (-1: no cut)");
  EXPECT_TRUE(std::isnan(metrics->GetFlicker()));
  EXPECT_EQ(metrics->GetLag(), -1);
  metrics->SetCutFrame(1);
  EXPECT_TRUE(metrics->Compute()) << metrics->GetLastError();
  EXPECT_EQ(metrics->GetLag(), 0);
  EXPECT_EQ(metrics->GetGhosting(), 1.0);
  metrics->Reset();
  EXPECT_EQ(metrics->GetNumberOfFrames(), 0);
}
