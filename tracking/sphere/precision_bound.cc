#include "tracking/sphere/precision_bound.h"

#include <cmath>
#include <limits>
#include <vector>

#include "common/median.h"

namespace dimer::tracking {
namespace {

constexpr double kNoiseLevelMargin = 0.03;  // of full scale: 8 grey levels of 255
constexpr size_t kMinNoisePairs = 1000;
constexpr double kNoiseCutSigmas = 4.0;

}  // namespace

double FrameNoiseSigma(const cv::Mat& frame) {
  cv::Mat f;
  frame.convertTo(f, CV_64F);
  // Pairs near black or the clip are left out: their noise is cut (a dark backdrop read at
  // ~1 grey level with noise 2 would halve the estimate).
  const double full = frame.depth() == CV_8U ? 255.0 : 65535.0;
  const double lo = kNoiseLevelMargin * full, hi = full - lo;
  std::vector<double> d;
  d.reserve(size_t(f.rows) * size_t(f.cols));
  for (int r = 0; r < f.rows; ++r) {
    const double* p = f.ptr<double>(r);
    for (int c = 0; c + 1 < f.cols; ++c) {
      if (std::min(p[c], p[c + 1]) >= lo && std::max(p[c], p[c + 1]) <= hi) {
        d.push_back(p[c + 1] - p[c]);
      }
    }
  }
  if (d.size() < kMinNoisePairs) return std::numeric_limits<double>::quiet_NaN();
  // A difference of two N(0, s^2) pixels is N(0, 2 s^2). First a robust scale (the median of
  // |d|, 0.6745 s sqrt(2)): on 8-bit frames it is an integer or a half, up to 17 % off at s = 3;
  // then the RMS of the differences within 4 of those sigmas (edges left out), which counts the
  // rounding as the noise it is.
  std::vector<double> a;
  a.reserve(d.size());
  for (double v : d) a.push_back(std::abs(v));
  const double rough = MedianOf(a) / 0.6745;  // sigma of d
  const double cut = kNoiseCutSigmas * rough + 0.5;
  double sum2 = 0;
  size_t n = 0;
  for (double v : d) {
    if (std::abs(v) <= cut) sum2 += v * v, ++n;
  }
  if (n < kMinNoisePairs) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(sum2 / double(n) / 2.0);
}

Eigen::Vector2d TranslationBound(const Appearance& a, double noise_sigma) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!a.valid() || !(noise_sigma > 0)) return {nan, nan};
  double gx2 = 0, gy2 = 0;
  for (int y = 1; y + 1 < a.image.rows; ++y) {
    for (int x = 1; x + 1 < a.image.cols; ++x) {
      const auto m = [&](int yy, int xx) { return a.mask.at<uint8_t>(yy, xx) != 0; };
      if (!(m(y, x) && m(y, x - 1) && m(y, x + 1) && m(y - 1, x) && m(y + 1, x))) continue;
      const double gx = 0.5 * (a.image.at<float>(y, x + 1) - a.image.at<float>(y, x - 1));
      const double gy = 0.5 * (a.image.at<float>(y + 1, x) - a.image.at<float>(y - 1, x));
      gx2 += gx * gx;
      gy2 += gy * gy;
    }
  }
  if (!(gx2 > 0) || !(gy2 > 0)) return {nan, nan};
  return {noise_sigma / std::sqrt(gx2), noise_sigma / std::sqrt(gy2)};
}

}  // namespace dimer::tracking
