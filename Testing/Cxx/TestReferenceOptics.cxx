// The optics the reference is built from, each checked against an independent form:
// Fresnel against Fresnel's sine/tangent laws and Born & Wolf's real-valued conductor
// formula, Snell's law, the phase function's normalization and mean cosine, the
// kernels' normalization, and the equal-area sampling map.
#include "TestReferenceUtilities.h"

#include "vtkCausticsReferenceCore.h"

#include <gtest/gtest.h>

#include <cmath>

using reftest::Pi;

TEST(ReferenceOptics, DielectricFresnelMatchesFresnelLaws)
{
  for (double n : { 1.33, 1.5, 2.4 })
  {
    for (int step = 0; step <= 89; ++step)
    {
      const double theta = step * Pi / 180.0;
      // Both directions of the interface; the laws are exact closed forms, so only
      // double rounding separates them (1e-12).
      EXPECT_NEAR(caustics::FresnelDielectric(std::cos(theta), 1.0, n),
        reftest::FresnelLaws(theta, 1.0, n), 1e-12)
        << "n " << n << " theta " << step;
      EXPECT_NEAR(caustics::FresnelDielectric(std::cos(theta), n, 1.0),
        reftest::FresnelLaws(theta, n, 1.0), 1e-12)
        << "inside, n " << n << " theta " << step;
    }
    // Normal incidence and Brewster's angle (p-polarized part vanishes).
    EXPECT_NEAR(caustics::FresnelDielectric(1.0, 1.0, n), std::pow((n - 1) / (n + 1), 2), 1e-15);
    const double brewster = std::atan(n), refracted = std::asin(std::sin(brewster) / n);
    const double s = std::sin(brewster - refracted) / std::sin(brewster + refracted);
    EXPECT_NEAR(caustics::FresnelDielectric(std::cos(brewster), 1.0, n), 0.5 * s * s, 1e-12);
    // Total internal reflection beyond the critical angle, and grazing incidence.
    const double critical = std::asin(1.0 / n);
    EXPECT_EQ(caustics::FresnelDielectric(std::cos(critical + 1e-6), n, 1.0), 1.0);
    EXPECT_LT(caustics::FresnelDielectric(std::cos(critical - 1e-3), n, 1.0), 1.0);
    EXPECT_NEAR(caustics::FresnelDielectric(0.0, 1.0, n), 1.0, 1e-12);
  }
  // A vanishing interface reflects nothing.
  EXPECT_EQ(caustics::FresnelDielectric(0.3, 1.0, 1.0), 0.0);
}

TEST(ReferenceOptics, ConductorFresnelMatchesBornAndWolf)
{
  // Silver, gold (RGB values used by the module), and a dielectric (k = 0).
  const double materials[][2] = { { 0.155, 4.83 }, { 0.117, 3.12 }, { 0.138, 2.15 },
    { 0.143, 3.98 }, { 0.374, 2.38 }, { 1.44, 1.60 }, { 1.5, 0.0 } };
  for (const auto& m : materials)
  {
    for (int step = 0; step <= 89; ++step)
    {
      const double theta = step * Pi / 180.0;
      EXPECT_NEAR(caustics::FresnelConductor(std::cos(theta), m[0], m[1]),
        reftest::ConductorLaws(theta, m[0], m[1]), 1e-10)
        << "n " << m[0] << " k " << m[1] << " theta " << step;
    }
    const double normal =
      ((m[0] - 1) * (m[0] - 1) + m[1] * m[1]) / ((m[0] + 1) * (m[0] + 1) + m[1] * m[1]);
    EXPECT_NEAR(caustics::FresnelConductor(1.0, m[0], m[1]), normal, 1e-14);
    EXPECT_NEAR(caustics::FresnelConductor(0.0, m[0], m[1]), 1.0, 1e-12);
  }
  // With k = 0 a conductor is a dielectric seen from outside.
  EXPECT_NEAR(
    caustics::FresnelConductor(0.6, 1.5, 0.0), caustics::FresnelDielectric(0.6, 1.0, 1.5), 1e-14);
}

TEST(ReferenceOptics, RefractionObeysSnell)
{
  const caustics::Vec3 n{ { 0, 1, 0 } };
  for (double eta : { 1.0 / 1.5, 1.5, 1.0 })
  {
    for (int step = 0; step < 90; step += 7)
    {
      const double theta = step * Pi / 180.0;
      const caustics::Vec3 d{ { std::sin(theta) * 0.6, -std::cos(theta), std::sin(theta) * 0.8 } };
      caustics::Vec3 t;
      const bool refracted = caustics::Refract(d, n, eta, t);
      if (eta * std::sin(theta) >= 1.0)
      {
        EXPECT_FALSE(refracted) << "total internal reflection at " << step;
        continue;
      }
      ASSERT_TRUE(refracted);
      const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      EXPECT_NEAR(length, 1.0, 1e-14);
      const double sinT = std::sqrt(t[0] * t[0] + t[2] * t[2]);
      EXPECT_NEAR(sinT, eta * std::sin(theta), 1e-14) << "Snell at " << step;
      EXPECT_LT(t[1], 0.0);
      // In the plane of incidence: the tangential part keeps its direction.
      EXPECT_NEAR(t[0] * d[2] - t[2] * d[0], 0.0, 1e-14);
    }
  }
  const caustics::Vec3 d{ { 0.6, -0.8, 0 } };
  const caustics::Vec3 r = caustics::Reflect(d, n);
  EXPECT_DOUBLE_EQ(r[0], 0.6);
  EXPECT_DOUBLE_EQ(r[1], 0.8);
}

