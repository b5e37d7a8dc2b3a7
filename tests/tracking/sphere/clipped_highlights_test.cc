// Clipped highlights (tracking/sphere/clipped_highlights.h): a small steel-like sphere whose
// lamp highlight the camera clips. Its learnt appearance, registered with the clipped pixels,
// locks toward the pixel grid; the learning frames' test must leave them out there, and keep
// them where nothing is clipped or where they carry the position.
#include "tracking/sphere/clipped_highlights.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "common/disc_coverage.h"
#include "render/seeded_noise.h"
#include "tracking/sphere/appearance_model.h"
#include "tracking/sphere/fast_follow.h"

namespace dimer::tracking {
namespace clipped_highlights_test {
namespace {

constexpr double kRadius = 10.0;
constexpr int kWidth = 160, kHeight = 64;
constexpr double kRow = 30.0;
constexpr double kColumns[2] = {45.0, 115.0};
constexpr int kFrames = 48;

// How a sphere looks: a disc `body` levels over a backdrop of 10, brighter in its lower half
// (a reflection of the plate), and a lamp's highlight of peak `lamp` and width `lamp_px`
// (Gaussian sigma) up and to the left of the centre. The camera clips at 255.
struct Look {
  double body = 40, lamp = 1500, lamp_px = 0.7, noise = 2;
};

cv::Mat DrawFrame(const std::array<Eigen::Vector2d, 2>& centre, const Look& look,
                  Gaussian* noise) {
  cv::Mat img(kHeight, kWidth, CV_32F, cv::Scalar(10.0));
  for (const Eigen::Vector2d& c : centre) {
    for (int y = int(c.y() - kRadius) - 2; y <= int(c.y() + kRadius) + 2; ++y) {
      for (int x = int(c.x() - kRadius) - 2; x <= int(c.x() + kRadius) + 2; ++x) {
        const double dx = x - c.x(), dy = y - c.y();
        const double below = std::clamp(dy + 0.5, 0.0, 1.0);
        img.at<float>(y, x) +=
            float(DiscPixelArea(x, y, c, kRadius) * look.body * (1.0 + 1.5 * below));
        // The lamp's image is far smaller than a pixel's reach of the sphere's curvature: the
        // pixel integrates it (its mean over a 4 x 4 grid inside the pixel).
        double lamp = 0;
        for (int sy = 0; sy < 4; ++sy) {
          for (int sx = 0; sx < 4; ++sx) {
            const double ux = dx + (sx + 0.5) / 4 - 0.5 + 3.0, uy = dy + (sy + 0.5) / 4 - 0.5 + 4.0;
            lamp += std::exp(-(ux * ux + uy * uy) / (2 * look.lamp_px * look.lamp_px)) / 16;
          }
        }
        img.at<float>(y, x) += float(look.lamp * lamp);
      }
    }
  }
  cv::Mat out(kHeight, kWidth, CV_8U);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      out.at<uint8_t>(y, x) =
          cv::saturate_cast<uint8_t>(img.at<float>(y, x) + look.noise * noise->Next());
    }
  }
  return out;
}

// The spheres at sub-pixel phase (u, v) of the pixel grid (the right one at the opposite phase).
std::array<Eigen::Vector2d, 2> Centres(double u, double v) {
  return {Eigen::Vector2d(kColumns[0] + u, kRow + v),
          Eigen::Vector2d(kColumns[1] + 1 - u, kRow + 1 - v)};
}

struct Scene {
  std::vector<LearningSample> samples;
  std::array<LearntSphere, 2> learnt;
};

// kFrames learning frames at phases spread over the pixel, the rough centres the truth.
Scene Learn(const Look& look, uint64_t seed) {
  Gaussian noise(FrameSeed(seed, 0));
  Scene s;
  for (int i = 0; i < kFrames; ++i) {
    const std::array<Eigen::Vector2d, 2> c = Centres(std::fmod(0.37 * i, 1.0),
                                                     std::fmod(0.61 * i, 1.0));
    LearningSample l;
    l.image = DrawFrame(c, look, &noise);
    l.plate_row = kRow + kRadius + 6;
    l.plate_col = 0.5 * (kColumns[0] + kColumns[1]);
    l.found = {true, true};
    l.centre = c;
    s.samples.push_back(l);
  }
  s.learnt = LearnAppearances(s.samples, kRadius, false);
  return s;
}

// Followed on fresh frames at 10 x 10 phases, sphere k: the error's mean over the phases of
// each tenth of a pixel in column, its peak-to-peak (locking), mean and rms about the mean.
struct Locking {
  double peak_to_peak = 0, rms = 0, mean = 0;
};
Locking Follow(const Appearance& a, const Look& look, int k, uint64_t seed) {
  Gaussian noise(FrameSeed(seed, 1));
  const FollowModel m = PrepareFollow(a);
  std::array<double, 10> bin{};
  std::vector<double> errors;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const std::array<Eigen::Vector2d, 2> c = Centres((i + 0.5) / 10, (j + 0.5) / 10);
      LearningSample l;
      l.image = DrawFrame(c, look, &noise);
      l.plate_row = kRow + kRadius + 6;
      l.plate_col = 0.5 * (kColumns[0] + kColumns[1]);
      l.centre = c;
      const std::optional<Located> got =
          FollowOnlyQuickly(l.image, a, m, c[k], LearningContext(l, k), FollowStop{});
      EXPECT_TRUE(got.has_value());
      if (!got) continue;
      const double e = got->position.x() - c[k].x();
      bin[size_t(k == 0 ? i : 9 - i)] += e / 10;
      errors.push_back(e);
    }
  }
  Locking out;
  out.peak_to_peak = *std::max_element(bin.begin(), bin.end()) -
                     *std::min_element(bin.begin(), bin.end());
  double mean = 0, ss = 0;
  for (double e : errors) mean += e / double(errors.size());
  for (double e : errors) ss += (e - mean) * (e - mean);
  out.rms = std::sqrt(ss / double(errors.size()));
  out.mean = mean;
  return out;
}

