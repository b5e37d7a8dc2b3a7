// Matches that are not the sphere (tracking/match_scores.h): far below their sphere's own
// scores, or giving the rigid dimer another length; the rest left alone.
#include "tracking/match_scores.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// n frames of a dimer 100 px long drifting right, both found, scores about `level` (a spread of
// +-0.002), lengths within +-0.03 px.
std::vector<FrameTrack> Frames(size_t n, double level) {
  std::vector<FrameTrack> f(n);
  for (size_t i = 0; i < n; ++i) {
    const double wiggle = double(int(i % 5) - 2);
    f[i].index = i;
    f[i].found = {true, true};
    f[i].centre = {Eigen::Vector2d(50 + 0.5 * double(i), 120),
                   Eigen::Vector2d(150 + 0.5 * double(i) + 0.015 * wiggle, 118)};
    f[i].score = {level + 0.001 * wiggle, level - 0.001 * wiggle};
  }
  return f;
}

TEST(MatchScores, AMatchFarBelowItsSpheresScoresIsDropped) {
  std::vector<FrameTrack> f = Frames(30, 0.99);
  f[7].score[1] = 0.62;                 // beside the sphere (POV-Ray: 0.53-0.63 against 0.99)
  f[7].centre[1].x() -= 0.2;            // (its length alone would pass)
  f[12].score[0] = 0.99 - 0.14;         // lower, within kMinScoreDrop: kept
  f[20].score[1] = kNaN;                // ECC did not converge: not judged by its score
  const MatchScores m = DropOutlyingMatches(&f);
  EXPECT_FALSE(f[7].found[1]);
  EXPECT_TRUE(std::isnan(f[7].score[1]));
  EXPECT_TRUE(f[7].found[0]);
  EXPECT_TRUE(f[12].found[0]);
  EXPECT_TRUE(f[20].found[1]);
  EXPECT_EQ(m.dropped[0], 0u);
  EXPECT_EQ(m.dropped[1], 1u);
  EXPECT_NEAR(m.median[0], 0.99, 0.002);
  EXPECT_NEAR(m.floor[1], 0.99 - kMinScoreDrop, 0.003);
  size_t found = 0;
  for (const FrameTrack& t : f) found += t.found[0] + t.found[1];
  EXPECT_EQ(found, 59u);
}

TEST(MatchScores, ASphereWhoseScoresAreAllLowKeepsThem) {
  // Under-exposed footage: every score about 0.6, spread 0.03: nothing is an outlier.
  std::vector<FrameTrack> f = Frames(30, 0.6);
  for (size_t i = 0; i < f.size(); ++i) f[i].score[0] += 0.03 * std::sin(double(i));
  f[3].score[0] = 0.5;
  const MatchScores m = DropOutlyingMatches(&f);
  EXPECT_EQ(m.dropped[0] + m.dropped[1] + m.dropped_length[0] + m.dropped_length[1], 0u);
}

TEST(MatchScores, APairOfAnotherLengthLosesTheSphereLessLikeItself) {
  std::vector<FrameTrack> f = Frames(30, 0.99);
  // A sphere at the frame's edge matched 9.7 px short, ECC not converged (no score).
  f[25].centre[1].x() -= 9.7;
  f[25].score[1] = kNaN;
  // Another pair too long by 3 px, the left sphere's score the further below its median.
  f[10].centre[0].x() -= 3;
  f[10].score[0] = 0.95;
  f[10].score[1] = 0.985;
  const MatchScores m = DropOutlyingMatches(&f);
  EXPECT_TRUE(f[25].found[0]);
  EXPECT_FALSE(f[25].found[1]);
  EXPECT_FALSE(f[10].found[0]);
  EXPECT_TRUE(f[10].found[1]);
  EXPECT_EQ(m.dropped_length[0], 1u);
  EXPECT_EQ(m.dropped_length[1], 1u);
  EXPECT_NEAR(m.length_px, 100, 0.05);
}

TEST(MatchScores, OtherMethodsAreJudgedByTheLengthAloneAndShortTracksNotAtAll) {
  std::vector<FrameTrack> f = Frames(30, kNaN);  // the centroid: no scores
  f[4].centre[1].x() += 5;
  const MatchScores m = DropOutlyingMatches(&f);
  EXPECT_TRUE(std::isnan(m.median[0]));
  EXPECT_EQ(m.dropped_length[0] + m.dropped_length[1], 1u);
  EXPECT_FALSE(f[4].found[0] && f[4].found[1]);
  // Too few frames to know the sphere's scores or the dimer's length: nothing dropped.
  std::vector<FrameTrack> few = Frames(kMinScoredFrames - 1, 0.99);
  few[2].score[0] = 0.3;
  few[3].centre[1].x() += 5;
  const MatchScores n = DropOutlyingMatches(&few);
  EXPECT_EQ(n.dropped[0] + n.dropped[1] + n.dropped_length[0] + n.dropped_length[1], 0u);
}

}  // namespace
}  // namespace dimer::tracking