TEST(ReferenceOptics, HenyeyGreensteinIsNormalizedWithMeanCosineG)
{
  for (double g : { -0.7, 0.0, 0.3, 0.7, 0.9 })
  {
    // Midpoint rule in cos(theta), 2e5 intervals (h = 1e-5): its error, about
    // 2 pi h^2 / 24 p'(1), is 1.1e-7 for g = 0.9 (p'(1) = 4e3) and < 1e-9 for |g| <= 0.7.
    const int steps = 200000;
    double total = 0.0, mean = 0.0;
    for (int k = 0; k < steps; ++k)
    {
      const double mu = -1.0 + (k + 0.5) * 2.0 / steps;
      const double p = caustics::HenyeyGreenstein(mu, g) * 2.0 * Pi * (2.0 / steps);
      total += p;
      mean += p * mu;
    }
    EXPECT_NEAR(total, 1.0, 2e-7) << "g " << g;
    EXPECT_NEAR(mean, g, 2e-7) << "g " << g;
  }
  EXPECT_NEAR(caustics::HenyeyGreenstein(0.3, 0.0), 1.0 / (4.0 * Pi), 1e-15);
}

TEST(ReferenceOptics, KernelsAreNormalizedMarginals)
{
  const double r = 0.37;
  // 2D kernel over the plane (polar midpoint rule; the kernel is a polynomial in d^2).
  const int steps = 20000;
  double total2 = 0.0;
  for (int k = 0; k < steps; ++k)
  {
    const double d = (k + 0.5) * r / steps;
    total2 += caustics::EpanechnikovKernel2D(d * d, r) * 2.0 * Pi * d * (r / steps);
  }
  EXPECT_NEAR(total2, 1.0, 1e-8);
  // 1D kernel: integral 1, and the 2D kernel integrated along a line at distance d.
  double total1 = 0.0;
  for (int k = 0; k < steps; ++k)
  {
    const double d = -r + (k + 0.5) * 2.0 * r / steps;
    total1 += caustics::EpanechnikovKernel1D(d, r) * 2.0 * r / steps;
  }
  EXPECT_NEAR(total1, 1.0, 1e-7);
  for (double d : { 0.0, 0.1, 0.3 })
  {
    double line = 0.0;
    for (int k = 0; k < steps; ++k)
    {
      const double w = -r + (k + 0.5) * 2.0 * r / steps;
      line += caustics::EpanechnikovKernel2D(d * d + w * w, r) * 2.0 * r / steps;
    }
    EXPECT_NEAR(caustics::EpanechnikovKernel1D(d, r), line, 1e-6 * line + 1e-12) << d;
  }
  EXPECT_EQ(caustics::EpanechnikovKernel2D(r * r, r), 0.0);
  EXPECT_EQ(caustics::EpanechnikovKernel1D(r, r), 0.0);
}

TEST(ReferenceOptics, ConcentricMapPreservesArea)
{
  // The image of a small square has area pi x its area everywhere (Jacobian pi),
  // and the map stays inside the unit disk. Samples avoid the diagonals, where the
  // map's two wedges meet with a kink (finite differences straddling it mislead).
  const double h = 1e-6;
  for (double u = 0.05; u < 1.0; u += 0.1)
  {
    for (double v = 0.08; v < 1.0; v += 0.1)
    {
      double x0, y0, x1, y1, x2, y2;
      caustics::ConcentricSquareToDisk(u, v, x0, y0);
      caustics::ConcentricSquareToDisk(u + h, v, x1, y1);
      caustics::ConcentricSquareToDisk(u, v + h, x2, y2);
      const double jacobian = std::abs((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)) / (h * h);
      EXPECT_NEAR(jacobian, Pi, 1e-3) << u << " " << v; // finite differences: O(h / radius)
      EXPECT_LE(x0 * x0 + y0 * y0, 1.0 + 1e-15);
    }
  }
  double x, y;
  caustics::ConcentricSquareToDisk(1.0, 0.5, x, y);
  EXPECT_NEAR(x, 1.0, 1e-15);
  EXPECT_NEAR(y, 0.0, 1e-15);
}
