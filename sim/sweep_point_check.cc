#include "sim/sweep_point_check.h"

#include <cmath>

#include "common/modes.h"
#include "sim/constants.h"
#include "sim/model.h"

namespace dimer::sim {
namespace {

bool IsMode(const std::string& s) {  // the project's one table of mode names (common/modes.h)
  for (const auto& [name, mode] : ModeNames()) {
    if (name == s) return true;
  }
  return false;
}
bool IsImpactType(const std::string& s) {
  return s == "none" || s == "continuous_slide" || s == "slip_stick" || s == "slip_reversal";
}
// A fraction of the window's time: summed phase by phase, so a whole window at rest reads
// 1 + 1 ulp (SweepPointCheck.FreshResultsAreValid).
bool IsFraction(double x) { return x >= 0 && x <= 1 + 64 * 2.220446049250313e-16; }

// Well-formed UTF-8 (no overlong forms, surrogates or code points above U+10FFFF).
bool IsUtf8(const std::string& s) {
  size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int n = 0;
    unsigned lo = 0x80, hi = 0xBF;
    if (c < 0x80) { ++i; continue; }
    if (c >= 0xC2 && c <= 0xDF) n = 1;
    else if (c == 0xE0) n = 2, lo = 0xA0;
    else if (c >= 0xE1 && c <= 0xEC) n = 2;
    else if (c == 0xED) n = 2, hi = 0x9F;
    else if (c >= 0xEE && c <= 0xEF) n = 2;
    else if (c == 0xF0) n = 3, lo = 0x90;
    else if (c >= 0xF1 && c <= 0xF3) n = 3;
    else if (c == 0xF4) n = 3, hi = 0x8F;
    else return false;
    if (i + n >= s.size()) return false;  // the sequence is cut off
    for (int k = 1; k <= n; ++k) {
      const unsigned char b = static_cast<unsigned char>(s[i + k]);
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return false;
    }
    i += n + 1;
  }
  return true;
}

// |x - y| within round-off of the larger (both NaN counts as equal).
bool Same(double x, double y) {
  if (std::isnan(x) || std::isnan(y)) return std::isnan(x) && std::isnan(y);
  return std::abs(x - y) <= 1e-12 * std::max(std::abs(x), std::abs(y));
}

}  // namespace

std::string PointResultProblem(const PointResult& p, const SweepSpec& spec) {
  if (p.index < 0 || static_cast<size_t>(p.index) >= spec.PointCount()) return "no such point";
  if (!IsUtf8(p.error)) return "its error text is not UTF-8";
  if (!p.error.empty()) return "";  // a failed point carries only its message
  if (!IsMode(p.mode)) return "mode is not one of rest, drift, jump, flutter, irregular";
  if (!IsImpactType(p.impact_type)) return "impact_type is not an impact outcome";
  if (p.bouncing_sphere < -1 || p.bouncing_sphere > 1) return "bouncing_sphere is not -1, 0, 1";
  if (p.drift_survived < -1 || p.drift_survived > 1) return "drift_survived is not -1, 0, 1";
  if (p.orbit_periods < 0 || p.orbit_periods > kMaxOrbitPeriods) return "orbit_periods is not 0..4";
  const SimOptions o = spec.PointOptionsNoInit(static_cast<size_t>(p.index));
  // The mean speed over the window cannot exceed what gravity and the plate give in the whole
  // run: (1 + Gamma) g for the run's duration, beside a drop's initial speed (< 1 m/s here).
  const double v_max = 1.0 + (1.0 + o.gamma) * kGravity * o.Duration();
  if (!(std::abs(p.drift_speed) <= v_max)) return "drift_speed is not a speed this run can have";
  if (!(std::isnan(p.drift_speed_err) || (p.drift_speed_err >= 0 && p.drift_speed_err <= v_max))) {
    return "drift_speed_err is out of range";
  }
  if (!Same(p.drift_scaled, p.drift_speed * o.freq_hz / kGravity) ||
      !Same(p.drift_scaled_err, p.drift_speed_err * o.freq_hz / kGravity)) {
    return "drift_scaled is not drift_speed f/g";
  }
  if (!(p.events_per_period >= 0 && p.events_per_period <= o.max_events_per_period)) {
    return "events_per_period is out of range";
  }
  for (int s = 0; s < 2; ++s) {
    if (!(p.impacts_per_period[s] >= 0 && p.impacts_per_period[s] <= p.events_per_period)) {
      return "impacts_per_period is out of range";
    }
    if (!IsFraction(p.rest_fraction[s])) return "rest_fraction is not a fraction";
  }
  if (p.impact_type == "none" ? !std::isnan(p.impact_type_fraction)
                              : !IsFraction(p.impact_type_fraction)) {
    return "impact_type_fraction is out of range";
  }
  return "";
}

}  // namespace dimer::sim
