// The plate's frame of a tilted plate (common/plate_frame.h): a dimer lying on a tilted plate
// lies at height R along the normal with theta 0, whatever x, and the plate's height under it
// is the plate's displacement.
#include "common/plate_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace dimer {
namespace {

constexpr double kR = 4.75e-3, kHalf = 13.8e-3;  // sphere radius, half the centre distance

// A dimer flat on a plate tilted by `deg`, displaced by `zp` along its normal, its centre of
// mass `s` along the plate: the lab trajectory sim writes (x horizontal, z up).
Trajectory OnTiltedPlate(double deg, double zp, const std::vector<double>& along) {
  const double a = deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  const Eigen::Vector2d t(c, s), n(-s, c);
  Trajectory lab;
  for (size_t i = 0; i < along.size(); ++i) {
    const Eigen::Vector2d cm = along[i] * t + (zp + kR) * n;
    const Eigen::Vector2d left = cm - kHalf * t, right = cm + kHalf * t;
    const double plate_z = (zp + cm.x() * s) / c;  // sim/reference_frames.cc PlateSurfaceZ under the CM
    lab.Append(1e-3 * double(i), left, right, plate_z, a);
  }
  return lab;
}

TEST(PlateFrame, ADimerLyingOnATiltedPlateLiesAtRadiusHeightAlongIt) {
  for (double deg : {-8.0, 3.0, 8.0}) {
    const Trajectory p = InPlateFrame(OnTiltedPlate(deg, 2e-4, {-0.05, 0.0, 0.07}), deg);
    const double along[] = {-0.05, 0.0, 0.07};
    for (size_t i = 0; i < p.size(); ++i) {
      EXPECT_NEAR(p.tip_left[i].y(), 2e-4 + kR, 1e-15) << deg;
      EXPECT_NEAR(p.tip_right[i].y(), 2e-4 + kR, 1e-15) << deg;
      EXPECT_NEAR(p.tip_left[i].x(), along[i] - kHalf, 1e-15) << deg;
      EXPECT_NEAR(p.tip_right[i].x(), along[i] + kHalf, 1e-15) << deg;
      EXPECT_NEAR(p.plate_z[i], 2e-4, 1e-15) << deg;  // the same wherever the dimer is
      EXPECT_NEAR(p.theta[i], 0.0, 1e-15) << deg;
      EXPECT_EQ(p.t[i], 1e-3 * double(i));
    }
  }
}

TEST(PlateFrame, ALevelPlateIsLeftAsItIs) {
  const Trajectory lab = OnTiltedPlate(0.0, 1e-4, {0.01, 0.02});
  const Trajectory p = InPlateFrame(lab, 0.0);
  for (size_t i = 0; i < lab.size(); ++i) {
    EXPECT_EQ(p.tip_left[i], lab.tip_left[i]);
    EXPECT_EQ(p.plate_z[i], lab.plate_z[i]);
  }
  const std::array<double, 6> q{0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  EXPECT_EQ(StateInPlateFrame(q, 0.0), q);
}

TEST(PlateFrame, StatesTurnLikeTheTips) {
  // Moving up the plate at 0.02 m/s and spinning: the velocity lies along the plate.
  const double a = 5 * std::numbers::pi / 180;
  const std::array<double, 6> lab{0.1 * std::cos(a), 0.1 * std::sin(a), a + 0.2,
                                  0.02 * std::cos(a), 0.02 * std::sin(a), 3.0};
  const std::array<double, 6> p = StateInPlateFrame(lab, 5.0);
  EXPECT_NEAR(p[0], 0.1, 1e-15);
  EXPECT_NEAR(p[1], 0.0, 1e-15);
  EXPECT_NEAR(p[2], 0.2, 1e-15);
  EXPECT_NEAR(p[3], 0.02, 1e-15);
  EXPECT_NEAR(p[4], 0.0, 1e-15);
  EXPECT_EQ(p[5], 3.0);
}

}  // namespace
}  // namespace dimer
