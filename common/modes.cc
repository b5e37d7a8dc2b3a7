#include "common/modes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dimer {

const std::vector<std::pair<std::string, Mode>>& ModeNames() {
  static const std::vector<std::pair<std::string, Mode>> names = {
      {"rest", Mode::kRest},       {"drift", Mode::kDrift},         {"jump", Mode::kJump},
      {"flutter", Mode::kFlutter}, {"irregular", Mode::kIrregular}};
  return names;
}

std::string ToString(Mode m) {
  for (const auto& [name, mode] : ModeNames())
    if (mode == m) return name;
  return "irregular";
}

namespace {

Mode Label(const std::array<double, 2>& ipp, const std::array<double, 2>& rf, int* bouncing) {
  auto one_per_period = [](double x) { return x >= kOnePerPeriodMin && x <= kOnePerPeriodMax; };
  auto every_other = [](double x) { return x >= kEveryOtherMin && x <= kEveryOtherMax; };
  *bouncing = -1;
  if (rf[0] >= kRestAllFraction && rf[1] >= kRestAllFraction && ipp[0] == 0 && ipp[1] == 0)
    return Mode::kRest;
  auto bounces = [&](int s) {
    return rf[s] < kNotRestingFraction && ipp[s] >= kBounceMin && ipp[s] <= kOnePerPeriodMax;
  };
  auto stays_at_plate = [&](int s) { return rf[s] >= kNotRestingFraction || ipp[s] >= kHoppingMin; };
  for (int b = 0; b < 2; ++b) {
    if (bounces(b) && stays_at_plate(1 - b)) {
      *bouncing = b;
      return Mode::kDrift;
    }
  }
  if (rf[0] < kNotRestingFraction && rf[1] < kNotRestingFraction) {
    if (one_per_period(ipp[0]) && one_per_period(ipp[1])) return Mode::kJump;
    if (every_other(ipp[0]) && every_other(ipp[1])) return Mode::kFlutter;
  }
  return Mode::kIrregular;
}

// The least period p of the window's per-period statistics (ModeSummary::orbit_periods).
int OrbitPeriods(const std::vector<PeriodStats>& periods, int first, int end, double period_s, double x_end) {
  constexpr double kG = 9.81;  // m/s^2 (docs/MODEL.md)
  auto advance = [&](int k) { return (k + 1 < end ? periods[k + 1].x_start : x_end) - periods[k].x_start; };
  const double dx_tol = kOrbitAdvanceTol * kG * period_s * period_s, t_tol = kOrbitTimeTol * period_s;
  for (int p = 1; p <= kMaxOrbitPeriods && 2 * p <= end - first; ++p) {
    bool repeats = true;
    for (int k = first; k + p < end && repeats; ++k) {
      const PeriodStats &a = periods[k], &b = periods[k + p];
      repeats = a.impacts == b.impacts && std::abs(a.rest_time[0] - b.rest_time[0]) <= t_tol &&
                std::abs(a.rest_time[1] - b.rest_time[1]) <= t_tol &&
                std::abs(advance(k) - advance(k + p)) <= dx_tol;
    }
    if (repeats) return p;
  }
  return 0;
}

}  // namespace

ModeSummary ClassifyPeriods(const std::vector<PeriodStats>& periods, int first, int count,
                            double period_s, double x_end, std::array<int, 2> bounce_dir) {
  ModeSummary ms;
  const int n = static_cast<int>(periods.size());
  first = std::clamp(first, 0, n);
  const int w = std::clamp(count, 0, n - first);
  ms.window_periods = w;
  if (w == 0) return ms;
  const int end = first + w;
  for (int k = first; k < end; ++k) {
    for (int s = 0; s < 2; ++s) {
      ms.impacts_per_period[s] += periods[k].impacts[s];
      ms.rest_fraction[s] += periods[k].rest_time[s];
    }
  }
  for (int s = 0; s < 2; ++s) {
    ms.impacts_per_period[s] /= w;
    ms.rest_fraction[s] /= w * period_s;
  }
  ms.mode = Label(ms.impacts_per_period, ms.rest_fraction, &ms.bouncing_sphere);
  ms.label = ToString(ms.mode);
  ms.orbit_periods = OrbitPeriods(periods, first, end, period_s, x_end);
  // Per-period velocities: mean over the window and its standard error.
  const double mean = (x_end - periods[first].x_start) / (w * period_s);
  double var = 0;
  for (int k = first; k < end; ++k) {
    const double x1 = k + 1 < end ? periods[k + 1].x_start : x_end;
    const double v = (x1 - periods[k].x_start) / period_s;
    var += (v - mean) * (v - mean);
  }
  const double sign = ms.bouncing_sphere >= 0 ? bounce_dir[ms.bouncing_sphere] : 1;
  ms.drift_speed = sign * mean;
  ms.drift_speed_err = w > 1 ? std::sqrt(var / (w - 1) / w) : std::numeric_limits<double>::quiet_NaN();
  return ms;
}

int SettledWindow(int whole_periods) { return std::max(1, std::min(100, whole_periods / 2)); }

}  // namespace dimer
