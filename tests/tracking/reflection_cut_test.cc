// A steel sphere reflects the plate in its lower part, and the horizon of that reflection moves
// within the sphere as the sphere rises (tracking/sphere/appearance_model.h, kHorizonGuardPx). Frames
// made here, with exact centres: the left sphere rests, the right one rises by up to 24 px while
// the horizon in it moves down by 0.08 px per px of lift. Matched with its reflection, the
// rising sphere's row followed the horizon; the template method leaves the reflection out.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <random>

#include "tracking/sphere/appearance_model.h"
#include "common/disc_coverage.h"
#include "tracking/io/frame_source.h"
#include "tracking/run_track.h"

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
  o.follower.method = Method::kAuto;
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

// The horizon of the plate's reflection, found in an appearance that also holds a soft box's
// reflection just above it: a disc of radius 4.5 px, saturated, 5 px above the horizon and 9
// of the 25 central columns wide, over a dim sphere (7) and a dim plate reflection (30 below the
// horizon), the levels of the POV-Ray front_softbox spheres. The lamp's lower edge steps 8x
// more than the horizon over its columns and 3x more averaged over all the central columns;
// the horizon crosses all of them.
TEST(ReflectionCut, ASoftBoxAboveTheHorizonIsNotTakenForIt) {
  constexpr int kHalf = 28;
  constexpr double kRadius = 23.75;
  constexpr int kHorizonRow = kHalf + 4;  // first row of the plate's reflection
  for (const double lamp_col : {-5.0, 0.0, 6.0}) {
    Appearance a;
    a.half = kHalf;
    a.radius_px = kRadius;
    a.image = cv::Mat(2 * kHalf + 1, 2 * kHalf + 1, CV_32F);
    a.mask = cv::Mat::zeros(a.image.size(), CV_8U);
    for (int y = 0; y < a.image.rows; ++y) {
      for (int x = 0; x < a.image.cols; ++x) {
        const double dx = x - kHalf, dy = y - kHalf;
        const double lamp = 0.5 * std::erfc((std::hypot(dx - lamp_col, dy + 4.0) - 4.5) / 0.7);
        a.image.at<float>(y, x) = float((y >= kHorizonRow ? 30.0 : 7.0) + 248.0 * lamp);
        a.mask.at<uint8_t>(y, x) = std::hypot(dx, dy) <= kRadius ? 1 : 0;
      }
    }
    const int row = ReflectionHorizon(a.image, a.mask, a.half, a.radius_px);
    // The Sobel step straddles the two rows about the change.
    EXPECT_GE(row, kHorizonRow - 1) << "lamp at column " << lamp_col;
    EXPECT_LE(row, kHorizonRow) << "lamp at column " << lamp_col;
  }
}

}  // namespace
}  // namespace dimer::tracking
