#pragma once
// The one definition of the dimer's modes of motion for the whole project (docs/MODEL.md,
// "What the paper reports"). The simulator (from its event log) and compare (from a sampled
// trajectory, tracked or simulated) both reduce a run to per-period statistics and label them
// with ClassifyPeriods, so a label means the same thing wherever it is printed.
//
// Rules over a window of whole periods (per-sphere averages):
//   rest:      both spheres on the plate >= 95 % of the time and no impact;
//   drift:     the paper's D-mode, one end resting while the other bounces, whatever the
//              bounce's period: one sphere bounces (rests < 5 %, hits the plate 0.3..1.2 times
//              per period: period 1, 2 or 3) while the other stays at the plate (rests >= 5 %
//              of the time, or hits it at least 1.5 times per period: the short dimer's
//              resting end is knocked into small hops by each bounce and rests only 1-10 %,
//              A_r 2.5-2.7 at Gamma 0.9, tests/common/modes_test.cc);
//   jump:      neither rests (< 5 %), each hits once per period;
//   flutter:   neither rests (< 5 %), each hits once every other period (0.35..0.65);
//   irregular: anything else.
// One threshold (5 %) separates a sphere that rests from one that does not. In the paper's
// sweeps (docs/paper/data) a bouncing end rests 0 %, and a resting end that rests near 5 %
// (A_r 2.3-2.4 at Gamma 0.9: 3-5 %) hops 3-4 times a period, so the hop count, far from its own
// threshold, decides there; the simulator's exact rest times and compare's frame-counted ones
// then give one label on one file (a rule asking the resting end to rest >= 20 % cuts through
// steady drift orbits: 0.198 in sim against 0.213 in compare at A_r 3.0, Gamma 1.15, eps 0.5).
// Drift speed: mean lab-x velocity of the CM over the window's whole periods, signed positive
// toward the bouncing end (drift only; otherwise the plain mean), with the standard error from
// the period-to-period scatter.
#include <array>
#include <string>
#include <vector>

namespace dimer {

enum class Mode { kRest, kDrift, kJump, kFlutter, kIrregular };
// One string table for files, the CLI and reports.
const std::vector<std::pair<std::string, Mode>>& ModeNames();
std::string ToString(Mode m);

// Thresholds of the rules above (fractions of the period's time, impacts per period).
inline constexpr double kRestAllFraction = 0.95;     // "rest": both spheres on the plate
inline constexpr double kNotRestingFraction = 0.05;  // below: the sphere does not rest
inline constexpr double kOnePerPeriodMin = 0.8, kOnePerPeriodMax = 1.2;
inline constexpr double kBounceMin = 0.3;            // drift: the bouncing end, period <= 3
inline constexpr double kHoppingMin = 1.5;           // drift: a resting end that hops
inline constexpr double kEveryOtherMin = 0.35, kEveryOtherMax = 0.65;
// An impact counts when it approaches the plate faster than this fraction of g/f: the
// micro-bounces of a resting end (the inelastic collapse) are far slower.
inline constexpr double kSignificantImpactRel = 0.05;

struct PeriodStats {
  std::array<int, 2> impacts{};       // impacts per sphere (0 left, 1 right) in this period
  std::array<double, 2> rest_time{};  // time each sphere spent on the plate, s
  double x_start = 0;                 // CM's x along the plate at the period start, m
  int events = 0;                     // simulator events (0 for sampled trajectories)
};

struct ModeSummary {
  Mode mode = Mode::kIrregular;
  std::string label = "irregular";  // ToString(mode)
  int bouncing_sphere = -1;         // drift: the sphere that bounces (0 left, 1 right)
  double drift_speed = 0;           // m/s, positive toward the bouncing end in drift
  // m/s, standard error from period-to-period scatter; NaN for a one-period window (no scatter:
  // the error is unknown, not zero; Modes.OnePeriodHasNoError)
  double drift_speed_err = 0;
  int window_periods = 0;
  std::array<double, 2> impacts_per_period{}, rest_fraction{};
  // The orbit's period in plate periods, apart from the label (a drift of period 2 is a drift):
  // the least p <= kMaxOrbitPeriods with which every period of the window repeats its impacts,
  // rest times (to kOrbitTimeTol of a period) and CM advance (to kOrbitAdvanceTol g T^2);
  // 0 when none does (an orbit of longer period, one still creeping, or a track's noise).
  int orbit_periods = 0;
};

inline constexpr int kMaxOrbitPeriods = 4;
inline constexpr double kOrbitTimeTol = 1e-6;     // of a period
inline constexpr double kOrbitAdvanceTol = 1e-6;  // of g T^2 (~16 mm at 25 Hz)

// Labels the periods [first, first + count) of `periods`. `x_end` is the CM's x along the plate
// (as `x_start`) at the end of the last of them; `bounce_dir[s]` is the sign of (x of sphere s - x of the other) there.
ModeSummary ClassifyPeriods(const std::vector<PeriodStats>& periods, int first, int count,
                            double period_s, double x_end, std::array<int, 2> bounce_dir);

// The window the project reports a run's settled mode over: the last half of the run's whole
// periods, at most 100 (at least 1).
int SettledWindow(int whole_periods);

}  // namespace dimer
