#include "tracking/match_scores.h"

#include <algorithm>
#include <cmath>

#include "common/median.h"

namespace dimer::tracking {

MatchScores DropOutlyingMatches(std::vector<FrameTrack>* frames) {
  MatchScores out;
  for (int k = 0; k < 2; ++k) {
    std::vector<double> s;
    for (const FrameTrack& f : *frames) {
      if (f.whole(k) && std::isfinite(f.score[k])) s.push_back(f.score[k]);
    }
    if (s.size() < kMinScoredFrames) continue;
    const double median = MedianOf(s);
    for (double& x : s) x = std::abs(x - median);
    const double sigma = 1.4826 * MedianOf(s);
    out.median[k] = median;
    out.floor[k] = median - std::max(kScoreDropSigmas * sigma, kMinScoreDrop);
    for (FrameTrack& f : *frames) {
      if (f.found[k] && std::isfinite(f.score[k]) && f.score[k] < out.floor[k]) {
        f.Drop(k);
        ++out.dropped[k];
      }
    }
  }
  // The dimer's length.
  std::vector<double> len;
  for (const FrameTrack& f : *frames) {
    if (f.whole(0) && f.whole(1)) len.push_back((f.centre[1] - f.centre[0]).norm());
  }
  if (len.size() < kMinScoredFrames) return out;
  const double median = MedianOf(len);
  for (double& x : len) x = std::abs(x - median);
  const double tolerance = std::max(kLengthTolerancePx, kLengthSigmas * 1.4826 * MedianOf(len));
  out.length_px = median;
  for (FrameTrack& f : *frames) {
    if (!(f.found[0] && f.found[1])) continue;
    if (std::abs((f.centre[1] - f.centre[0]).norm() - median) <= tolerance) continue;
    // The sphere less like itself: its score furthest below its median (none: furthest).
    auto below = [&](int k) {
      return std::isfinite(f.score[k]) && std::isfinite(out.median[k])
                 ? out.median[k] - f.score[k]
                 : std::numeric_limits<double>::infinity();
    };
    const int k = below(1) > below(0) ? 1 : 0;
    f.Drop(k);
    ++out.dropped_length[k];
  }
  return out;
}

}  // namespace dimer::tracking
