#pragma once
// The observables the coefficient fit compares (fit.h), taken from one analysis, dimensionless
// (velocities in units of g/f, phases in periods), each with its standard error. A track and a
// trial simulation give lists with the same names when they settle in the same mode.
#include <string>
#include <vector>

#include "compare/analysis.h"

namespace dimer::compare {

struct Observable {
  std::string name;
  double value = kNaN, err = kNaN;
  double floor = 0;  // systematic floor added in quadrature (analysis resolution)
  int slip_bin = -1;  // the phase bin of a slip_bin_<k> observable; -1 for the others
};

// The observables of `a` read as the mode `mode` (empty: a's own settled mode), so that a
// trial simulation that settles elsewhere still yields the same list, only far off: first the
// mode's own statistics (impacts per period and rest fractions of the bouncing and resting
// ends; of each sphere for jump and flutter), which grade how far a trial is from the mode.
// In drift the bouncing end is a's, or, if a is not in drift, the sphere that rests least.
// `impact_phase` (NaN: a's own) is where the slip bins next to the bouncing end's impact are
// left out; a trial simulation is given the track's, so both leave out the same bins.
std::vector<Observable> FitObservables(const Analysis& a, const std::string& mode = "",
                                       double impact_phase = kNaN);

// The observables a fit compares against: FitObservables(track), less each slip bin in which
// the resting sphere is on the plate on fewer than half of its frames of the settled window (a
// bin of lift-off). Such a bin averages the few frames that happen to be in contact, and a trial
// near the truth keeps it in some samplings and not in others: on fit_study_tracked.sh's
// mirror-lit A_r 6.0 (bins of 4 and 8 frames of 98) the missing bins added 25 each to chi2
// (FitObservables.*).
std::vector<Observable> TrackObservables(const Analysis& track);

}  // namespace dimer::compare
