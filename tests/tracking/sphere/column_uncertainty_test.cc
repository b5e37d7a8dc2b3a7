// The stated uncertainty of the template method's column offset (LimbColumnOffset,
// tracking/sphere/appearance_model.h) against the spread the same footage shows over noise seeds: a
// faintly outlined steel-like sphere, learnt from 20 noisy 8-bit frames as the tracker learns it.
// The delete-a-group jackknife over the learning samples states the spread itself; the outline
// pairs' own scatter, which takes neighbouring rays for independent edges, fell short of it on
// POV-Ray footage (tests/tracking/povray_footage_test.cc, PovrayNoiseSeeds), though not on this
// footage (0.055 px against 0.059). Here the check is that the jackknife is neither short of
// the spread nor far above it (it states 1.25 times it: an edge's argmax is a rough statistic).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tracking/sphere/appearance_model.h"
#include "common/disc_coverage.h"
#include "render/seeded_noise.h"
#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace column_uncertainty_test {
namespace {

constexpr double kRadius = 23.75;
constexpr int kWidth = 320, kHeight = 140;
constexpr double kRow = 70.0;                        // the spheres' centre row (at rest)
constexpr double kCols[2] = {90.0, 230.0};
constexpr int kFrames = 20;
constexpr int kSeeds = 12;
constexpr double kNoise = 2.0;                       // grey levels per frame
constexpr double kPsfPx = 0.7;                       // the lens's Gaussian blur, sigma

// One frame: both spheres at sub-pixel positions `c`, dark backdrop (4), each sphere's upper
// half a faint 5 above it, its lower half the reflected plate (60), two highlights; the outline
// antialiased by exact pixel coverage, blurred by the lens; 8-bit with noise.
cv::Mat Frame(const std::array<Eigen::Vector2d, 2>& c, Gaussian* noise) {
  cv::Mat img(kHeight, kWidth, CV_32F);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      double v = 4.0;
      for (const Eigen::Vector2d& p : c) {
        const double dx = x - p.x(), dy = y - p.y();
        if (std::abs(dx) > kRadius + 2 || std::abs(dy) > kRadius + 2) continue;
        const double inside = DiscPixelArea(x, y, p, kRadius);
        double body = dy > 4 ? 60.0 : 5.0;
        auto spot = [&](double x0, double y0, double amp) {
          return amp * std::exp(-((dx - x0) * (dx - x0) + (dy - y0) * (dy - y0)) / 2.0);
        };
        body += spot(-7, -8, 200) + spot(5, -6, 160);
        v += inside * body;
      }
      img.at<float>(y, x) = float(v);
    }
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), kPsfPx);
  cv::Mat out(kHeight, kWidth, CV_8U);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const double v = img.at<float>(y, x) + kNoise * noise->Next();
      out.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(v);
    }
  }
  return out;
}

struct Film {
  std::vector<LearningSample> samples;
  std::vector<std::array<Eigen::Vector2d, 2>> truth;
};

// kFrames frames at rest on the plate, each sphere moved by a different sub-pixel amount per
// frame (the grid's phase varies as in a real film); rough centres off as from highlights.
Film MakeFilm(uint64_t seed) {
  Film f;
  Gaussian noise(FrameSeed(seed, 0));
  for (int i = 0; i < kFrames; ++i) {
    const double u = std::fmod(0.37 * i, 1.0) - 0.5, w = std::fmod(0.61 * i, 1.0) - 0.5;
    const std::array<Eigen::Vector2d, 2> c{Eigen::Vector2d(kCols[0] + u, kRow + 0.1 * w),
                                           Eigen::Vector2d(kCols[1] + w, kRow + 0.1 * u)};
    LearningSample s;
    s.image = Frame(c, &noise);
    s.plate_row = kRow + kRadius + 0.1;  // the plate drawn nowhere: only its cut matters
    s.plate_col = 0.5 * (kCols[0] + kCols[1]);
    s.found = {true, true};
    s.centre = {c[0] + Eigen::Vector2d(1.2, 3.0), c[1] + Eigen::Vector2d(-0.8, 2.0)};
    f.samples.push_back(s);
    f.truth.push_back(c);
  }
  return f;
}

