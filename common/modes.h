#pragma once
// The one definition of the dimer's modes of motion for the whole project (docs/MODEL.md,
// "What the paper reports"). The simulator (from its event log) and compare (from a sampled
// trajectory, tracked or simulated) both reduce a run to per-period statistics and label them
// with ClassifyPeriods, so a label means the same thing wherever it is printed.
//
// Rules over a window of whole periods (per-sphere averages):
//   rest:      both spheres on the plate >= 95 % of the time and no impact;
//   drift:     one sphere rests >= 20 % of the time, the other hits once per period
//              (0.8..1.2 impacts per period on average) and rests < 5 %;
//   jump:      neither rests (< 5 %), each hits once per period;
//   flutter:   neither rests (< 5 %), each hits once every other period (0.35..0.65);
//   irregular: anything else.
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
inline constexpr double kRestingFraction = 0.20;     // drift: the resting end
inline constexpr double kNotRestingFraction = 0.05;  // a bouncing end
inline constexpr double kOnePerPeriodMin = 0.8, kOnePerPeriodMax = 1.2;
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
  double drift_speed_err = 0;       // m/s, standard error from period-to-period scatter
  int window_periods = 0;
  std::array<double, 2> impacts_per_period{}, rest_fraction{};
};

// Labels the periods [first, first + count) of `periods`. `x_end` is the CM's x along the plate
// (as `x_start`) at the end of the last of them; `bounce_dir[s]` is the sign of (x of sphere s - x of the other) there.
ModeSummary ClassifyPeriods(const std::vector<PeriodStats>& periods, int first, int count,
                            double period_s, double x_end, std::array<int, 2> bounce_dir);

// The window the project reports a run's settled mode over: the last half of the run's whole
// periods, at most 100 (at least 1).
int SettledWindow(int whole_periods);

}  // namespace dimer
