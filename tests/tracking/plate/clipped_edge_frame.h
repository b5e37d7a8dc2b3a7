#pragma once
// A plate edge as the POV-Ray footage makes it (tests/footage/povray_footage.cc): the scene
// box-sampled (dark 0 above row `edge`, 128 x gain below), a Gaussian blur of sigma `psf` px,
// noise sigma 2, rounded and clipped to 8 bits. Shared by tests/tracking/plate/plate_edge_test.cc and
// bench/bench_plate_edge.cc (--psf-sensitivity).
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

namespace dimer::tracking {

inline cv::Mat ClippedBlurredEdge(double edge, double gain, double psf, uint64_t seed) {
  cv::Mat f(120, 320, CV_32F);
  for (int row = 0; row < f.rows; ++row) {
    f.row(row).setTo(128.0 * gain * std::clamp(row + 0.5 - edge, 0.0, 1.0));
  }
  const int k = 2 * int(std::ceil(3 * psf)) + 1;
  cv::GaussianBlur(f, f, cv::Size(k, k), psf, psf, cv::BORDER_REFLECT_101);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 2.0);
  cv::Mat out(f.size(), CV_8U);
  for (int row = 0; row < f.rows; ++row) {
    for (int col = 0; col < f.cols; ++col) {
      out.at<uint8_t>(row, col) =
          uint8_t(std::clamp(std::round(f.at<float>(row, col) + noise(rng)), 0.0, 255.0));
    }
  }
  return out;
}

}  // namespace dimer::tracking
