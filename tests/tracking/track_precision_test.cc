// What `track` says of how precisely it followed each sphere (tracking/track_precision.h).
#include "tracking/track_precision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace dimer::tracking {
namespace {

// 2000 frames: the left sphere drifting and the right one bouncing (parabolic flights with a
// kink at each landing, as real tracks have), each centre with noise `sd` per axis.
std::vector<FrameTrack> Track(const Eigen::Vector2d& sd_left, const Eigen::Vector2d& sd_right) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n(0, 1);
  std::vector<FrameTrack> frames(2000);
  for (size_t i = 0; i < frames.size(); ++i) {
    FrameTrack& f = frames[i];
    f.index = i;
    const double t = double(i % 80);
    f.found = {true, i % 97 != 0};  // the right sphere lost now and then
    f.centre[0] = Eigen::Vector2d(100 + 0.05 * double(i), 150) +
                  Eigen::Vector2d(sd_left.x() * n(rng), sd_left.y() * n(rng));
    f.centre[1] = Eigen::Vector2d(170 + 0.05 * double(i), 150 - 0.25 * t + 0.003 * t * t) +
                  Eigen::Vector2d(sd_right.x() * n(rng), sd_right.y() * n(rng));
  }
  return frames;
}

TEST(TrackPrecision, TheScatterIsMeasuredOnTheTrackAlone) {
  const auto frames = Track({0.03, 0.05}, {0.2, 0.1});
  const auto p = MeasurePrecision(frames, {Eigen::Vector2d(0.025, 0.04), Eigen::Vector2d(0.03, 0.03)});
  EXPECT_NEAR(p[0].measured.x(), 0.03, 0.004);
  EXPECT_NEAR(p[0].measured.y(), 0.05, 0.006);
  EXPECT_NEAR(p[1].measured.x(), 0.2, 0.025);
  EXPECT_NEAR(p[1].measured.y(), 0.1, 0.012);
  EXPECT_EQ(p[0].bound, Eigen::Vector2d(0.025, 0.04));
  // The left sphere at its bound: followed. The right one's column 6.7 times its bound and
  // above 0.15 px: not followed.
  EXPECT_TRUE(p[0].followed);
  EXPECT_FALSE(p[1].followed);
  EXPECT_FALSE(p[0].poor);
  EXPECT_FALSE(p[1].poor);
}

// A still plate with the dimer set down in a new pose in every frame (one sphere resting, the
// other lifted up to 3 degrees, the dimer moved along the plate): the centres jump by pixels
// from frame to frame, the length stays what it is. That is the motion, not a tracker failing;
// with the same jumps and each centre's own 0.3 px error, it is the tracker.
TEST(TrackPrecision, SeparatePosesAreMotionNotScatter) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n(0, 1);
  const double length = 138.7;
  for (double own_sd : {0.02, 0.3}) {
    std::vector<FrameTrack> frames(30);
    for (size_t i = 0; i < frames.size(); ++i) {
      FrameTrack& f = frames[i];
      f.index = i;
      f.found = {true, true};
      const double tilt = 0.05 * u(rng);
      f.centre[0] = Eigen::Vector2d(100 + 60 * u(rng), 150);
      f.centre[1] = f.centre[0] + length * Eigen::Vector2d(std::cos(tilt), -std::sin(tilt));
      for (int k = 0; k < 2; ++k) f.centre[k] += own_sd * Eigen::Vector2d(n(rng), n(rng));
    }
    const auto p = MeasurePrecision(frames, {Eigen::Vector2d(0.02, 0.02), Eigen::Vector2d(0.02, 0.02)});
    for (int k = 0; k < 2; ++k) {
      SCOPED_TRACE(::testing::Message() << "own error " << own_sd << " sphere " << k);
      EXPECT_GT(p[k].measured.x(), 5.0);  // the poses' jumps
      EXPECT_EQ(p[k].followed, own_sd < 0.1);
      EXPECT_EQ(p[k].uneven_motion, own_sd < 0.1);
    }
  }
}

TEST(TrackPrecision, PoorFootageIsTheBoundsOwnVerdict) {
  const auto frames = Track({0.25, 0.25}, {0.02, 0.02});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto p = MeasurePrecision(frames, {Eigen::Vector2d(0.2, 0.1), Eigen::Vector2d(nan, nan)});
  // At its bound, but the bound above 0.15 px: followed, on poor footage.
  EXPECT_TRUE(p[0].followed);
  EXPECT_TRUE(p[0].poor);
  // No bound (not the template method) and the centres within 0.15 px: followed.
  EXPECT_TRUE(p[1].followed);
  EXPECT_FALSE(p[1].poor);
  // Ten times the bound but within the method's own hundredths of a pixel: followed.
  const auto q = MeasurePrecision(Track({0.02, 0.02}, {0.02, 0.02}),
                                  {Eigen::Vector2d(0.002, 0.002), Eigen::Vector2d(0.002, 0.002)});
  EXPECT_TRUE(q[0].followed);
  EXPECT_TRUE(q[1].followed);
  // Too few consecutive found frames: NaN, and no verdict.
  std::vector<FrameTrack> two(frames.begin(), frames.begin() + 2);
  const auto r = MeasurePrecision(two, {Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(0.2, 0.2)});
  EXPECT_TRUE(std::isnan(r[0].measured.x()));
  EXPECT_TRUE(r[0].followed);
}

// The silhouette methods state no bound; the rigid dimer still decides. POV-Ray ruler frames
// 20-40 with the centroid: centres 9-15 px off, scattering 0.84 / 0.18 px from frame to frame,
// the dimer's length 0.86 px. The same scatter with the length holding is the motion.
TEST(TrackPrecision, WithoutABoundTheLengthDecides) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector2d none(nan, nan);
  const auto p = MeasurePrecision(Track({0.8, 0.2}, {0.3, 0.1}), {none, none});
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(k);
    EXPECT_GT(p[k].length_measured, 0.15);
    EXPECT_FALSE(p[k].followed);
    EXPECT_FALSE(p[k].uneven_motion);
  }
  std::vector<FrameTrack> poses = Track({0, 0}, {0, 0});
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0, 1);
  for (FrameTrack& f : poses) {
    const Eigen::Vector2d jump(0.8 * n(rng), 0.2 * n(rng));
    f.centre[0] += jump;
    f.centre[1] += jump;  // the dimer moved whole: its length holds
  }
  const auto q = MeasurePrecision(poses, {none, none});
  EXPECT_TRUE(q[0].followed);
  EXPECT_TRUE(q[0].uneven_motion);
}

}  // namespace
}  // namespace dimer::tracking