// The true offset (reference -> centre) of sphere k's learnt appearance: the mean over the
// samples of the true centre less the position the learning registered it at.
Eigen::Vector2d TrueOffset(const Film& f, const LearntSphere& s, int k) {
  Eigen::Vector2d sum(0, 0);
  for (size_t i = 0; i < s.samples.size(); ++i) {
    sum += f.truth[s.samples[i]][k] - s.registered[i];
  }
  return sum / double(s.samples.size());
}

TEST(JackknifeError, OfKnownValuesAndWithTooFewGroups) {
  // mean 2.5, sum of squares 5: sqrt(3/4 * 5).
  EXPECT_NEAR(JackknifeError({1, 2, 3, 4}), std::sqrt(3.75), 1e-12);
  // Groups that could not be measured do not count.
  EXPECT_NEAR(JackknifeError({1, NAN, 2, 3, 4, INFINITY}), std::sqrt(3.75), 1e-12);
  EXPECT_TRUE(std::isnan(JackknifeError({1, 2, NAN})));
  EXPECT_TRUE(std::isnan(JackknifeError({})));
  EXPECT_EQ(JackknifeError({2, 2, 2}), 0.0);
}

TEST(ColumnUncertainty, TheStatedColumnUncertaintyMatchesItsSpreadOverNoiseSeeds) {
  // Under the sanitizers (DIMERLAB_TEST_SCALE < 1) two seeds exercise the code and the
  // statistics are left to the full run.
  const int seeds = testing::TestScale() < 1 ? 2 : kSeeds;
  double err2 = 0, stated2 = 0, pairs2 = 0;
  int n = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const Film f = MakeFilm(uint64_t(seed));
    const std::array<LearntSphere, 2> learnt = LearnAppearances(f.samples, kRadius, true);
    for (int k = 0; k < 2; ++k) {
      ASSERT_TRUE(learnt[k].appearance.valid()) << "seed " << seed;
      ASSERT_EQ(learnt[k].jackknife.size(), std::min(size_t(kJackknifeGroups), size_t(kFrames)));
      const Eigen::Vector2d truth = TrueOffset(f, learnt[k], k);
      const OffsetEstimate e = LimbColumnOffset(learnt[k], truth.y());
      const OffsetEstimate pairs_only = LimbColumnOffset(learnt[k].appearance, truth.y());
      ASSERT_EQ(e.source, "limb") << "seed " << seed;
      EXPECT_EQ(e.value, pairs_only.value) << "the jackknife changes the uncertainty only";
      err2 += (e.value - truth.x()) * (e.value - truth.x());
      stated2 += e.err * e.err;
      pairs2 += pairs_only.err * pairs_only.err;
      ++n;
    }
  }
  const double rms_err = std::sqrt(err2 / n), rms_stated = std::sqrt(stated2 / n);
  const double rms_pairs = std::sqrt(pairs2 / n);
  std::printf("[ stats    ] column error RMS %.4f px over %d spheres; stated RMS %.4f px "
              "(the pairs' scatter alone %.4f px)\n",
              rms_err, n, rms_stated, rms_pairs);
  if (seeds < kSeeds) return;
  // 24 spheres: the RMS error is known to about 15 %. Stated too small is the harm (a user
  // trusts a position it does not have); stated far too large hides real bias. The jackknife
  // errs large on a statistic as rough as an edge's argmax (Efron-Stein): 1.25x here.
  EXPECT_GE(rms_stated, 0.8 * rms_err);
  EXPECT_LE(rms_stated, 2.0 * rms_err);
}

}  // namespace
}  // namespace column_uncertainty_test
}  // namespace dimer::tracking
