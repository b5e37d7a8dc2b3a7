#pragma once
// Fitting the contact coefficients by simulation: the scene the track shows is simulated with
// trial coefficients, the simulation is analysed with the same code as the track, and the
// observables are compared with their uncertainties:
//   the drift speed <u> f / g; the bouncing end's mean take-off speed and apparent restitution
//   (v_after / -v_before) and its mean impact phase; the phase-averaged slip profile and the
//   slip after / before the bouncing end's impact. (Jump/flutter: each sphere's take-off speed
//   and impact phase.)
//   chi2 = r^T (D + V V^T)^-1 r, r = sim - track, D = diag(sigma_track^2 + sigma_sim^2 +
// floor^2 + 2 s^2), V V^T the covariance the tracker's error locked to the drive's phase gives
// the observables (measured on the track: locked_error.h; zero for a sim file, where chi2 is
// the plain sum of squares), and
// s the observable's spread over trials whose frames fall at other instants of the motion (the
// release moved by fractions of a frame; fit.cc, AddScatter), estimated at the start, at the
// paper's coefficients and at the optimum: a slip bin that holds a jump of U moves in steps as
// the jump crosses a frame time, and a chaotic drift gives another realisation at eps + 1e-9, so
// that without s chi2 jumps by tens between neighbouring coefficients and the search stops on a
// step (bench_fit_study: "no acceptable fit" on 5 of its 12 fits, ranges missing the truth on 1;
// Fit.FindsADriftWhoseSlipBinsMoveInSteps).
// The optimiser is NLopt's bounded Nelder-Mead, run from the start (the coefficients the user
// gives, --eps etc., as given), from the paper's coefficients when those differ, and from the
// best of a multi-start search (NLopt MLSL over a Sobol sequence), keeping the best; derivative-free and deterministic (the objective is
// piecewise smooth, with jumps where the impact type changes or the release falls into another
// orbit, and has local minima: a start far from the truth can end in one, which the goodness of
// fit then shows). The start is never replaced by a value read off the track: the bouncing
// end's apparent restitution (v_after / -v_before of its centre, 0.558 on a scene of eps 0.55)
// is not eps, and started there the search does not find its way back to the truth: chi2 778
// at its end against 0 at the truth (Fit.StartedAtTheTruthStaysThere).
// Goodness of fit: chi2/dof and its p-value (goodness_of_fit.h). Below kMinFitPValue the
// profiles (below) are searched for a lower point, and the fit moves there if one is lower by
// more than the range's threshold (fit_search.h, JudgeAndMove: FitSearch.*); still below, it is
// "no acceptable fit": no coefficient is constrained, the best point is reported only as the
// point that fails, with the observables furthest off. Otherwise uncertainties and
// identifiability come from the profile of chi2 along each parameter (the others re-optimised
// at each value): the range where chi2 <= chi2_min + max(1, chi2_min / dof, chi2's roughness at
// the optimum: its spread between coefficients 1e-7 of their ranges apart, where a chaotic orbit
// changes realisation; a smaller rise is not resolved). Not chi2's spread between the samplings:
// with their spread in the errors, chi2 moves between samplings by its own statistical spread,
// while along a profile a regular orbit's chi2 is smooth (fit_study_tracked.sh's backlit A_r 4.2:
// roughness 0, sampling spread 5.7, and with that as the threshold ranges 2.4-2.7 times as wide;
// FitSearch.ARoughChi2sRangeSpansItsRoughness). A
// parameter is constrained only when that range closes on both sides within the bounds; a
// range that reaches both bounds means the scene does not constrain it: unconstrained, with no
// value.
#include <functional>
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "compare/locked_error.h"
#include "sim/model.h"

