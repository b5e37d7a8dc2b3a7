#pragma once
// Slip velocity of the resting sphere's contact point (docs/MODEL.md "Contact kinematics"):
//   U = u - omega r_z,  r_z = z_s - R - z_cm  (the contact point's height relative to the CM),
// u = d x_cm / dt and omega = d theta / dt from the sampled positions.
//
// Filter: a local quadratic least-squares fit (Savitzky-Golay) of half-width h frames, its
// derivative at the frame. Windows never cross an impact of either sphere (velocities jump
// there) nor a missing frame: they are cut at those and slide to stay inside the segment,
// so ends use one-sided windows. h is the smallest in [2, 10] whose derivative noise, from the
// measured position noise, is below 0.5 % of g/f; noise-free simulations get h = 2. A segment
// shorter than the window (2h + 1 frames) gives no slip: in a simulation those are the resting
// end's micro-bounces, a frame or two apart, whose impacts fall between the frames the filter
// sees (2.5 % of the peak off the exact slip in one bin at A_r 3.9 when kept).
//
// U is signed positive toward the bouncing end (as the drift), defined while the resting sphere
// is within max(thr, 0.01 d) of the plate (NaN elsewhere): the micro-bounces of the inelastic
// collapse after each impact (micrometres, which a simulation resolves and a camera does not)
// do not interrupt it, so simulations and tracks report the slip over the same frames. It is
// phase-averaged over the plate period with standard errors, over the settled window only (the
// drift's and the modes' periods): a profile over the whole run mixes the release's transient
// into it, 9 % of the peak off the settled one in the steepest bin of a 100-period drift at
// A_r 3.9, against 1 % for the settled window's own
// (SimSlip.SettledProfileFollowsTheExactSlipOverTheSameFrames). The whole run's profile is kept
// apart (whole_profile).
// The positive slip after the bouncing end's impact and the negative slip before the next one
// are reported separately: the mean slip over the first and the second half of the interval
// between consecutive impacts of the bouncing end, both impacts within the settled window.
#include <vector>

#include "compare/contacts.h"
#include "compare/periods.h"
#include "compare/plate_fit.h"
#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr int kSlipMinHalfWindow = 2, kSlipMaxHalfWindow = 10;
inline constexpr double kSlipNoiseTarget = 0.005;  // velocity noise, fraction of g/f
inline constexpr double kSlipHopRel = 0.01;        // hops below this fraction of d still count

struct SlipResult {
  int resting_sphere = -1;   // 0 left, 1 right; -1 when no sphere rests
  int sign = 1;              // +1: U positive toward +x is toward the bouncing end
  int half_window = 0;       // h, frames
  double velocity_noise = kNaN;  // predicted noise of U, m/s
  std::vector<double> U;     // per frame, m/s (NaN where the sphere does not rest)
  double window_t_start = kNaN, window_t_end = kNaN;  // the settled window the profile averages, s
  int window_periods = 0;
  std::vector<double> phase, profile, profile_err;  // K bin centres [0,1), mean U, its error
  std::vector<int> profile_count;
  // Frames of the settled window in each bin, resting or not: a bin whose profile_count falls
  // short of them is one where the sphere leaves the plate on some periods (fit_observables.h).
  std::vector<int> profile_frames;
  std::vector<double> whole_profile, whole_profile_err;  // the same over every frame of the run
  std::vector<int> whole_profile_count;
  double after = kNaN, after_err = kNaN;    // mean U, first half after a bouncing impact
  double before = kNaN, before_err = kNaN;  // mean U, second half (before the next impact)
  int intervals = 0;                        // bouncing-impact intervals used for after/before
};

// `settled` (periods.h) is the window averaged and its bouncing sphere (-1 if none) decides the
// resting sphere and the sign.
SlipResult AnalyzeSlip(const SampledRun& run, const PlateDrive& plate, const Contacts& contacts,
                       const ModeWindow& settled, int phase_bins, int half_window = 0);

// The derivative filter, exposed for tests: d/dt of `v` at every frame, windows cut at
// `breaks` (fractional frame indices) and NaN entries.
std::vector<double> SegmentDerivative(const std::vector<double>& v, double dt,
                                      const std::vector<double>& breaks, int half_window);

// Phase average of `values` (NaN skipped) at plate phases `phase` into `bins` bins.
void PhaseAverage(const std::vector<double>& phase, const std::vector<double>& values, int bins,
                  std::vector<double>* centres, std::vector<double>* mean,
                  std::vector<double>* err, std::vector<int>* count);

}  // namespace dimer::compare
