#pragma once
// The tracker's error that repeats with the drive's phase, measured from the film's own
// referees and carried into the fit's errors (fit.h).
//
// A settled orbit puts a sphere at the same height at the same drive phase every period, so an
// error that depends on where the sphere sits on the pixel grid (or on the plate's edge beside
// it) is the same every period: averaging periods does not shrink it, and no standard error
// counts it. On fit_study_tracked.sh's mirror-lit A_r 4.8 film the rows' error averaged by
// drive phase spreads 0.007-0.008 px, six times what averaging its noise would leave; the slip
// bins then miss a simulation of the truth by 2.7 of their standard errors rms (3.6 on the
// backlit film, whose columns' error is locked the same way), and fits state ranges that miss
// the truth (docs/BENCHMARKS.md, fit_study_tracked.sh).
//
// Two things on the film do not move with the drive, and their phase averages say how large
// that error is:
//   - the dimer's length (rigid): its spread over drive phase, less its noise's share, is the
//     two centres' error along the rod, each sphere's column taking half its variance;
//   - the resting sphere's height above the plate while it stays on the plate: it can only rise
//     off the plate (a hop too small for the contact threshold), never sink, so the spread of
//     its phase averages below their core (the median of those not raised by hops), less the
//     noise's share, is the rows' error.
// Where no sphere rests long enough (jump, flutter) the rows are given the columns' figure.
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "compare/fit_observables.h"

namespace dimer::compare {

struct LockedError {
  int phase_bins = 0;          // bins of the drive's phase the averages are taken in
  double col_m = 0;            // each sphere's column (x) error locked to the phase, sd, m
  double row_m = 0;            // each sphere's row (z) error locked to the phase, sd, m
  int length_bins = 0;         // bins the length's estimate rests on (0: none)
  int rest_bins = 0;           // bins of steady contact the rows' estimate rests on (0: none)
  std::string row_source;      // "resting_height", or "length" (rows given the columns' figure)
};

// Measured over `a`'s settled window (its whole run when nothing settled).
LockedError MeasureLockedError(const Analysis& a);

// Each row: how `observed` (TrackObservables of `track`) moves when the track's centres are
// moved by one draw of locked errors of `e`'s size (white over its phase bins, each sphere and
// axis drawn alone, a fixed seed) and the track is analysed again as it was (its thresholds and
// slip filter); 0 where either value is not finite. Empty when `e` is zero.
std::vector<std::vector<double>> LockedErrorDeviations(const Analysis& track, const LockedError& e,
                                                       const std::vector<Observable>& observed,
                                                       int draws);

}  // namespace dimer::compare
