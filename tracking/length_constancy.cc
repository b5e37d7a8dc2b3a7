#include "tracking/length_constancy.h"

#include <algorithm>
#include <cmath>

#include "common/median.h"

namespace dimer::tracking {

std::vector<double> DimerLengths(const std::vector<FrameTrack>& frames) {
  std::vector<double> len;
  len.reserve(frames.size());
  for (const FrameTrack& f : frames) {
    len.push_back(f.whole(0) && f.whole(1) ? (f.centre[1] - f.centre[0]).norm()
                                           : std::numeric_limits<double>::quiet_NaN());
  }
  return len;
}

LengthConstancy JudgeLengthConstancy(const std::vector<FrameTrack>& frames) {
  LengthConstancy c;
  const std::vector<double> len = DimerLengths(frames);
  std::vector<double> found, second;
  for (size_t i = 0; i < len.size(); ++i) {
    if (std::isfinite(len[i])) found.push_back(len[i]);
    // Consecutive frames of the track, all three with the length (a skipped frame breaks it).
    if (i >= 2 && std::isfinite(len[i]) && std::isfinite(len[i - 1]) && std::isfinite(len[i - 2]) &&
        frames[i].index == frames[i - 2].index + 2) {
      second.push_back(std::abs(len[i] - 2 * len[i - 1] + len[i - 2]));
    }
  }
  c.frames = found.size();
  if (found.size() < kLengthMinFrames || second.size() < kLengthMinFrames) return c;
  c.median_px = MedianOf(found);
  c.noise_px = MedianOf(second) / 0.6745 / std::sqrt(6.0);
  c.tolerance_px = std::max(kLengthDepartMinPx, kLengthNoiseSigmas * c.noise_px);
  double worst = 0;
  for (size_t i = 0; i < len.size(); ++i) {
    if (!std::isfinite(len[i])) continue;
    const double d = std::abs(len[i] - c.median_px);
    worst = std::max(worst, d);
    if (d <= c.tolerance_px) continue;
    if (c.departing++ == 0) c.first = i;
    c.last = i;
  }
  c.worst_px = worst;
  return c;
}

}  // namespace dimer::tracking
