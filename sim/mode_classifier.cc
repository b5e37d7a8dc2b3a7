#include "sim/mode_classifier.h"

#include <cmath>

namespace dimer::sim {

ModeSummary ClassifyMode(const std::vector<PeriodStats>& periods, double period_s, double x_end,
                         std::array<int, 2> bounce_dir, int window) {
  ModeSummary ms;
  const int n = static_cast<int>(periods.size());
  const int w = std::min(window, n);
  ms.window_periods = w;
  if (w == 0) return ms;
  const int first = n - w;
  for (int k = first; k < n; ++k) {
    for (int s = 0; s < 2; ++s) {
      ms.impacts_per_period[s] += periods[k].impacts[s];
      ms.rest_fraction[s] += periods[k].rest_time[s];
    }
  }
  for (int s = 0; s < 2; ++s) {
    ms.impacts_per_period[s] /= w;
    ms.rest_fraction[s] /= w * period_s;
  }
  const auto& ipp = ms.impacts_per_period;
  const auto& rf = ms.rest_fraction;
  auto one_per_period = [](double x) { return x >= 0.8 && x <= 1.2; };
  auto every_other = [](double x) { return x >= 0.35 && x <= 0.65; };
  if (rf[0] >= 0.95 && rf[1] >= 0.95 && ipp[0] == 0 && ipp[1] == 0) {
    ms.label = "rest";
  } else {
    for (int b = 0; b < 2; ++b) {
      if (one_per_period(ipp[b]) && rf[b] < 0.05 && rf[1 - b] >= 0.2) {
        ms.label = "drift";
        ms.bouncing_sphere = b;
      }
    }
    if (ms.label != "drift" && rf[0] < 0.05 && rf[1] < 0.05) {
      if (one_per_period(ipp[0]) && one_per_period(ipp[1])) ms.label = "jump";
      if (every_other(ipp[0]) && every_other(ipp[1])) ms.label = "flutter";
    }
  }
  // Per-period velocities: mean and standard error.
  std::vector<double> speeds;
  for (int k = first; k < n; ++k) {
    const double x1 = k + 1 < n ? periods[k + 1].x_start : x_end;
    speeds.push_back((x1 - periods[k].x_start) / period_s);
  }
  double mean = (x_end - periods[first].x_start) / (w * period_s), var = 0;
  for (double v : speeds) var += (v - mean) * (v - mean);
  const double err = w > 1 ? std::sqrt(var / (w - 1) / w) : 0.0;
  const double sign = ms.bouncing_sphere >= 0 ? bounce_dir[ms.bouncing_sphere] : 1;
  ms.drift_speed = sign * mean;
  ms.drift_speed_err = err;
  return ms;
}

}  // namespace dimer::sim
