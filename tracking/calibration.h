#pragma once
// Stage "calibrate": pixels to metres for a tracked film. The scale is --m-per-px when given,
// else the dimer's length with --ar (dimer_length_scale.h), else the sphere's diameter over its
// radius measured; z = 0 is --row0 or the plate's median row; with a sloping plate edge
// (plate_slope.h) the axes turn with it.
#include <cstddef>
#include <limits>

#include <Eigen/Core>

#include "tracking/dimer_length_scale.h"
#include "tracking/track_args.h"
#include "tracking/track_sequence.h"

namespace dimer::tracking {

// Pixels to metres. With a sloping plate edge (plate_slope.h) the axes turn with it: x along
// the plate, z along its normal, about the plate's mean row `row0` at the frame's centre column
// `col0`; with a level plate, x = col m_per_px and z = (row0 - row) m_per_px.
struct Calibration {
  double m_per_px = std::numeric_limits<double>::quiet_NaN();
  double row0 = std::numeric_limits<double>::quiet_NaN();
  double col0 = 0, cos_a = 1, sin_a = 0;  // pivot column; the slope's angle
  // The track's median centre distance (offsets applied) and its frames: the scale with --ar
  // and no --m-per-px, a check with both.
  double length_px = std::numeric_limits<double>::quiet_NaN();
  size_t length_frames = 0;
  LengthScale length_scale;  // the passes that chose the radius tracked with (--ar alone)
  Eigen::Vector2d ToMetres(const Eigen::Vector2d& px) const {
    const double dc = px.x() - col0, dr = px.y() - row0;
    return m_per_px * Eigen::Vector2d(col0 + dc * cos_a + dr * sin_a, dc * sin_a - dr * cos_a);
  }
};

// Throws InputError where nothing calibrates the film (no sphere found, too few frames showing
// both for --ar). `passes`: what --ar's passes settled on (empty without --ar alone).
Calibration Calibrate(const TrackArgs& args, const SequenceResult& r, const LengthScale& passes);

}  // namespace dimer::tracking
