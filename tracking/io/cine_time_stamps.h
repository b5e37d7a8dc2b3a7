#pragma once
// The per-image time stamps of a Phantom .cine file: the TIME_ONLY tagged block (cine_layout.h)
// that Phantom's software writes between SETUP and the image offset table. They are the times
// the saved images were taken, so they give the rate between the frames actually saved: a film
// recorded at 90,000 frames/s and saved with a decimation of 10 says 90,000 in its header and
// 9,000 in its time stamps.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dimer::tracking {

// Parses the tagged blocks in `blocks` (n bytes) and returns each of the `image_count` images'
// time in seconds after the first image's. Empty when there is no TIME_ONLY block of exactly
// `image_count` entries, or when its times do not strictly increase (a damaged block is ignored:
// the header's rate is then used).
std::vector<double> CineFrameTimes(const uint8_t* blocks, size_t n, size_t image_count);

// Frames per second over the times: (count - 1) / (last - first); 0 with fewer than 2 times.
double FrameRateOfTimes(const std::vector<double>& times);

}  // namespace dimer::tracking
