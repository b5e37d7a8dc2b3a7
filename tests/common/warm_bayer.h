#pragma once
// What a colour camera's raw sensor records of a grey 8-bit frame under a warm lamp: an RGGB
// Bayer mosaic whose red, green and blue pixels see 1, 0.8 and 0.55 of the light (the tests of
// colour .cine files: tracking/io/mosaic_grey.h). Header-only: shared by test programs that link
// different libraries.
#include <opencv2/core.hpp>

namespace dimer::testing {

inline cv::Mat WarmBayerMosaic(const cv::Mat& grey) {
  CV_Assert(grey.type() == CV_8UC1);
  cv::Mat m(grey.size(), CV_8UC1);
  for (int r = 0; r < grey.rows; ++r) {
    for (int c = 0; c < grey.cols; ++c) {
      const int phase = 2 * (r % 2) + c % 2;  // RGGB: 0 red, 1 and 2 green, 3 blue
      const double gain = phase == 0 ? 1.0 : phase == 3 ? 0.55 : 0.8;
      m.at<uint8_t>(r, c) = cv::saturate_cast<uint8_t>(gain * grey.at<uint8_t>(r, c));
    }
  }
  return m;
}

}  // namespace dimer::testing
