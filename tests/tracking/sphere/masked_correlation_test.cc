#include "tracking/sphere/masked_correlation.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>

namespace dimer::tracking {
namespace {

// A disc-shaped mask with a corridor cut through it (as the rod's is) and its lowest rows cut
// (as the plate's are): rows with gaps and rows with none.
cv::Mat SphereLikeMask(int size) {
  cv::Mat m = cv::Mat::zeros(size, size, CV_8U);
  cv::circle(m, {size / 2, size / 2}, size / 2 - 1, cv::Scalar(1), cv::FILLED);
  m(cv::Rect(size / 2 + 3, size / 2 - 2, size - size / 2 - 3, 5)).setTo(0);
  m(cv::Rect(0, size - 4, size, 4)).setTo(0);
  return m;
}

cv::Mat Noise(int rows, int cols, double level, double sigma, uint64_t seed) {
  cv::Mat img(rows, cols, CV_32F);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::NORMAL, level, sigma);
  return img;
}

// The coefficient at one place by its definition, in double: Pearson's over the masked pixels.
double Pearson(const cv::Mat& image, const cv::Mat& templ, const cv::Mat& mask, int px, int py) {
  double n = 0, st = 0, si = 0, stt = 0, sii = 0, sti = 0;
  for (int y = 0; y < templ.rows; ++y) {
    for (int x = 0; x < templ.cols; ++x) {
      if (!mask.at<uint8_t>(y, x)) continue;
      const double t = templ.at<float>(y, x), i = image.at<float>(py + y, px + x);
      n += 1, st += t, si += i, stt += t * t, sii += i * i, sti += t * i;
    }
  }
  return (sti - st * si / n) / std::sqrt((stt - st * st / n) * (sii - si * si / n));
}

TEST(MaskedCorrelation, AgreesWithOpenCvsMaskedMatchTemplate) {
  for (const int size : {15, 31, 57}) {
    const cv::Mat templ = Noise(size, size, 120, 40, size);
    const cv::Mat mask = SphereLikeMask(size);
    // The template somewhere in a noisy window 4 px wider on each side, and pure noise around.
    cv::Mat image = Noise(size + 8, size + 8, 100, 30, 7 * size);
    cv::addWeighted(image(cv::Rect(3, 5, size, size)), 0.3, templ, 0.7, 0,
                    image(cv::Rect(3, 5, size, size)));
    cv::Mat ours, theirs;
    MaskedCorrelation(image, templ, mask, &ours);
    cv::matchTemplate(image, templ, theirs, cv::TM_CCOEFF_NORMED, mask);
    ASSERT_EQ(ours.size(), theirs.size());
    double worst = 0;
    for (int y = 0; y < ours.rows; ++y) {
      for (int x = 0; x < ours.cols; ++x) {
        worst = std::max(worst, double(std::abs(ours.at<float>(y, x) - theirs.at<float>(y, x))));
      }
    }
    EXPECT_LT(worst, 2e-5) << "template " << size;
    cv::Point at;
    cv::minMaxLoc(ours, nullptr, nullptr, nullptr, &at);
    EXPECT_EQ(at, cv::Point(3, 5)) << "template " << size;
  }
}

// 16-bit levels, a faint pattern on a high pedestal: float sums of the raw levels' squares
// would lose the contrast; the coefficient must stay that of its definition.
TEST(MaskedCorrelation, KeepsTheContrastOfAFaintPatternOnAHighLevel) {
  const int size = 41;
  const cv::Mat templ = Noise(size, size, 0, 1, 3);
  const cv::Mat mask = SphereLikeMask(size);
  cv::Mat image = Noise(size + 6, size + 6, 60000, 4, 5);
  image(cv::Rect(2, 4, size, size)) += 8 * templ;
  cv::Mat ours;
  MaskedCorrelation(image, templ, mask, &ours);
  for (int y = 0; y < ours.rows; ++y) {
    for (int x = 0; x < ours.cols; ++x) {
      EXPECT_NEAR(ours.at<float>(y, x), Pearson(image, templ, mask, x, y), 1e-4)
          << "place " << x << ", " << y;
    }
  }
  EXPECT_GT(ours.at<float>(4, 2), 0.85);
}

TEST(MaskedCorrelation, IsUndefinedWhereTheImageOrTheMaskHoldsNoContrast) {
  const int size = 21;
  const cv::Mat templ = Noise(size, size, 50, 10, 1);
  cv::Mat ours;
  MaskedCorrelation(cv::Mat(size + 2, size + 2, CV_32F, cv::Scalar(80)), templ,
                    SphereLikeMask(size), &ours);
  for (int y = 0; y < ours.rows; ++y) {
    for (int x = 0; x < ours.cols; ++x) EXPECT_TRUE(std::isnan(ours.at<float>(y, x)));
  }
  MaskedCorrelation(Noise(size + 2, size + 2, 80, 5, 2), templ, cv::Mat::zeros(size, size, CV_8U),
                    &ours);
  EXPECT_TRUE(std::isnan(ours.at<float>(0, 0)));
}

}  // namespace
}  // namespace dimer::tracking