namespace dimer::compare {

// The analysis floors (fit_observables.cc) allow for what the analysis and the tracker do not
// resolve, sized for the worst footage: on a rendered and tracked drift the slip bins miss their
// fit by 9e-4 g/f rms against a floor of 2e-3 (docs/ANALYSIS.md), and on fit_study_tracked.sh,
// with the tracker's phase-locked error in chi2, chi2/dof was 0.02-0.33 on 21 of 24 fits.
// An acceptable fit whose chi2/dof is below 1 has its floors scaled down until chi2/dof is 1, its
// optimum polished again and its profiles drawn with them (there: 85 % of the ranges meant as
// 68 % hold the truth, 94 % on the backlit films and 76 % on the mirror-lit ones; with a tenth
// as the least factor 83 %, 89 % and 76 %: docs/BENCHMARKS.md). Never below this factor, so
// that a noise-free track, whose chi2 at floors of nothing would be ~0, keeps some of its
// ranges: bench_fit_study's are 0.15-1 times as wide and all hold the truth
// (FitSearch.FloorsThatOverstateTheScatterAreScaledToIt).
inline constexpr double kMinFloorScale = 0.25;

struct FitParameter {
  std::string name;              // eps | mu_hat | mu_hat_s | mu | mu_s
  bool fitted = false;           // varied by the optimiser (else only sliced)
  double lo = kNaN, hi = kNaN;   // bounds searched
  double value = kNaN;           // optimum (meaningful only when constrained)
  double err = kNaN;             // half-width of the chi2 range (when constrained)
  double range_lo = kNaN, range_hi = kNaN;  // values with chi2 within the threshold
  // constrained | bounded_below | bounded_above | unconstrained | no_acceptable_fit (value: the
  // best point only; err and range NaN)
  std::string status;
  std::vector<double> slice_x, slice_chi2;  // the profile through the optimum
  // Every parameter where the profile reaches range_lo and range_hi (the others re-optimised
  // there); empty at an open end. The correlations are read off them (fit_correlation.h).
  std::vector<double> at_range_lo, at_range_hi;
};

struct FitResult {
  std::vector<FitParameter> params;
  double chi2 = kNaN;            // at the optimum
  int dof = 0;                   // observables - fitted parameters
  double p_value = kNaN;         // P(chi2 >= the value found | dof), goodness_of_fit.h
  bool acceptable = false;       // p_value >= kMinFitPValue
  std::vector<std::string> off;  // no acceptable fit: the observables furthest off, worst first
  // params x params, row-major: the correlation of each pair of constrained parameters from
  // their profiles (fit_correlation.h); 1 on the diagonal of a constrained one, NaN elsewhere.
  std::vector<double> correlation;
  double threshold = kNaN;       // chi2 range threshold (rise above chi2 allowed)
  // The factor the analysis floors were scaled by (1: as set; fit.h), and chi2/dof at the
  // optimum and its p-value with them as set (the goodness test is made there).
  double floor_scale = 1;
  double chi2_per_dof_at_floors = kNaN;
  double p_value_at_floors = kNaN;
  // The tracker's error locked to the drive's phase, measured on the track; its covariance over
  // the observables is in chi2 (locked_error.h), and observed_err includes its diagonal.
  LockedError locked;
  int evaluations = 0;           // simulations run
  double seconds = 0;            // wall time
  std::vector<std::string> observable_names;
  std::vector<double> observed, observed_err, simulated;  // at the optimum
  sim::SimOptions best;          // the simulation options at the optimum
};

struct FitOptions {
  int global_evaluations = 300;  // multi-start search budget, simulations (NLopt MLSL-LDS)
  int max_evaluations = 150;     // budget of each local Nelder-Mead search, simulations
  int slice_points = 15;         // points per parameter slice
  // The least factor an acceptable fit's analysis floors are scaled by to bring chi2/dof to 1
  // (1: never scaled; fit.h, kMinFloorScale).
  double min_floor_scale = kMinFloorScale;
  // Each trial is as long as the track's whole periods (fit.cc, FitScene), at most these two
  // together: a longer track is represented by its settled window's length after a transient.
  int transient_periods = 100;   // periods
  int measured_periods = 100;    // periods
  std::function<void(int simulations)> progress;  // called after each simulation (may be empty)
  // An upper estimate of the simulations a fit runs, for progress meters: the searches, the
  // polishes, the profiles (the slice's points, the optimum and ~10 bisections of each range
  // end, fit.cc), the samplings and roughness, and the two ends of each range searched again
  // (fit.cc, RefineRangeEnds); a fit that fails the goodness test and moves to a lower point its
  // profiles found runs up to kProfileMoves more rounds of profiles (fit.cc).
  int EstimatedSimulations() const {
    return global_evaluations + max_evaluations * 4 + 5 * 30 * (slice_points + 21) + 5 * 8 +
           5 * 2 * 30;
  }
};

// chi2 of one trial: `coefficients` supplies eps, mu_hat, mu_hat_s, mu, mu_s; the rest is the
// scene the track shows (as FitCoefficients builds it). For diagnostics and tests.
double FitChi2(const Analysis& track, const sim::SimOptions& coefficients, const FitOptions& options);

// `scene`: the simulation options that describe the experiment (geometry, drive, the
// starting coefficients); the fitted coefficients are varied from there.
FitResult FitCoefficients(const Analysis& track, const sim::SimOptions& scene,
                          const FitOptions& options);

}  // namespace dimer::compare
