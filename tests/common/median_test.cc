// The robust order statistics of common/median.h.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "common/median.h"

namespace dimer {
namespace {

TEST(Median, UpperMiddleAndEmpty) {
  EXPECT_EQ(MedianOf({3, 1, 2}), 2);
  EXPECT_EQ(MedianOf({4, 1, 3, 2}), 3);
  EXPECT_TRUE(std::isnan(MedianOf({})));
}

// The re-centring's row shift (appearance_model.cc): a resting sphere's (plate - R - row) values
// cluster a few tenths of a pixel wide; one failed registration lies far below them.
TEST(LowestSupported, PassesOverALoneLowOutlier) {
  const std::vector<double> resting{-5.90, -5.69, -5.71, -22.79, -5.61, 117.7, -5.75, 8.05};
  EXPECT_EQ(LowestSupported(resting, 1.0, 3), -5.90);
  // Two outliers close together are a cluster of two: passed over when three are asked for.
  const std::vector<double> pair{-22.8, -22.5, -5.9, -5.8, -5.7};
  EXPECT_EQ(LowestSupported(pair, 1.0, 3), -5.9);
  EXPECT_EQ(LowestSupported(pair, 1.0, 2), -22.8);
}

TEST(LowestSupported, CleanDataGiveTheMinimum) {
  const std::vector<double> v{-9.7, -10.01, -9.6, -9.9, -2.0, 7.5};
  EXPECT_EQ(LowestSupported(v, 1.0, 3), -10.01);
}

TEST(LowestSupported, NaNWithoutSupportAndNonFiniteIgnored) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(LowestSupported({-3.0, 0.0, 3.0}, 1.0, 2)));
  EXPECT_TRUE(std::isnan(LowestSupported({}, 1.0, 1)));
  EXPECT_EQ(LowestSupported({nan, 2.0, nan, 2.5, -std::numeric_limits<double>::infinity()}, 1.0, 2),
            2.0);
}

// Noise of about a level, rounded to whole levels: the plain median of |differences| jumps by
// whole levels (0.67 or 1.48 of sigma), the quantised one follows sigma within 10 %.
TEST(QuantisedMedian, FollowsTheNoiseBelowAndAboveOneLevel) {
  std::mt19937 gen(3);
  for (double sigma : {0.6, 0.8, 1.0, 1.3, 2.0, 4.0}) {
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<double> d;
    for (int i = 0; i < 200000; ++i) d.push_back(std::round(noise(gen)));
    // The noise rounded to whole levels carries the rounding's 1/sqrt(12) too.
    const double rounded = std::sqrt(sigma * sigma + 1.0 / 12.0);
    EXPECT_NEAR(1.4826 * QuantisedMedian(d, 1.0), rounded, 0.10 * rounded) << "sigma " << sigma;
    if (sigma == 1.0) {
      // The plain median of |d| is 1 here: 1.48 sigma, what the highlight floor used to read.
      std::vector<double> a;
      for (double x : d) a.push_back(std::abs(x));
      EXPECT_EQ(MedianOf(a), 1.0);
    }
  }
}

// Levels x 257 (8-bit data widened to 16 bits) give the same median x 257, exactly.
TEST(QuantisedMedian, ScalesWithTheLevelStep) {
  const std::vector<double> d{0, 1, -1, 2, 0, -3, 1, 1, 0, -2, 4};
  std::vector<double> wide;
  for (double x : d) wide.push_back(257 * x);
  EXPECT_EQ(QuantisedMedian(wide, 257.0), 257 * QuantisedMedian(d, 1.0));
  // 11 values: |d| = 0 x3, 1 x4, 2 x2, 3, 4; half (5.5) is passed in the bin of 1, [0.5, 1.5],
  // 2.5 of its 4 counts in.
  EXPECT_DOUBLE_EQ(QuantisedMedian(d, 1.0), 0.5 + 2.5 / 4.0);
  EXPECT_TRUE(std::isnan(QuantisedMedian({}, 1.0)));
}

}  // namespace
}  // namespace dimer
