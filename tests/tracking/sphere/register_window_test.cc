// RegisterTranslation works on the mask's bounding box (plus a margin) only, for speed; the
// answer must be that of the same two ECC runs on the whole images (template_locator.cc).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <cmath>
#include <random>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {
namespace {

// A noisy sphere-like pattern (soft disc, two highlights, a bright lower half that the mask
// cuts, as the plate's reflection is cut), sampled at (col + sx, row + sy).
cv::Mat Sphere(int size, double sx, double sy, uint64_t seed) {
  cv::Mat m(size, size, CV_32F);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, 2);
  const double c = (size - 1) / 2.0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double dx = x + sx - c, dy = y + sy - c;
      const double r = std::sqrt(dx * dx + dy * dy);
      const double disc = 1.0 / (1.0 + std::exp((r - 20) / 0.6));
      auto spot = [&](double x0, double y0, double a) {
        return a * std::exp(-((dx - x0) * (dx - x0) + (dy - y0) * (dy - y0)) / 2.9);
      };
      m.at<float>(y, x) = float(10 + disc * (dy > 4 ? 120 : 30) + spot(-6, -9, 180) +
                                spot(5, -7, 140) + noise(rng));
    }
  }
  return m;
}

// The same two runs as RegisterTranslation, on the whole images.
Eigen::Vector2d WholeImageEcc(const cv::Mat& fixed, const cv::Mat& moving, const cv::Mat& mask,
                              Eigen::Vector2d t) {
  const cv::TermCriteria stop(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-7);
  cv::Mat warp = (cv::Mat_<float>(2, 3) << 1, 0, float(t.x()), 0, 1, float(t.y()));
  cv::findTransformECC(fixed, moving, warp, cv::MOTION_TRANSLATION, stop, mask, 5);
  const double tx = warp.at<float>(0, 2), ty = warp.at<float>(1, 2);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, tx, 0, 1, ty);
  cv::Mat shifted, shifted_mask;
  cv::warpAffine(moving, shifted, shift, moving.size(), cv::INTER_LANCZOS4 | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  cv::warpAffine(mask, shifted_mask, shift, mask.size(), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat residual = cv::Mat::eye(2, 3, CV_32F);
  cv::findTransformECC(fixed, shifted, residual, cv::MOTION_TRANSLATION, stop, shifted_mask, 5);
  return {tx + residual.at<float>(0, 2), ty + residual.at<float>(1, 2)};
}

TEST(RegisterTranslation, OnTheMasksBoundingBoxAsOnTheWholeImages) {
  const int size = 69;  // half 34: the mask's box (upper part, rod cut) is well inside
  const cv::Mat moving = Sphere(size, 0, 0, 1);
  cv::Mat mask = cv::Mat::zeros(size, size, CV_8U);
  cv::circle(mask, {34, 34}, 22, cv::Scalar(1), cv::FILLED);
  mask.rowRange(38, size) = 0;            // the reflection below the horizon cut
  mask(cv::Rect(50, 28, 19, 10)) = 0;     // a rod corridor to the right
  ASSERT_LT(cv::boundingRect(mask).area(), size * size / 2);
  double worst = 0;
  int k = 0;
  for (double sx : {-0.45, -0.1, 0.3}) {
    for (double sy : {-0.35, 0.05, 0.4}) {
      const cv::Mat fixed = Sphere(size, sx, sy, 100 + k++);
      const Eigen::Vector2d start(std::round(sx) , std::round(sy));
      Eigen::Vector2d t = start;
      ASSERT_TRUE(RegisterTranslation(fixed, moving, mask, &t));
      const Eigen::Vector2d whole = WholeImageEcc(fixed, moving, mask, start);
      worst = std::max(worst, (t - whole).cwiseAbs().maxCoeff());
      EXPECT_NEAR(t.x(), sx, 0.05);  // and it found the shift at all
      EXPECT_NEAR(t.y(), sy, 0.05);
    }
  }
  // Float sums taken over fewer zeros in another order: far below the tracker's 0.005 px.
  EXPECT_LT(worst, 1e-4) << "windowed vs whole-image ECC, px";
}

}  // namespace
}  // namespace dimer::tracking
