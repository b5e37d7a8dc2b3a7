#pragma once
// One point of a sweep: run the simulator in-process (no process start per point) and reduce the
// run to the sweep's row (docs/FORMATS.md, "Sweep files"). Everything is computed over the
// measured window, the `periods` periods after the discarded `transient`, with the project's one
// mode definition (common/modes.h, ClassifyPeriods).
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>

#include "sim/sweep_spec.h"

namespace dimer::sim {

struct PointResult {
  int64_t index = -1;               // grid index
  std::string mode = "irregular";   // common/modes.h label over the window
  int8_t bouncing_sphere = -1;      // drift: 0 left, 1 right; -1 otherwise
  double drift_speed = NAN;         // m/s, positive toward the bouncing end in drift
  double drift_speed_err = NAN;     // m/s, standard error from the period-to-period scatter
  double drift_scaled = NAN;        // <u> f / g
  double drift_scaled_err = NAN;
  int8_t drift_survived = -1;       // drift release: 1 if still drifting on the released end
                                    // (the right one) over the window, 0 if not; -1 other inits
  double events_per_period = NAN;   // simulator events per period over the window
  std::array<double, 2> impacts_per_period{NAN, NAN}, rest_fraction{NAN, NAN};
  // The orbit's period in plate periods over the window (ModeSummary::orbit_periods: 1..4, 0
  // when none up to 4 repeats), apart from the label: a drift of period 2 is a drift.
  int8_t orbit_periods = 0;
  // Impacts of the bouncing end (drift; both ends otherwise) over the window, by how the slip
  // ended as the impact law reports it: the most frequent of continuous_slide / slip_stick /
  // slip_reversal ("none" without impacts), and the share of impacts of that type.
  std::string impact_type = "none";
  double impact_type_fraction = NAN;
  std::string error;  // non-empty: the run stopped early (event storm); numbers above are NaN
};

// Runs point i of `spec`. Returns a result with index -1 when `should_stop` interrupted the run:
// an interrupted point is never recorded.
PointResult RunSweepPoint(const SweepSpec& spec, size_t i,
                          const std::function<bool()>& should_stop = {});

}  // namespace dimer::sim
