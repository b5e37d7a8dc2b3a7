#include "tracking/io/cine_time_stamps.h"

#include "tracking/io/cine_layout.h"

namespace dimer::tracking {
namespace {

uint64_t Le(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int k = 0; k < bytes; ++k) v |= uint64_t(p[k]) << (8 * k);
  return v;
}

}  // namespace

std::vector<double> CineFrameTimes(const uint8_t* blocks, size_t n, size_t image_count) {
  using namespace cine;
  size_t at = 0;
  while (n - at >= size_t(kTagHeaderSize)) {
    const uint64_t size = Le(blocks + at, 4);
    const auto type = uint16_t(Le(blocks + at + 4, 2));
    if (size < uint64_t(kTagHeaderSize) || size > n - at || type == kTagRangeData) break;
    if (type == kTagTimeOnly && (size - kTagHeaderSize) / 8 == image_count &&
        (size - kTagHeaderSize) % 8 == 0 && image_count > 0) {
      // TIME64: a 32-bit fraction of a second (2^-32 s) then 32-bit seconds; differences in
      // those integer units keep the precision a double of seconds since 1970 would lose
      // (0.2 us, 2 % of a frame at 90,000 frames/s).
      const uint8_t* data = blocks + at + kTagHeaderSize;
      const uint64_t first = Le(data + 4, 4) << 32 | Le(data, 4);
      std::vector<double> times(image_count);
      uint64_t previous = first;
      for (size_t i = 0; i < image_count; ++i) {
        const uint64_t t = Le(data + 8 * i + 4, 4) << 32 | Le(data + 8 * i, 4);
        if (i > 0 && t <= previous) return {};
        previous = t;
        times[i] = double(t - first) / 4294967296.0;
      }
      return times;
    }
    at += size_t(size);
  }
  return {};
}

double FrameRateOfTimes(const std::vector<double>& times) {
  if (times.size() < 2 || !(times.back() > times.front())) return 0;
  return double(times.size() - 1) / (times.back() - times.front());
}

}  // namespace dimer::tracking
