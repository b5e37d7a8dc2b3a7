#pragma once
// What the frames and the flights say of the plate's tilt, for the report and stderr. A camera
// that is not level and a plate tilted on purpose both slope the plate's edge in the frames,
// and `track` runs the metres along the plate either way; only the flights (free_fall.h) tell
// the two apart, so the simulation's tilt is the user's to give (`--tilt-deg`, or a sim file's).
#include <string>
#include <vector>

#include "compare/analysis.h"

namespace dimer::compare {

// A tilt from the flights this far (deg, and 3 of its sigma) from the simulation's is noted.
inline constexpr double kTiltNoteDeg = 0.3;

// Notes on `track`: the edge's slope where `track` applied one; the flights' tilt where it
// differs from `sim_tilt_deg`, the simulation's (NaN: nothing is compared).
std::vector<std::string> TiltNotes(const Analysis& track, double sim_tilt_deg);

}  // namespace dimer::compare
