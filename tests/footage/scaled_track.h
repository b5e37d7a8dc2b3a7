#pragma once
// A footage folder tracked the way a user runs `dimerlab track` (tracking/run_track.h RunTrack, the
// command's whole path: the track file written and read back), with the scale given
// (--m-per-px), from the dimer's length (--ar) or from the spheres' size (neither), and each
// sphere's mean error against the folder's truth.csv: what the scale's origin does to the
// scale and to the rows, which rest on the sphere radius it implies (see
// povray.dimer_length.CASE).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>

namespace dimer::footage {

struct ScaledTrack {
  double m_per_px = 0;        // the track file's
  double m_per_px_given = -1; // its code: 0 from --diameter, 1 given, 2 from --ar
  double ar_passes = 0;       // the calibration passes --ar ran
  double seconds = 0;         // the whole command, wall
  std::array<Eigen::Vector2d, 2> bias{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};  // mean
  std::array<size_t, 2> found{0, 0};  // frames each sphere was found in
};

// Tracks `folder` into `output` (replaced) with `m_per_px` and `ar` (NaN: not given), `auto`.
ScaledTrack TrackScaled(const std::string& folder, const std::string& output, double m_per_px,
                        double ar);

}  // namespace dimer::footage
