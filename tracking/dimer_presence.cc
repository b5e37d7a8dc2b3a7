#include "tracking/dimer_presence.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/format.h"
#include "common/median.h"

namespace dimer::tracking {

DimerPresence MeasureDimerPresence(const SequenceResult& r) {
  DimerPresence p;
  p.frames = r.frames.size();
  std::vector<double> lengths;
  for (const FrameTrack& f : r.frames) {
    if (f.found[0] && f.found[1]) {
      lengths.push_back((f.centre[1] - f.centre[0]).norm());
    } else if (f.found[0] || f.found[1]) {
      ++p.one;
    }
  }
  p.both = lengths.size();
  if (lengths.empty()) return p;
  p.length_px = MedianOf(lengths);
  const double tolerance =
      std::max(kDimerLengthTolerancePx, kDimerLengthToleranceFraction * p.length_px);
  p.dimer = size_t(std::count_if(lengths.begin(), lengths.end(), [&](double d) {
    return std::abs(d - p.length_px) <= tolerance;
  }));
  return p;
}

std::string NoDimerMessage(const DimerPresence& p) {
  return Format("no dimer: two spheres a constant distance apart in %zu of %zu frames (%.0f %% "
                "needed); found two objects in %zu (any distance), one in %zu, none in %zu; "
                "track the frames that show the dimer (--frames)",
                p.dimer, p.frames, 100.0 * kMinDimerFraction, p.both, p.one,
                p.frames - p.both - p.one);
}

}  // namespace dimer::tracking
