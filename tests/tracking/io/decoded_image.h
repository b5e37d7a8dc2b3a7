#pragma once
// What the direct decoder tests (BMP, TIFF) compare against: OpenCV's own decoding of the same
// bytes, exact equality of type, size and every pixel, and seeded random frames.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdint>
#include <vector>

namespace dimer::tracking {

inline cv::Mat OpenCvGrey(const std::vector<uint8_t>& b) {
  return cv::imdecode(b, cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
}

inline bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Uniform over the type's whole range (8- or 16-bit).
inline cv::Mat Random(int w, int h, int type, uint64_t seed) {
  cv::Mat m(h, w, type);
  cv::RNG(seed).fill(m, cv::RNG::UNIFORM, 0, type == CV_16UC1 ? 65536 : 256);
  return m;
}

}  // namespace dimer::tracking