// The appearance with the clipped zone left out, whatever the decision.
Appearance WithoutZone(const Scene& s, int k) {
  Appearance cut = s.learnt[size_t(k)].appearance;
  cut.mask = cut.mask.clone();
  cut.mask.setTo(0, ClippedZone(s.learnt[size_t(k)], s.samples));
  return cut;
}

// A sharp lamp clipped on a small sphere with a clear outline (the mirror-lit renders at
// R = 11.9 px): the locking drops to a fifth.
TEST(ClippedHighlights, LeftOutWhereTheyLockThePositionToThePixelGrid) {
  const Look look;
  const Scene s = Learn(look, 3);
  ASSERT_TRUE(s.learnt[0].appearance.valid());
  for (int k = 0; k < 2; ++k) {
    const ClipDecision d = DecideClippedHighlights(s.learnt[size_t(k)], s.samples, k, 2);
    const Locking whole = Follow(s.learnt[size_t(k)].appearance, look, k, 5);
    const Locking decided = Follow(d.appearance, look, k, 5);
    std::printf("sphere %d: %s\n  locking %.4f -> %.4f px, rms %.4f -> %.4f px\n", k,
                d.reason.c_str(), whole.peak_to_peak, decided.peak_to_peak, whole.rms,
                decided.rms);
    EXPECT_TRUE(d.leave_out) << d.reason;
    EXPECT_GT(d.zone_px, 0);
    EXPECT_LT(decided.peak_to_peak, 0.5 * whole.peak_to_peak);
    EXPECT_LT(decided.rms, whole.rms);
    // The followed appearance keeps the learnt one's reference point: over fresh frames the
    // two register the same on average (the offsets to the centre rest on the learnt one).
    EXPECT_NEAR(decided.mean, whole.mean, 0.004);
    EXPECT_GT(std::abs(d.mean_d.x()) + std::abs(d.mean_d.y()), 0.0);
  }
}

