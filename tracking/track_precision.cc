#include "tracking/track_precision.h"

#include <cmath>

#include "tracking/sphere/impact_vertex.h"

namespace dimer::tracking {

std::array<SpherePrecision, 2> MeasurePrecision(const std::vector<FrameTrack>& frames,
                                                const std::array<Eigen::Vector2d, 2>& bound) {
  std::array<SpherePrecision, 2> out;
  const double length_measured = GapNoise(DimerLengthSeries(frames));
  const bool length_holds = length_measured <= kNotFollowedMinPx;  // false for NaN
  for (int k = 0; k < 2; ++k) {
    SpherePrecision& p = out[k];
    p.bound = bound[k];
    p.length_measured = length_measured;
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<double> v;
      v.reserve(frames.size());
      for (const FrameTrack& f : frames) {
        v.push_back(f.whole(k) ? f.centre[k][axis] : std::numeric_limits<double>::quiet_NaN());
      }
      // The second difference of a flight or a rest is ~0.01 px at most (gravity at 0.2 mm/px,
      // 2000 frames/s); an impact's kink is a few frames of hundreds, which the median passes.
      p.measured[axis] = GapNoise(v);
      // Without a bound (the silhouette methods) the scatter and the length decide alone.
      const bool beyond_bound = !(p.bound[axis] >= 0) ||
                                p.measured[axis] > kNotFollowedFactor * p.bound[axis];
      if (beyond_bound && p.measured[axis] > kNotFollowedMinPx) {
        if (length_holds) {
          p.uneven_motion = true;
        } else {
          p.followed = false;
        }
      }
      if (p.bound[axis] > kPoorFootageBoundPx) p.poor = true;
    }
  }
  return out;
}

}  // namespace dimer::tracking
