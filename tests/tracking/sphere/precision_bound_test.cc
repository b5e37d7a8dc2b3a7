// The Cramér-Rao bound of the template method (tracking/sphere/precision_bound.h) and the noise it is
// measured with.
#include "tracking/sphere/precision_bound.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <cmath>

namespace dimer::tracking {
namespace {

TEST(PrecisionBound, ARampsBoundIsSigmaOverItsGradientEnergy) {
  // I = 3 x + 0.5 y on a 41 x 41 appearance, every pixel known: the central differences are the
  // slopes, over the 39 x 39 pixels whose four neighbours are known.
  Appearance a;
  a.half = 20;
  a.image = cv::Mat(41, 41, CV_32F);
  for (int y = 0; y < 41; ++y) {
    for (int x = 0; x < 41; ++x) a.image.at<float>(y, x) = float(3.0 * x + 0.5 * y);
  }
  a.mask = cv::Mat::ones(41, 41, CV_8U);
  const Eigen::Vector2d b = TranslationBound(a, 2.0);
  EXPECT_NEAR(b.x(), 2.0 / (3.0 * 39.0), 1e-6);
  EXPECT_NEAR(b.y(), 2.0 / (0.5 * 39.0), 1e-6);
  // Masked pixels and their neighbours do not count: half the mask, half the energy.
  a.mask.colRange(21, 41).setTo(0);
  const Eigen::Vector2d h = TranslationBound(a, 2.0);
  EXPECT_NEAR(h.x(), 2.0 / (3.0 * std::sqrt(39.0 * 19.0)), 1e-6);
  // A flat appearance bounds nothing.
  a.image.setTo(7.0f);
  EXPECT_TRUE(std::isnan(TranslationBound(a, 2.0).x()));
}

TEST(PrecisionBound, NoiseOfAFrameIsMeasuredAwayFromBlackAndTheClip) {
  cv::Mat frame(240, 320, CV_8U);
  cv::RNG rng(7);
  for (int r = 0; r < frame.rows; ++r) {
    for (int c = 0; c < frame.cols; ++c) {
      // Top half a lit surface at 100, bottom half a dark backdrop at 1: its noise is cut at 0.
      const double level = r < 120 ? 100.0 : 1.0;
      frame.at<uint8_t>(r, c) = cv::saturate_cast<uint8_t>(level + rng.gaussian(3.0));
    }
  }
  EXPECT_NEAR(FrameNoiseSigma(frame), 3.0, 0.1);
  // Nothing but the backdrop: too few usable pairs to say.
  EXPECT_TRUE(std::isnan(FrameNoiseSigma(frame.rowRange(120, 240).clone())));
}

}  // namespace
}  // namespace dimer::tracking