// A faint outline under noise with a wide clipped highlight: the highlight's shoulders carry
// most of the position and lock little, and leaving the zone out would double the scatter.
TEST(ClippedHighlights, KeptWhereTheyCarryThePosition) {
  for (const Look look : {Look{3, 400, 2.0, 4}, Look{3, 600, 3.0, 4}, Look{5, 300, 1.5, 4},
                          Look{2, 1000, 2.5, 6}}) {
    const Scene s = Learn(look, 3);
    ASSERT_TRUE(s.learnt[0].appearance.valid());
    const ClipDecision d = DecideClippedHighlights(s.learnt[0], s.samples, 0, 2);
    const Locking whole = Follow(s.learnt[0].appearance, look, 0, 5);
    const Locking cut = Follow(WithoutZone(s, 0), look, 0, 5);
    std::printf("body %g, lamp %g (sigma %g px), noise %g: %s\n  rms %.4f kept, %.4f left out\n",
                look.body, look.lamp, look.lamp_px, look.noise, d.reason.c_str(), whole.rms,
                cut.rms);
    EXPECT_GT(d.zone_px, 0);
    EXPECT_FALSE(d.leave_out) << d.reason;
    EXPECT_LT(whole.rms, cut.rms);
    EXPECT_EQ(cv::countNonZero(d.appearance.mask != s.learnt[0].appearance.mask), 0);
  }
}

TEST(ClippedHighlights, NothingLeftOutWhereNothingIsClipped) {
  const Look look{40, 200, 0.7, 2};
  const Scene s = Learn(look, 3);
  ASSERT_TRUE(s.learnt[0].appearance.valid());
  const ClipDecision d = DecideClippedHighlights(s.learnt[0], s.samples, 0, 2);
  EXPECT_EQ(d.zone_px, 0);
  EXPECT_FALSE(d.leave_out);
  EXPECT_EQ(cv::countNonZero(d.appearance.mask != s.learnt[0].appearance.mask), 0);
  EXPECT_NE(d.reason.find("no clipped highlight"), std::string::npos) << d.reason;
}

// The followed appearance is moved by the mean difference: a frame registers that much lower.
TEST(ClippedHighlights, ShiftedContentRegistersByTheShift) {
  const Look look{40, 200, 0.7, 2};  // nothing clipped: no locking in either registration
  const Scene s = Learn(look, 3);
  ASSERT_TRUE(s.learnt[0].appearance.valid());
  const Appearance& a = s.learnt[0].appearance;
  const Eigen::Vector2d by(0.3, -0.2);
  const cv::Mat before = a.image.clone();
  const Appearance moved = ShiftContent(a, by);
  EXPECT_EQ(cv::countNonZero(moved.mask != a.mask), 0);
  EXPECT_EQ(cv::norm(a.image, before, cv::NORM_INF), 0.0);  // the learnt one untouched
  const FollowModel m = PrepareFollow(a), mm = PrepareFollow(moved);
  for (const LearningSample& sample : s.samples) {
    const MaskContext ctx = LearningContext(sample, 0);
    const std::optional<Located> p =
        FollowOnlyQuickly(sample.image, a, m, sample.centre[0], ctx, FollowStop{});
    const std::optional<Located> q =
        FollowOnlyQuickly(sample.image, moved, mm, sample.centre[0], ctx, FollowStop{});
    ASSERT_TRUE(p && q);
    // To 15 % of the shift: an outline of a pixel's width is undersampled, and its Lanczos
    // shift is not exactly the sphere moved (the shifts the decision makes are < 0.05 px).
    EXPECT_NEAR(q->position.x() - p->position.x(), -by.x(), 0.15 * std::abs(by.x()));
    EXPECT_NEAR(q->position.y() - p->position.y(), -by.y(), 0.15 * std::abs(by.y()));
  }
}

// Each sample is registered on its own and summed in order: the thread count changes nothing.
TEST(ClippedHighlights, TheDecisionDoesNotDependOnTheThreadCount) {
  const Scene s = Learn(Look{}, 7);
  ASSERT_TRUE(s.learnt[1].appearance.valid());
  const ClipDecision one = DecideClippedHighlights(s.learnt[1], s.samples, 1, 1);
  const ClipDecision two = DecideClippedHighlights(s.learnt[1], s.samples, 1, 2);
  EXPECT_EQ(one.mean_d2, two.mean_d2);
  EXPECT_EQ(one.mean_delta, two.mean_delta);
  EXPECT_EQ(one.n, two.n);
  EXPECT_EQ(one.reason, two.reason);
}

}  // namespace
}  // namespace clipped_highlights_test
}  // namespace dimer::tracking
