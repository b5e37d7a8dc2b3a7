// The robust order statistics of tracking/median.h.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tracking/median.h"

namespace dimer::tracking {
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

}  // namespace
}  // namespace dimer::tracking
