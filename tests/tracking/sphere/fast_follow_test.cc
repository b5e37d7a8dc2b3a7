#include "tracking/sphere/fast_follow.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "tests/tracking/sphere/sphere_pattern.h"

namespace dimer::tracking {
namespace fast_follow_test {
namespace {

constexpr double kR = testing::kPatternRadius;
// Highlights dimmer than template_locator_test.cc's.
constexpr testing::Highlights kSpots{140, 110};

// The pattern at (cx, cy) seen with `gain` and `offset`, noise `noise`, 8-bit, 160 x 120; a
// bright plate below `plate_row` (NaN: none).
cv::Mat Render(double cx, double cy, double gain, double offset, double noise, uint64_t seed,
               double plate_row = NAN) {
  return testing::RenderPattern(160, 120, cx, cy, gain, offset, noise, seed, plate_row, kSpots);
}

// The appearance rendered exactly, its reference point at the pattern's centre.
Appearance Exact() { return testing::ExactPattern(kSpots); }

TEST(FollowQuickly, RecoversASubPixelShiftWhateverTheGainAndOffset) {
  const Appearance a = Exact();
  const FollowModel m = PrepareFollow(a);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0, ss = 0;
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    const double cx = 80 + u(rng), cy = 60 + u(rng);
    const double gain = 0.5 + 0.55 * u(rng), offset = 10 * u(rng);  // not clipped
    const cv::Mat img = Render(cx, cy, gain, offset, 0.0, i);
    // A prediction 0.45 px off, as at 2000 frames/s after a change of speed.
    const QuickFollow q = FollowQuickly(img, m, a.mask, {cx + 0.35, cy - 0.28}, FollowStop{});
    ASSERT_TRUE(q.ok) << i << ": correlation " << q.correlation;
    EXPECT_NEAR(q.gain, gain, 0.02 * gain);
    EXPECT_GT(q.correlation, 0.999);
    const double e = (q.position - Eigen::Vector2d(cx, cy)).norm();
    worst = std::max(worst, e);
    ss += e * e;
  }
  // Noise free (8-bit quantisation only): ECC's result on this pattern is RMS 0.015 px, worst
  // 0.036 px (template_locator_test.cc); the quick step does better.
  EXPECT_LT(std::sqrt(ss / n), 0.01);
  EXPECT_LT(worst, 0.02);
}

TEST(FollowQuickly, NoiseAndTheFramesMaskDoNotBiasIt) {
  const Appearance a = Exact();
  const FollowModel m = PrepareFollow(a);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  double sx = 0, sy = 0, sxx = 0, syy = 0;
  const int n = 60;
  for (int i = 0; i < n; ++i) {
    const double cx = 80 + u(rng), cy = 60 + u(rng);
    // A bright plate 3 px below the sphere and a bright bar (a rod) leaving it to the right,
    // both cut by the frame's mask (the sums are the mask's, not the appearance's).
    const double plate = cy + kR + 3;
    cv::Mat img = Render(cx, cy, 1.2, 5, 2.0, 100 + i, plate);
    cv::rectangle(img, cv::Point(int(cx + kR - 1), int(cy - 3)), cv::Point(159, int(cy + 3)),
                  cv::Scalar(230), cv::FILLED);
    MaskContext ctx;
    ctx.plate_row = plate;
    ctx.rod_dir = {1, 0};
    const Eigen::Vector2d guess(cx + 0.6, cy + 0.4);
    const QuickFollow q = FollowQuickly(img, m, FrameMask(a, guess, ctx), guess, FollowStop{});
    ASSERT_TRUE(q.ok) << i;
    const double ex = q.position.x() - cx, ey = q.position.y() - cy;
    sx += ex, sy += ey, sxx += ex * ex, syy += ey * ey;
  }
  const double mx = sx / n, my = sy / n;
  EXPECT_LT(std::abs(mx), 0.01);
  EXPECT_LT(std::abs(my), 0.01);
  EXPECT_LT(std::sqrt(sxx / n - mx * mx), 0.02);  // sigma = 2 grey levels, as LocateAppearance
  EXPECT_LT(std::sqrt(syy / n - my * my), 0.02);
}

TEST(FollowQuickly, FailsFromAPredictionSeveralPixelsOffAndWithoutASphere) {
  const Appearance a = Exact();
  const FollowModel m = PrepareFollow(a);
  const cv::Mat img = Render(80.3, 60.7, 1.0, 0.0, 2.0, 1);
  for (const Eigen::Vector2d& off : {Eigen::Vector2d(3.5, 0), Eigen::Vector2d(0, -4),
                                    Eigen::Vector2d(2.5, 2.5), Eigen::Vector2d(-6, 3)}) {
    const QuickFollow q = FollowQuickly(img, m, a.mask, Eigen::Vector2d(80.3, 60.7) + off, {});
    EXPECT_FALSE(q.ok) << off.transpose() << ": at " << q.position.transpose()
                       << ", correlation " << q.correlation;
  }
  // Noise only, and a frame without the sphere but for the plate's bright rows.
  cv::Mat noise(120, 160, CV_8U);
  cv::randn(noise, 40, 2);
  EXPECT_FALSE(FollowQuickly(noise, m, a.mask, {80, 60}, {}).ok);
  const cv::Mat plate_only = Render(80, -100, 1.0, 0.0, 2.0, 3, 70.0);
  EXPECT_FALSE(FollowQuickly(plate_only, m, a.mask, {80, 60}, {}).ok);
  // Too near the frame's edge for its patch: left to ECC.
  EXPECT_FALSE(FollowQuickly(Render(25, 60, 1, 0, 2, 4), m, a.mask, {25, 60}, {}).ok);
}

TEST(FollowAppearance, WhereTheQuickStepFailsItIsEccsResult) {
  const Appearance a = Exact();
  const FollowModel m = PrepareFollow(a);
  const cv::Mat img = Render(80.3, 60.7, 1.0, 0.0, 2.0, 1);
  const EccStop ecc{50, 1e-5};
  // 1.2 px off: beyond what the quick step accepts (kFollowMaxMovePx), which ECC tries alone.
  for (const Eigen::Vector2d& guess : {Eigen::Vector2d(81.5, 60.7), Eigen::Vector2d(84, 63)}) {
    ASSERT_FALSE(FollowQuickly(img, m, a.mask, guess, {}).ok);
    const Located f = FollowAppearance(img, a, m, guess, {}, {}, ecc);
    const Located e = LocateAppearance(img, a, guess, 0, {}, ecc);
    EXPECT_EQ(f.ok, e.ok);
    EXPECT_EQ(f.position, e.position);
    EXPECT_EQ(f.score, e.score);
  }
  // Where it succeeds, its answer, reported like ECC's, and near ECC's.
  const Eigen::Vector2d guess(80.6, 60.5);
  const QuickFollow q = FollowQuickly(img, m, a.mask, guess, {});
  ASSERT_TRUE(q.ok);
  const Located f = FollowAppearance(img, a, m, guess, {}, {}, ecc);
  EXPECT_TRUE(f.ok);
  EXPECT_EQ(f.position, q.position);
  EXPECT_EQ(f.refined, q.correlation);
  EXPECT_LT((f.position - LocateAppearance(img, a, guess, 0, {}, ecc).position).norm(), 0.03);
  // Without a quick step (max_iterations 0): ECC's answer.
  const Located off = FollowAppearance(img, a, m, guess, {}, FollowStop{0, 8, 0.8}, ecc);
  EXPECT_EQ(off.position, LocateAppearance(img, a, guess, 0, {}, ecc).position);
}

}  // namespace
}  // namespace fast_follow_test
}  // namespace dimer::tracking
