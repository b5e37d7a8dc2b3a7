// The scale from the dimer's length (tracking/dimer_length_scale.h): the median centre distance,
// the radius and scale it implies, and the passes that settle the radius the film is tracked
// with. The POV-Ray films calibrated this way are in povray_footage_test.cc.
#include "tracking/dimer_length_scale.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace dimer::tracking {
namespace {

FrameTrack Pair(double left_col, double right_col, double right_row, bool both = true) {
  FrameTrack f;
  f.found = {true, both};
  f.centre = {Eigen::Vector2d(left_col, 200), Eigen::Vector2d(right_col, right_row)};
  return f;
}

TEST(MedianDimerLength, IsTheMedianDistanceOverFramesShowingBothSpheres) {
  std::vector<FrameTrack> frames;
  // Twelve frames with the right sphere lifted by 3-4-5 triangles' worth: distances 5 k.
  for (int k = 1; k <= 12; ++k) frames.push_back(Pair(100, 100 + 3.0 * k, 200 - 4.0 * k));
  frames.push_back(Pair(100, 1000, 200, /*both=*/false));  // one sphere only: not a length
  size_t used = 0;
  // The median of 5, 10, ..., 60 (the upper middle, common/median.h): the 7th, 35; the same
  // whatever the frames' order.
  EXPECT_DOUBLE_EQ(MedianDimerLength(frames, &used), 35.0);
  EXPECT_EQ(used, 12u);
  std::reverse(frames.begin(), frames.end());
  EXPECT_DOUBLE_EQ(MedianDimerLength(frames), 35.0);
}

TEST(MedianDimerLength, TooFewFramesGiveNoLength) {
  std::vector<FrameTrack> frames;
  for (size_t k = 0; k + 1 < kLengthScaleMinFrames; ++k) frames.push_back(Pair(100, 238, 200));
  size_t used = 0;
  EXPECT_TRUE(std::isnan(MedianDimerLength(frames, &used)));
  EXPECT_EQ(used, kLengthScaleMinFrames - 1);
  frames.push_back(Pair(100, 238, 200));
  EXPECT_DOUBLE_EQ(MedianDimerLength(frames), 138.0);
}

TEST(DimerLengthScale, RadiusAndScaleFollowTheAspectRatio) {
  // The paper's A_r = 3.9 dimer of 9.5 mm spheres at 0.2 mm/px: centres 27.55 mm = 137.75 px
  // apart, spheres 23.75 px in radius.
  EXPECT_NEAR(RadiusFromDimerLength(137.75, 3.9), 23.75, 1e-12);
  EXPECT_NEAR(ScaleFromDimerLength(137.75, 3.9, 9.5e-3), 2e-4, 1e-16);
  // Touching spheres: the centres one diameter apart.
  EXPECT_NEAR(RadiusFromDimerLength(47.5, 2.0), 23.75, 1e-12);
}

// A tracker whose length depends on the radius it is given, as the template's does (its
// outline fits and template size): the length is right at the true radius, and off by `gain`
// px per px of radius error; with the radius measured (NaN) it returns `measured`.
struct FakeTracker {
  double true_radius = 23.75, ar = 3.9, gain = 0.5, measured = 135.7;
  int calls = 0;
  double operator()(double radius) {
    ++calls;
    const double truth = 2.0 * (ar - 1.0) * true_radius;
    return std::isnan(radius) ? measured : truth + gain * (radius - true_radius);
  }
};

TEST(DimerLengthScale, PassesSettleOnTheRadiusTheLengthImplies) {
  FakeTracker t;
  t.gain = 0.3;
  const LengthScale s = IterateDimerLengthScale(std::ref(t), t.ar);
  ASSERT_TRUE(s.ok) << s.failure;
  EXPECT_TRUE(s.converged);
  // Each pass shrinks the radius error by gain / (2 (A_r - 1)) = 0.052: from -0.35 px to -0.018,
  // then -0.001, within the tolerance (0.02 px) of the pass before.
  EXPECT_NEAR(s.radius_px, t.true_radius, 0.01);
  EXPECT_EQ(s.passes.size(), 3u);
  EXPECT_TRUE(std::isnan(s.passes[0].radius_px_used)) << "the first pass measures the radius";
  EXPECT_NEAR(s.passes[1].radius_px_used, RadiusFromDimerLength(t.measured, t.ar), 1e-12);
  EXPECT_EQ(t.calls, 3);
}

TEST(DimerLengthScale, ALengthIndependentOfTheRadiusNeedsTwoPasses) {
  FakeTracker t;
  t.gain = 0;  // the centroid and disc methods: the radius only sizes the calibration
  t.measured = 2.0 * (t.ar - 1.0) * t.true_radius;
  const LengthScale s = IterateDimerLengthScale(std::ref(t), t.ar);
  ASSERT_TRUE(s.ok);
  EXPECT_TRUE(s.converged);
  EXPECT_EQ(s.passes.size(), 2u);
  EXPECT_DOUBLE_EQ(s.radius_px, t.true_radius);
}

TEST(DimerLengthScale, AnUnsettledRadiusIsSaidAfterTheLastPass) {
  FakeTracker t;
  t.gain = -2.0 * (t.ar - 1.0);  // each pass flips the radius error: no fixed point reached
  const LengthScale s = IterateDimerLengthScale(std::ref(t), t.ar);
  ASSERT_TRUE(s.ok);
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(int(s.passes.size()), kLengthScaleMaxPasses);
  EXPECT_EQ(t.calls, kLengthScaleMaxPasses);
}

TEST(DimerLengthScale, GuessesRunFromSixPixelsWhileTheDimerFitsTheFrame) {
  const std::vector<double> g = DimerLengthRadiusGuesses(640, 3.9);
  ASSERT_FALSE(g.empty());
  EXPECT_EQ(g.front(), kGuessMinRadiusPx);
  for (size_t i = 1; i < g.size(); ++i) EXPECT_NEAR(g[i] / g[i - 1], kGuessRatio, 1e-12);
  EXPECT_LE(2.0 * 3.9 * g.back(), 640.0);
  EXPECT_GT(2.0 * 3.9 * g.back() * kGuessRatio, 640.0) << "the next guess would not fit";
  EXPECT_TRUE(DimerLengthRadiusGuesses(40, 3.9).empty()) << "no sphere of 6 px fits";
}

TEST(DimerLengthScale, WhereTheMeasuredRadiusLosesTheSpheresTheGuessesFindThem) {
  // A tracker that finds both spheres only with a radius within 20 % of the true one (the
  // under-exposed POV-Ray film: none with its measured 8 px, both from 18 px to 28 px).
  const double truth = 23.75, ar = 3.9, nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> tried;
  auto length_of = [&](double r) {
    tried.push_back(r);
    if (std::isnan(r) || std::abs(r / truth - 1.0) > 0.2) return nan;
    return 2.0 * (ar - 1.0) * truth + 0.3 * (r - truth);
  };
  const LengthScale s = IterateDimerLengthScale(
      length_of, ar, [&] { return DimerLengthRadiusGuesses(640, ar); });
  ASSERT_TRUE(s.ok) << s.failure;
  EXPECT_TRUE(s.converged);
  EXPECT_NEAR(s.radius_px, truth, 0.01);
  // Measured, then 6, 7.5, 9.4, 11.7, 14.6 lose them; 18.3 finds them; two passes settle.
  ASSERT_GE(tried.size(), 7u);
  EXPECT_TRUE(std::isnan(tried[0]));
  EXPECT_NEAR(tried[6], 6.0 * std::pow(kGuessRatio, 5), 1e-9);
  EXPECT_EQ(s.passes.size(), tried.size());
  // No guess finds them: the failure says how many were tried.
  const LengthScale none = IterateDimerLengthScale(
      [&](double) { return nan; }, ar, [&] { return DimerLengthRadiusGuesses(640, ar); });
  EXPECT_FALSE(none.ok);
  EXPECT_NE(none.failure.find("guessed"), std::string::npos) << none.failure;
}

TEST(DimerLengthScale, NoLengthIsAFailureThatSaysWhy) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const LengthScale none = IterateDimerLengthScale([&](double) { return nan; }, 3.9);
  EXPECT_FALSE(none.ok);
  EXPECT_NE(none.failure.find("both spheres"), std::string::npos) << none.failure;
  // Found with the radius measured, lost with the radius the length implies: no calibration.
  int calls = 0;
  const LengthScale lost = IterateDimerLengthScale(
      [&](double r) {
        ++calls;
        return std::isnan(r) ? 137.75 : nan;
      },
      3.9);
  EXPECT_FALSE(lost.ok);
  EXPECT_EQ(calls, 2);
  EXPECT_NE(lost.failure.find("23.75"), std::string::npos) << lost.failure;
}

}  // namespace
}  // namespace dimer::tracking
