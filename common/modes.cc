#include "common/modes.h"

#include <algorithm>
#include <cmath>

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
  for (int b = 0; b < 2; ++b) {
    if (one_per_period(ipp[b]) && rf[b] < kNotRestingFraction && rf[1 - b] >= kRestingFraction) {
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
  ms.drift_speed_err = w > 1 ? std::sqrt(var / (w - 1) / w) : 0.0;
  return ms;
}

int SettledWindow(int whole_periods) { return std::max(1, std::min(100, whole_periods / 2)); }

}  // namespace dimer
