// The whole-frame search for spheres that do not look alike: each sphere's learnt appearance
// finds it (FrameFollower::AcquireAbove). On POV-Ray ruler_above_plate, rendered to 100 frames,
// the hopping sphere, seen against the ruler's white band, scored under kMinTemplateScore
// against the resting one's appearance in every frame; searched with the left's alone it was
// never found, and auto fell back to the centroid, 10 px off.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <array>
#include <cmath>
#include <memory>

#include "tests/tracking/sphere/sphere_pattern.h"
#include "tracking/frame_follower.h"
#include "tracking/sphere/sphere_locator.h"
#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {
namespace {

constexpr double kR = testing::kPatternRadius;
constexpr int kWidth = 320, kHeight = 120;
constexpr double kPlateRow = 100.0;
// The right sphere's look: its pattern's levels inverted about this, a dark sphere with dark
// highlights on a bright band, as a steel sphere seen against a white ruler.
constexpr double kInvertAbout = 200.0;

double Right(double col, double row, double cx, double cy) {
  return kInvertAbout - testing::SpherePattern(col, row, cx, cy);
}

// The left sphere as sphere_pattern.h draws it, the right one inverted, over a bright plate.
cv::Mat TwoUnlikeSpheres(const Eigen::Vector2d& left, const Eigen::Vector2d& right) {
  cv::Mat img(kHeight, kWidth, CV_8U);
  const double split = 0.5 * (left.x() + right.x());
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      double v = 150.0;
      if (y <= kPlateRow) {
        v = x < split ? testing::SpherePattern(x, y, left.x(), left.y())
                      : Right(x, y, right.x(), right.y());
      }
      img.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(std::lround(v));
    }
  }
  return img;
}

TEST(FrameFollower, FindsASphereUnlikeItsPartner) {
  std::array<Appearance, 2> looks{testing::ExactPattern(), testing::ExactPattern()};
  Appearance& right = looks[1];
  for (int y = 0; y < right.image.rows; ++y) {
    for (int x = 0; x < right.image.cols; ++x) {
      right.image.at<float>(y, x) = float(Right(x, y, right.half, right.half));
    }
  }
  FollowerOptions o;
  o.method = Method::kTemplate;
  o.polarity = 1;
  o.radius_px = kR;
  o.appearance = std::make_shared<const std::array<Appearance, 2>>(looks);
  const Eigen::Vector2d left_at(90.3, kPlateRow - kR - 0.4), right_at(221.6, kPlateRow - kR - 6.2);
  const cv::Mat frame = TwoUnlikeSpheres(left_at, right_at);
  // The premise: the left's appearance does not find the right sphere.
  ASSERT_EQ(FindAppearance(frame, looks[0], kPlateRow, 1.5 * kR, kMinTemplateScore).size(), 1u);
  FrameFollower follower(o);
  const FrameTrack t = follower.Process(frame, 0);
  ASSERT_TRUE(t.found[0]);
  ASSERT_TRUE(t.found[1]);
  EXPECT_NEAR(t.centre[0].x(), left_at.x(), 0.05);
  EXPECT_NEAR(t.centre[0].y(), left_at.y(), 0.05);
  EXPECT_NEAR(t.centre[1].x(), right_at.x(), 0.05);
  EXPECT_NEAR(t.centre[1].y(), right_at.y(), 0.05);
}

}  // namespace
}  // namespace dimer::tracking
