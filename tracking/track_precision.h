#pragma once
// How precisely `track` followed each sphere, said to the user: the centres' scatter from frame
// to frame, measured on the track itself (the median second difference, impact_vertex.h's
// GapNoise), beside the footage's own bound for the template method (the Cramér-Rao bound of
// the learnt appearance in the first frame's noise, precision_bound.h). Where the scatter is
// far above the bound the tracker is not following the sphere as the footage allows: on a
// POV-Ray film at a quarter of the light and 0.4 mm/px (spheres of 11.9 px) both spheres were
// "found" in 95-99 % of the frames and more than a pixel off in 44 and 75 % of them, with no
// word of it (see povray.precision).
#include <Eigen/Core>
#include <array>
#include <limits>
#include <vector>

#include "tracking/frame_follower.h"

namespace dimer::tracking {

// A sphere is reported as not followed where its measured scatter is above this many times
// the bound on either axis and above kNotFollowedMinPx (a matte sphere's bound, 0.005 px, is
// met at 0.02: the method's own error is a few hundredths of a pixel whatever the footage).
inline constexpr double kNotFollowedFactor = 4.0;
inline constexpr double kNotFollowedMinPx = 0.15;
// The footage itself is too poor for sub-pixel work where the bound on either axis is above
// this, px: three times the 0.05 px target. The POV-Ray test footage's bounds are
// 0.003-0.09 px per axis; the quarter-light film at 0.4 mm/px, 0.26-0.31 px, and there the
// offsets estimated from the same footage were 0.7 and 1.5 px off, stating 0.08-0.16.
inline constexpr double kPoorFootageBoundPx = 0.15;

struct SpherePrecision {
  // Frame-to-frame scatter of the centre (col, row), px; NaN with fewer than 3 triples of
  // consecutive found frames.
  Eigen::Vector2d measured{std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::quiet_NaN()};
  // The footage's bound (col, row), px; NaN where not known (not the template method, a
  // frame too small or clipped for its noise).
  Eigen::Vector2d bound{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
  // The dimer's length from frame to frame (the same measure on the centres' distance where
  // both are found), px; NaN with fewer than 3 triples. It does not depend on the pose, so it
  // tells the motion's unevenness from the tracker's: separate poses of a calibration film, or a
  // jolt, scatter the centres and leave the length as it is.
  double length_measured = std::numeric_limits<double>::quiet_NaN();
  // false: measured beyond kNotFollowedFactor x bound (where the bound is known) and
  // kNotFollowedMinPx, and the length too beyond kNotFollowedMinPx (or unknown). Without a bound
  // the rigid dimer decides: on the ruler's 100-frame POV-Ray film, frames 20-40, auto ran the
  // centroid (the template found both spheres in none of its trial frames), whose centres were
  // 9-15 px off, scattering 0.84 / 0.18 px with the length 0.86 px, and nothing was said
  // (TrackPrecision.WithoutABoundTheLengthDecides).
  bool followed = true;
  // Measured beyond those while the length holds within kNotFollowedMinPx: the centres move
  // unevenly, the tracker follows them (TrackPrecision.SeparatePosesAreMotionNotScatter).
  bool uneven_motion = false;
  bool poor = false;     // the bound beyond kPoorFootageBoundPx
};

// The measured scatter of each sphere's centres in `frames` (frame order), with `bound` (per
// sphere, px; NaN: unknown) beside it.
std::array<SpherePrecision, 2> MeasurePrecision(const std::vector<FrameTrack>& frames,
                                                const std::array<Eigen::Vector2d, 2>& bound);

}  // namespace dimer::tracking
