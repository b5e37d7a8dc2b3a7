#include "tracking/sphere/pixel_window.h"

#include <cmath>
#include <cstdint>

namespace dimer::tracking {
namespace {

template <typename T>
void Copy(const cv::Mat& frame, int polarity, PixelWindow* w) {
  for (int y = 0; y < w->size; ++y) {
    const T* src = frame.ptr<T>(w->row0 + y) + w->col0;
    float* dst = &w->v[size_t(y) * w->size];
    for (int x = 0; x < w->size; ++x) dst[x] = float(polarity * int(src[x]));
  }
}

}  // namespace

bool ExtractWindow(const cv::Mat& frame, const Eigen::Vector2d& centre, int half, int polarity,
                   PixelWindow* w) {
  w->col0 = int(std::lround(centre.x())) - half;
  w->row0 = int(std::lround(centre.y())) - half;
  w->size = 2 * half + 1;
  if (w->col0 < 0 || w->row0 < 0 || w->col0 + w->size > frame.cols ||
      w->row0 + w->size > frame.rows) {
    return false;
  }
  w->v.resize(size_t(w->size) * w->size);
  if (frame.depth() == CV_8U) {
    Copy<uint8_t>(frame, polarity, w);
  } else {
    Copy<uint16_t>(frame, polarity, w);
  }
  return true;
}

}  // namespace dimer::tracking
