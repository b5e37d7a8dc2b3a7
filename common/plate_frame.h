#pragma once
// A tilted plate's trajectory turned into the plate's own frame: x along the plate's mean
// surface, z along its normal, both about the lab origin (which lies on that surface). This is
// the frame `track` measures in when the plate's edge slopes in the image, so a simulation of a
// tilted plate (written in the lab frame, x horizontal) is compared, rendered and analysed in it.
// Gaps, drift and slip along the plate are then read directly; the plate's height under the
// dimer becomes its displacement along the normal, the same at every x.
#include <array>

#include "common/trajectory.h"

namespace dimer {

// tilt_deg: the plate's inclination (> 0 rising toward +x), as `sim --tilt-deg`. 0 returns `lab`
// as it is (taken by value and turned in place: a level file costs no copy when moved in).
// The lab plate height is taken under the midpoint of the two tips (the centre of mass).
Trajectory InPlateFrame(Trajectory lab, double tilt_deg);

// A lab state (x, z, theta, u, v, omega) in the same fixed, turned frame (velocities relative to
// the lab, not to the moving plate).
std::array<double, 6> StateInPlateFrame(const std::array<double, 6>& lab, double tilt_deg);

}  // namespace dimer
