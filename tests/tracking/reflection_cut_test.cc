// A steel sphere reflects the plate in its lower part, and the horizon of that reflection moves
// within the sphere as the sphere rises (tracking/appearance_model.h, kHorizonGuardPx). Frames
// made here, with exact centres: the left sphere rests, the right one rises by up to 24 px while
// the horizon in it moves down by 0.08 px per px of lift. Matched with its reflection, the
// rising sphere's row followed the horizon; the template method leaves the reflection out.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <random>

#include "tracking/disc_coverage.h"
#include "tracking/frame_source.h"
#include "tracking/track.h"

namespace dimer::tracking {
namespace {

constexpr int kWidth = 512, kHeight = 256;
constexpr double kPlateRow = 200.5, kR = 20.0;
constexpr double kHorizonPerLift = 0.08;  // px the horizon moves per px of lift
constexpr size_t kFrames = 40;

struct Sphere {
  Eigen::Vector2d c;
  double lift;
};

// One sphere's level at (x, y): a faint upper part, two lamps' highlights fixed to the centre,
// the plate's reflection below a horizon that depends on the lift.
double SphereLevel(const Sphere& s, int x, int y) {
  const double dx = x - s.c.x(), dy = y - s.c.y();
  const double horizon = 3.0 + kHorizonPerLift * s.lift;
  double body = dy > horizon ? 90.0 : 14.0;
  auto spot = [&](double x0, double y0, double amp) {
    return amp * std::exp(-((dx - x0) * (dx - x0) + (dy - y0) * (dy - y0)) / 2.0);
  };
  body += spot(-6, -8, 160) + spot(5, -6, 130);
  return body;
}

cv::Mat Frame(const Sphere (&s)[2], std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 2.0);
  cv::Mat f(kHeight, kWidth, CV_8U);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      double v = y > kPlateRow ? 80.0 : 2.0;  // the plate's front face below its top edge
      for (const Sphere& sp : s) {
        if (std::abs(x - sp.c.x()) > kR + 2 || std::abs(y - sp.c.y()) > kR + 2) continue;
        const double a = DiscPixelArea(x, y, sp.c, kR);
        if (a > 0) v = (1 - a) * v + a * SphereLevel(sp, x, y);
      }
      f.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(v + noise(*rng));
    }
  }
  return f;
}

TEST(ReflectionCut, ARisingMirrorSphereDoesNotFollowItsReflection) {
  std::mt19937 rng(11);
  std::vector<cv::Mat> frames;
  std::vector<std::array<Sphere, 2>> truth;
  for (size_t i = 0; i < kFrames; ++i) {
    const double lift = 0.6 * double(i);
    const Sphere s[2] = {{{150.3, kPlateRow - kR}, 0.0},
                         {{290.6 + 0.05 * double(i), kPlateRow - kR - lift}, lift}};
    frames.push_back(Frame(s, &rng));
    truth.push_back({s[0], s[1]});
  }
  MemorySource source(frames);
  SequenceOptions o;
  o.tracker.method = Method::kAuto;
  o.contact_radius_px = kR;  // the scale is given
  o.threads = 2;
  const SequenceResult r = TrackSequence(source, o);
  ASSERT_EQ(r.method, Method::kTemplate) << r.method_reason;
  ASSERT_EQ(r.frames.size(), kFrames);
  // Row error of the rising sphere against its lift: a straight-line fit's slope.
  double sl = 0, se = 0, sll = 0, sle = 0;
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector2d mean(0, 0);
    std::vector<Eigen::Vector2d> err;
    for (size_t i = 0; i < kFrames; ++i) {
      ASSERT_TRUE(r.frames[i].found[k]) << "frame " << i << " sphere " << k;
      err.push_back(r.frames[i].centre[k] - truth[i][k].c);
      mean += err.back() / double(kFrames);
      if (k == 1) {
        const double l = truth[i][1].lift, e = err.back().y();
        sl += l, se += e, sll += l * l, sle += l * e;
      }
    }
    double scatter = 0;
    for (const auto& e : err) scatter += (e - mean).squaredNorm() / double(kFrames);
    std::printf("[ stats    ] sphere %d: bias (%+.3f, %+.3f) px, scatter %.3f px, offsets col %s row %s\n",
                k, mean.x(), mean.y(), std::sqrt(scatter), r.offsets.col[k].source.c_str(),
                r.offsets.row[k].source.c_str());
    EXPECT_LT(mean.norm(), 0.1) << "sphere " << k;
    EXPECT_LT(std::sqrt(scatter), 0.05) << "sphere " << k;
  }
  const double n = double(kFrames);
  const double slope = (n * sle - sl * se) / (n * sll - sl * sl);
  std::printf("[ stats    ] rising sphere's row error per px of lift: %+.4f\n", slope);
  // Matched with its reflection the row would follow the horizon by a good part of
  // kHorizonPerLift; left out, it does not follow it at all.
  EXPECT_LT(std::abs(slope), 0.1 * kHorizonPerLift);
}

}  // namespace
}  // namespace dimer::tracking
