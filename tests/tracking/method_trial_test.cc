// auto's trial (tracking/method_trial.h): the noise a track shows, read from the track itself.
#include "tracking/method_trial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

// A dimer in flight (parabolic rows, drifting columns, length 100 px at a slow tilt) with
// Gaussian noise `sigma` on every coordinate, an impact (a kink in the row's velocity) every
// 40 frames, and sphere k missing in frames where `missing(i, k)`.
template <typename Missing>
std::vector<FrameTrack> Track(size_t n, double sigma, uint64_t seed, Missing missing) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  std::vector<FrameTrack> out(n);
  for (size_t i = 0; i < n; ++i) {
    const double t = double(i % 40);  // frames since the last impact
    const double row = 150 - 2.0 * t + 0.05 * t * t;
    const double tilt = 0.002 * double(i);
    const Eigen::Vector2d left(100 + 0.3 * double(i), row);
    const Eigen::Vector2d right = left + 100 * Eigen::Vector2d(std::cos(tilt), -std::sin(tilt));
    out[i].index = i;
    for (int k = 0; k < 2; ++k) {
      out[i].found[k] = !missing(i, k);
      out[i].centre[k] = (k == 0 ? left : right) + Eigen::Vector2d(noise(rng), noise(rng));
    }
  }
  return out;
}

TEST(MethodTrial, ReadsTheCentresNoiseFromTheirSmoothnessAndTheLengthsConstancy) {
  const auto none = [](size_t, int) { return false; };
  for (const double sigma : {0.01, 0.05, 0.2}) {
    double smooth = 0, length = 0;
    const int runs = 40;
    for (int s = 0; s < runs; ++s) {
      const TrialScores t = ScoreTrial(Track(kTrialFrames, sigma, uint64_t(s), none), Method::kCentroid);
      smooth += t.smooth_px / runs;
      length += t.length_px / runs;
      EXPECT_EQ(t.both_found, kTrialFrames);
      EXPECT_DOUBLE_EQ(t.score, std::max(t.smooth_px, t.length_px / std::sqrt(2.0)));
    }
    // Each centre's noise is sigma; the length, a difference of two centres, has sqrt(2) sigma
    // along the rod. Over 40 runs of 48 frames the mean is within 10 %, impacts included.
    EXPECT_NEAR(smooth / sigma, 1.0, 0.1) << sigma;
    EXPECT_NEAR(length / (std::sqrt(2.0) * sigma), 1.0, 0.1) << sigma;
  }
}

// The template's trial also judges the dimer's length against its noise (length_constancy.h),
// which the learning's referee reads (length_relearn.h): a rigid track passes; one whose right
// sphere drifts 3 px along the rod over the trial's second half, as a held appearance does,
// departs there.
TEST(MethodTrial, JudgesTheLengthsConstancyForTheLearningsReferee) {
  const auto none = [](size_t, int) { return false; };
  const TrialScores rigid = ScoreTrial(Track(kTrialFrames, 0.03, 2, none), Method::kTemplate);
  EXPECT_EQ(rigid.constancy.frames, kTrialFrames);
  EXPECT_EQ(rigid.constancy.departing, 0u);
  std::vector<FrameTrack> held = Track(kTrialFrames, 0.03, 2, none);
  for (size_t i = kTrialFrames / 2; i < kTrialFrames; ++i) {
    const Eigen::Vector2d along = (held[i].centre[1] - held[i].centre[0]).normalized();
    held[i].centre[1] += 3.0 * double(i - kTrialFrames / 2) / double(kTrialFrames / 2) * along;
  }
  const TrialScores t = ScoreTrial(held, Method::kTemplate);
  EXPECT_GT(t.constancy.departing, 0u);
  EXPECT_GE(t.constancy.first, kTrialFrames / 2);
  EXPECT_GT(t.constancy.worst_px, 1.0);
}

TEST(MethodTrial, AMethodThatMissesASphereInMoreThanATenthOfTheFramesCannotCompete) {
  const auto every_fifth = [](size_t i, int k) { return k == 1 && i % 5 == 0; };
  const TrialScores t = ScoreTrial(Track(kTrialFrames, 0.05, 1, every_fifth), Method::kCentroid);
  EXPECT_LT(double(t.both_found), kTrialMinFoundFraction * double(t.frames));
  EXPECT_TRUE(std::isnan(t.score));
  const auto one_missing = [](size_t i, int k) { return k == 0 && i == 7; };
  EXPECT_TRUE(std::isfinite(
      ScoreTrial(Track(kTrialFrames, 0.05, 1, one_missing), Method::kCentroid).score));
}

TEST(MethodTrial, TheSilhouettesReplaceTheTemplateOnlyAtHalfItsNoiseOrWhereItCannotCompete) {
  TrialScores tmpl, sil;
  tmpl.score = 0.017, sil.score = 0.014;  // POV-Ray matte steel: the rim fit's rows 1 px off
  EXPECT_FALSE(SilhouetteWinsTrial(tmpl, sil));
  sil.score = 0.008;
  EXPECT_TRUE(SilhouetteWinsTrial(tmpl, sil));
  sil.score = NAN;
  EXPECT_FALSE(SilhouetteWinsTrial(tmpl, sil));
  tmpl.score = NAN, sil.score = 0.05;
  EXPECT_TRUE(SilhouetteWinsTrial(tmpl, sil));
}

TEST(MethodTrial, DiscFitReplacesTheCentroidWhereItShowsLessNoiseByTheMargin) {
  struct Trial {
    double centroid, discfit;
    bool discfit_wins;
  };
  for (const Trial& t : {Trial{0.0050, 0.0016, true},   // our renderer's backlit film, A_r 3.9
                         Trial{0.0050, 0.0050, false},  // POV-Ray's steel: both end with the rim fit
                         Trial{0.0050, 0.0046, false}, Trial{0.0050, NAN, false},
                         Trial{NAN, 0.01, true}}) {
    TrialScores centroid, discfit;
    centroid.score = t.centroid, discfit.score = t.discfit;
    EXPECT_EQ(DiscFitWinsTrial(centroid, discfit), t.discfit_wins)
        << t.centroid << " against " << t.discfit;
  }
}

}  // namespace
}  // namespace dimer::tracking
