#pragma once
// A track (or any trajectory) beside a simulation of the same scene: aligned in time by the
// plate phase (the candidate shift, in whole periods, that puts the track's end at the
// simulation's end, so a simulation with a transient is compared in its steady part), in space
// by an x offset (mean CM difference) and a mirror image when the bouncing end is the left one
// in one and the right one in the other (identities swapped with it), and in height relative
// to each plate's mean surface. Then residuals of each tip, and the two analyses' headline
// figures side by side.
#include <array>
#include <string>
#include <vector>

#include "compare/analysis.h"

namespace dimer::compare {

struct Comparison {
  std::string sim_path;          // the simulation's file (or "simulated" when run in memory)
  double time_offset_s = kNaN;   // t_sim = t_track + time_offset_s
  double x_offset_m = kNaN;      // x_track = x_sim' + x_offset_m (x_sim' mirrored if needed)
  bool mirrored = false;         // sim mirrored (x -> -x, left <-> right)
  // Per track frame (NaN where either is missing or outside the simulation):
  std::vector<double> t;                       // track time, s
  std::array<std::vector<double>, 2> sim_x, sim_z;  // aligned simulated tips (track frame), m
  std::array<std::vector<double>, 2> res_x, res_z;  // track - simulation, m
  std::array<double, 2> rms_x{kNaN, kNaN}, rms_z{kNaN, kNaN};  // over the settled window, m
  int frames_compared = 0;
  bool modes_agree = false;      // settled labels equal
  Analysis sim;                  // the simulation analysed with the same code
};

// InputError (naming both files) when they cannot describe the same experiment: A_r differing
// by more than 3 %, sample rates or drive frequencies differing by more than 1 %.
// `sim` is kept in the result (passed by value: move a temporary in).
Comparison CompareWithSimulation(const Analysis& track, Analysis sim);

}  // namespace dimer::compare
