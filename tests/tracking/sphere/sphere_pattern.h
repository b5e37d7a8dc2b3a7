#pragma once
// A smooth sphere-like pattern for the template locators' tests (template_locator_test.cc,
// fast_follow_test.cc): a soft disc (edge blurred over ~1 px), dimmer upper half, a bright lower
// crescent and two highlights; nothing symmetric about the centre, so a position error cannot
// hide. Pixel (col, row) samples it at the pixel centre.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking::testing {

inline constexpr double kPatternRadius = 20.0;

// The two highlights' peak levels.
struct Highlights {
  double first = 180, second = 140;
};

inline double SpherePattern(double col, double row, double cx, double cy, Highlights h = {}) {
  const double dx = col - cx, dy = row - cy;
  const double r = std::sqrt(dx * dx + dy * dy);
  const double disc = 1.0 / (1.0 + std::exp((r - kPatternRadius) / 0.6));
  const double body = 20.0 + (dy > 0 ? 60.0 * std::min(1.0, dy / 6.0) : 0.0);
  auto spot = [&](double x0, double y0, double a) {
    return a * std::exp(-((dx - x0) * (dx - x0) + (dy - y0) * (dy - y0)) / (2 * 1.2 * 1.2));
  };
  return 10.0 + disc * body + spot(-6, -9, h.first) + spot(5, -7, h.second);
}

// A w x h 8-bit frame of the pattern at (cx, cy) seen with `gain` and `offset`, Gaussian noise
// `noise` (seeded), a bright plate (150) below `plate_row` (NaN: none).
inline cv::Mat RenderPattern(int w, int h, double cx, double cy, double gain, double offset,
                             double noise, uint64_t seed, double plate_row = NAN,
                             Highlights spots = {}) {
  cv::Mat img(h, w, CV_8U);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double v = std::isfinite(plate_row) && y > plate_row
                     ? 150.0
                     : gain * SpherePattern(x, y, cx, cy, spots) + offset;
      if (noise > 0) v += noise * n(rng);
      img.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(std::lround(v));
    }
  }
  return img;
}

// The exact appearance, its reference point at the pattern's centre.
inline Appearance ExactPattern(Highlights spots = {}) {
  Appearance a;
  a.radius_px = kPatternRadius;
  a.half = int(std::ceil(kPatternRadius + 4));
  const int size = 2 * a.half + 1;
  a.image = cv::Mat(size, size, CV_32F);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      a.image.at<float>(y, x) = float(SpherePattern(x, y, a.half, a.half, spots));
    }
  }
  a.mask = cv::Mat::ones(size, size, CV_8U);
  return a;
}

}  // namespace dimer::tracking::testing
