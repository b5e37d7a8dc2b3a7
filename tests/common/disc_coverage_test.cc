#include "common/disc_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace dimer {
namespace {

// Brute-force coverage by an n x n grid of point samples: error ~ perimeter / n^2 per pixel.
double SampledArea(double col, double row, const Eigen::Vector2d& c, double r, int n) {
  int inside = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = col - 0.5 + (i + 0.5) / n - c.x(), y = row - 0.5 + (j + 0.5) / n - c.y();
      inside += x * x + y * y <= r * r;
    }
  }
  return double(inside) / (n * n);
}

TEST(DiscCoverage, AreasSumToTheDiscAreaExactly) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> frac(0.0, 1.0);
  for (double r : {0.3, 2.7, 23.75}) {
    const Eigen::Vector2d c(40 + frac(rng), 40 + frac(rng));
    double sum = 0;
    for (int row = 0; row < 80; ++row) {
      for (int col = 0; col < 80; ++col) sum += DiscPixelArea(col, row, c, r);
    }
    EXPECT_NEAR(sum, std::numbers::pi * r * r, 1e-9 * r * r) << "radius " << r;
  }
}

TEST(DiscCoverage, MatchesDenseSamplingOnEdgePixels) {
  const Eigen::Vector2d c(10.37, 7.81);
  const double r = 5.3;
  for (int row = 0; row < 16; ++row) {
    for (int col = 0; col < 18; ++col) {
      // 2000^2 samples: sampling error below ~1e-5 for a pixel crossed by the edge.
      if (std::abs(std::hypot(col - c.x(), row - c.y()) - r) > 1.0) continue;
      EXPECT_NEAR(DiscPixelArea(col, row, c, r), SampledArea(col, row, c, r, 2000), 2e-5)
          << col << "," << row;
    }
  }
}

TEST(DiscCoverage, DerivativesMatchFiniteDifferences) {
  const Eigen::Vector2d c(10.37, 7.81);
  const double r = 5.3, h = 1e-6;
  for (int row = 2; row < 14; ++row) {
    for (int col = 4; col < 17; ++col) {
      const PixelCoverage p = DiscPixelCoverage(col, row, c, r);
      EXPECT_NEAR(p.area, DiscPixelArea(col, row, c, r), 1e-15);
      auto area = [&](double dx, double dy, double dr) {
        return DiscPixelArea(col, row, c + Eigen::Vector2d(dx, dy), r + dr);
      };
      EXPECT_NEAR(p.d_cx, (area(h, 0, 0) - area(-h, 0, 0)) / (2 * h), 1e-6);
      EXPECT_NEAR(p.d_cy, (area(0, h, 0) - area(0, -h, 0)) / (2 * h), 1e-6);
      EXPECT_NEAR(p.d_r, (area(0, 0, h) - area(0, 0, -h)) / (2 * h), 1e-6);
    }
  }
}

TEST(DiscCoverage, NonSquareOffsetsAreNotSwapped) {
  // A disc right of the pixel covers it only through its x extent: an x/y swap would fail.
  const Eigen::Vector2d c(3.0, 0.0);
  EXPECT_GT(DiscPixelArea(0, 0, c, 2.6), 0.0);
  EXPECT_EQ(DiscPixelArea(0, 3, c, 2.6), 0.0);
}

}  // namespace
}  // namespace dimer
