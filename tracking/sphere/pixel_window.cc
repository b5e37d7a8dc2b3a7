#include "tracking/sphere/pixel_window.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dimer::tracking {
namespace {

// The window's pixels times `polarity`; `clamped`: the window leaves the frame, and its pixels
// beyond the edge repeat the nearest edge pixel.
template <typename T>
void Copy(const cv::Mat& frame, int polarity, bool clamped, PixelWindow* w) {
  for (int y = 0; y < w->size; ++y) {
    float* dst = &w->v[size_t(y) * w->size];
    if (!clamped) {
      const T* src = frame.ptr<T>(w->row0 + y) + w->col0;
      for (int x = 0; x < w->size; ++x) dst[x] = float(polarity * int(src[x]));
      continue;
    }
    const T* src = frame.ptr<T>(std::clamp(w->row0 + y, 0, frame.rows - 1));
    for (int x = 0; x < w->size; ++x) {
      dst[x] = float(polarity * int(src[std::clamp(w->col0 + x, 0, frame.cols - 1)]));
    }
  }
}

}  // namespace

bool ExtractWindow(const cv::Mat& frame, const Eigen::Vector2d& centre, int half, int polarity,
                   PixelWindow* w, int inside) {
  const int col = int(std::lround(centre.x())), row = int(std::lround(centre.y()));
  w->col0 = col - half;
  w->row0 = row - half;
  w->size = 2 * half + 1;
  const bool clamped = w->col0 < 0 || w->row0 < 0 || w->col0 + w->size > frame.cols ||
                       w->row0 + w->size > frame.rows;
  const int in = inside < 0 ? half : std::min(inside, half);
  if (clamped && (col - in < 0 || row - in < 0 || col + in >= frame.cols || row + in >= frame.rows)) {
    return false;
  }
  w->v.resize(size_t(w->size) * w->size);
  if (frame.depth() == CV_8U) {
    Copy<uint8_t>(frame, polarity, clamped, w);
  } else {
    Copy<uint16_t>(frame, polarity, clamped, w);
  }
  return true;
}

}  // namespace dimer::tracking
