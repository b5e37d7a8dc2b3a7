// The sensor's stuck pixels (tracking/io/defect_pixels.h): found where they stand out from all
// their neighbours in nearly every frame, not where a highlight passes or the scene is a fine
// texture, and replaced by an interpolation across them. (Tracked on POV-Ray footage with hot
// pixels: tests/tracking/povray_footage_test.cc, PovrayStuckPixels.)
#include "tracking/io/defect_pixels.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>


namespace dimer::tracking {
namespace {

constexpr int kWidth = 400, kHeight = 200;

// A dim backdrop with noise, a bright point (a highlight, 1 px plus its blur) moving one pixel
// per frame, and the given stuck pixels at fixed levels.
std::vector<cv::Mat> Frames(size_t n, const std::vector<std::pair<cv::Point, int>>& stuck,
                            int depth = CV_8U) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 2.0);
  const double scale = depth == CV_8U ? 1.0 : 257.0;
  std::vector<cv::Mat> out;
  for (size_t i = 0; i < n; ++i) {
    cv::Mat f(kHeight, kWidth, CV_64F);
    for (int r = 0; r < kHeight; ++r) {
      for (int c = 0; c < kWidth; ++c) f.at<double>(r, c) = 20 + (r > 150 ? 60 : 0) + noise(rng);
    }
    const cv::Point h(100 + int(i), 80);  // the highlight: 120 above, its neighbours 16 above
    f(cv::Rect(h.x - 1, h.y - 1, 3, 3)) += 16;
    f.at<double>(h) += 104;
    cv::Mat g;
    f.convertTo(g, depth, scale);
    for (const auto& [p, level] : stuck) {
      if (depth == CV_8U) {
        g.at<uint8_t>(p) = cv::saturate_cast<uint8_t>(level);
      } else {
        g.at<uint16_t>(p) = cv::saturate_cast<uint16_t>(level * scale);
      }
    }
    out.push_back(g);
  }
  return out;
}

std::set<std::pair<int, int>> AsSet(const std::vector<cv::Point>& v) {
  std::set<std::pair<int, int>> s;
  for (const cv::Point& p : v) s.insert({p.x, p.y});
  return s;
}

TEST(DefectPixels, HotAndDeadPixelsAreFoundAndAPassingHighlightIsNot) {
  // Hot on the dark backdrop and on the bright plate, a weak hot one, a dead one on the plate,
  // two side by side, and one in the frame's corner.
  const std::vector<std::pair<cv::Point, int>> stuck = {
      {{30, 40}, 255}, {{300, 170}, 200}, {{200, 60}, 45}, {{250, 180}, 0},
      {{60, 120}, 180}, {{61, 120}, 150}, {{0, 0}, 255}};
  for (int depth : {CV_8U, CV_16U}) {
    const DefectPixels d = FindDefectPixels(Frames(9, stuck, depth));
    std::set<std::pair<int, int>> want;
    for (const auto& [p, level] : stuck) want.insert({p.x, p.y});
    EXPECT_EQ(AsSet(d.at), want) << (depth == CV_8U ? "8" : "16") << "-bit";
    EXPECT_TRUE(d.reason.empty()) << d.reason;
    EXPECT_EQ(d.frames, 9u);
  }
  // The moving highlight stands out from all its neighbours in every frame, but never twice at
  // one pixel: clean frames have none.
  EXPECT_TRUE(FindDefectPixels(Frames(9, {})).at.empty());
  // Too few frames to tell.
  EXPECT_TRUE(FindDefectPixels(Frames(kMinDefectFrames - 1, stuck)).at.empty());
}

TEST(DefectPixels, AFineFixedTextureIsTheSceneNotTheSensor) {
  // Isolated bright dots every 6 px over the backdrop (a grid, a fabric): thousands of pixels
  // that stand out in every frame. Replacing them would erase the scene.
  std::vector<std::pair<cv::Point, int>> dots;
  for (int r = 3; r < 150; r += 6) {
    for (int c = 3; c < kWidth; c += 6) dots.push_back({{c, r}, 90});
  }
  const DefectPixels d = FindDefectPixels(Frames(9, dots));
  EXPECT_TRUE(d.at.empty());
  EXPECT_NE(d.reason.find("taken for the scene"), std::string::npos) << d.reason;
}

// On an image that is locally a plane, a stuck pixel is replaced by the plane's own level: the
// mean of a whole pair of opposite sound neighbours (two stuck side by side take the vertical
// pair); in a corner, with no whole pair, the mean of the sound neighbours.
TEST(DefectPixels, RepairInterpolatesAcrossTheStuckPixel) {
  cv::Mat f(6, 6, CV_16U);
  for (int r = 0; r < f.rows; ++r) {
    for (int c = 0; c < f.cols; ++c) f.at<uint16_t>(r, c) = uint16_t(10 + 3 * c + 5 * r);
  }
  const cv::Mat plane = f.clone();
  DefectPixels d;
  d.at = {{0, 0}, {2, 2}, {3, 2}};
  d.mask = cv::Mat::zeros(f.size(), CV_8U);
  for (const cv::Point& p : d.at) d.mask.at<uint8_t>(p) = 1, f.at<uint16_t>(p) = 65535;
  const cv::Mat g = RepairDefectPixels(f, d);
  EXPECT_EQ(g.at<uint16_t>(2, 2), plane.at<uint16_t>(2, 2));
  EXPECT_EQ(g.at<uint16_t>(2, 3), plane.at<uint16_t>(2, 3));
  EXPECT_EQ(g.at<uint16_t>(0, 0), (13 + 15 + 18) / 3);  // 15.33 rounded
  EXPECT_EQ(f.at<uint16_t>(2, 2), 65535) << "the frame given is left alone";
  EXPECT_EQ(cv::countNonZero(g != f), 3);
  // None: the same image, not a copy.
  EXPECT_EQ(RepairDefectPixels(f, DefectPixels{}).data, f.data);
}

}  // namespace
}  // namespace dimer::tracking
