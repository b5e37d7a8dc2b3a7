// One plate through the film (plate_consensus.h): learning frames that took a ruler's lower edge
// for the plate are measured again near the others' row; a plate that moves far is left alone.
#include "tracking/plate_consensus.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

constexpr int kConsensusWidth = 240, kConsensusHeight = 140;

// A dark backdrop, a white ruler's band over rows 40-54, a grey plate from `plate` down (its
// edge at `plate`, rows counted at pixel centres, blurred by 0.5 px), noise 2.
cv::Mat RulerAndPlate(double plate, unsigned seed) {
  cv::Mat f(kConsensusHeight, kConsensusWidth, CV_32F);
  for (int y = 0; y < f.rows; ++y) {
    // The plate's share of the row: its coverage, then the blur below.
    const double plate_cover = std::clamp(double(y) + 0.5 - plate, 0.0, 1.0);
    const double level = (y >= 40 && y < 55 ? 250.0 : 10.0) * (1 - plate_cover) + 130.0 * plate_cover;
    f.row(y).setTo(level);
  }
  cv::GaussianBlur(f, f, cv::Size(0, 0), 0.5);
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0, 2);
  for (int y = 0; y < f.rows; ++y) {
    for (int x = 0; x < f.cols; ++x) f.at<float>(y, x) += n(rng);
  }
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

std::vector<LearningSample> Samples(double amplitude, std::vector<double>* truth) {
  std::vector<LearningSample> s(12);
  for (size_t i = 0; i < s.size(); ++i) {
    const double plate = 90.0 + amplitude * std::sin(2 * std::numbers::pi * double(i) / 12.0);
    truth->push_back(plate);
    s[i].image = RulerAndPlate(plate, unsigned(i + 1));
    s[i].plate_row = plate;
    s[i].plate_col = 0.5 * (kConsensusWidth - 1);
  }
  return s;
}

TEST(PlateConsensus, FramesThatTookTheRulersEdgeAreMeasuredAgain) {
  std::vector<double> truth;
  std::vector<LearningSample> s = Samples(1.25, &truth);
  for (size_t i : {2, 5, 9}) s[i].plate_row = 55.0;  // the ruler's lower edge
  EXPECT_EQ(KeepOnePlate(10.0, &s), 3u);
  for (size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(s[i].plate_row, truth[i], (i == 2 || i == 5 || i == 9) ? 0.3 : 0.0) << i;
  }
}

TEST(PlateConsensus, APlateMovingFarIsItsMotion) {
  // 12 px of amplitude (10 Hz at Gamma 1 and 0.2 mm/px): no frame stands off the others.
  std::vector<double> truth;
  std::vector<LearningSample> s = Samples(12.0, &truth);
  EXPECT_EQ(KeepOnePlate(10.0, &s), 0u);
  for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(s[i].plate_row, truth[i]);
}

}  // namespace
}  // namespace dimer::tracking
