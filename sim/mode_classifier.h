#pragma once
// Which mode a simulated run settled in (MODEL.md "What the paper reports"), from the last
// periods of the run, and its drift speed.
//   rest:    both spheres in persistent contact >= 95 % of the time, no impacts;
//   drift:   one sphere rests >= 20 % of the time and the other has one impact per period
//            (0.8..1.2 on average) and rests < 5 %;
//   jump:    neither rests, each sphere has one impact per period;
//   flutter: neither rests, each sphere has one impact every other period (0.35..0.65);
//   irregular: anything else.
// Drift speed = mean lab-x velocity of the CM over the window, signed positive toward the
// bouncing end (drift mode only; otherwise the plain mean velocity).
#include <string>
#include <vector>

#include "sim/events.h"

namespace dimer::sim {

struct ModeSummary {
  std::string label = "irregular";
  int bouncing_sphere = -1;      // drift: the sphere that bounces
  double drift_speed = 0;        // m/s, positive toward the bouncing end in drift
  double drift_speed_err = 0;    // m/s, standard error from period-to-period scatter
  int window_periods = 0;
  std::array<double, 2> impacts_per_period{}, rest_fraction{};
};

// `periods` are complete periods; `x_end` is the lab x at the end of the last one;
// `bounce_dir` gives, for each sphere, the sign of (its x - the other's x) at the end.
ModeSummary ClassifyMode(const std::vector<PeriodStats>& periods, double period_s, double x_end,
                         std::array<int, 2> bounce_dir, int window);

}  // namespace dimer::sim
