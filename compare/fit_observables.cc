#include "compare/fit_observables.h"

#include <cmath>

namespace dimer::compare {
namespace {

// Floors: what the analysis itself resolves, so a noise-free track cannot demand more of a
// simulation than the analysis can tell apart.
constexpr double kDriftFloor = 5e-4;     // <u> f / g
constexpr double kSpeedFloor = 2e-3;     // velocities, units of g/f
constexpr double kRatioFloor = 5e-3;     // v_after / -v_before
constexpr double kPhaseFloor = 2e-3;     // periods
constexpr int kMinBinCount = 3;

struct Stats {
  double mean = kNaN, err = kNaN;
};

Stats MeanErr(const std::vector<double>& v) {
  Stats s;
  if (v.empty()) return s;
  double sum = 0, q = 0;
  for (double x : v) sum += x;
  s.mean = sum / v.size();
  for (double x : v) q += (x - s.mean) * (x - s.mean);
  s.err = v.size() > 1 ? std::sqrt(q / (v.size() - 1) / v.size()) : 0.0;
  return s;
}

// Circular mean of phases (periods) near their mean, with its error.
Stats PhaseMeanErr(const std::vector<double>& p) {
  double c = 0, s = 0;
  for (double x : p) c += std::cos(2 * M_PI * x), s += std::sin(2 * M_PI * x);
  if (p.empty()) return {};
  double centre = std::atan2(s, c) / (2 * M_PI);
  std::vector<double> d;
  for (double x : p) d.push_back(centre + std::remainder(x - centre, 1.0));
  Stats st = MeanErr(d);
  st.mean -= std::floor(st.mean);
  return st;
}

void SphereImpacts(const Analysis& a, int s, const std::string& tag, std::vector<Observable>* out) {
  const ModeWindow& w = a.periods.settled;
  const double vscale = kGravity / a.plate.freq_hz;
  std::vector<double> takeoff, ratio, phase;
  for (const Impact& i : a.contacts.sphere[s].impacts) {
    if (i.t < w.t_start || i.t > w.t_end || !i.bounce) continue;
    if (!std::isfinite(i.v_after) || !std::isfinite(i.v_before) || !(i.v_before < 0)) continue;
    takeoff.push_back(i.v_after / vscale);
    ratio.push_back(i.v_after / -i.v_before);
    phase.push_back(i.plate_phase);
  }
  const Stats t = MeanErr(takeoff), r = MeanErr(ratio), p = PhaseMeanErr(phase);
  out->push_back({tag + "_takeoff_speed", t.mean, t.err, kSpeedFloor});
  out->push_back({tag + "_restitution_ratio", r.mean, r.err, kRatioFloor});
  out->push_back({tag + "_impact_phase", p.mean, p.err, kPhaseFloor});
}

}  // namespace

std::vector<Observable> FitObservables(const Analysis& a) {
  std::vector<Observable> out;
  const ModeSummary& ms = a.periods.settled.summary;
  const double vscale = kGravity / a.plate.freq_hz;
  if (ms.label == "drift") {
    out.push_back({"drift_scaled", a.drift.scaled, a.drift.scaled_err, kDriftFloor});
    SphereImpacts(a, ms.bouncing_sphere, "bouncing", &out);
    out.push_back({"slip_after", a.slip.after / vscale, a.slip.after_err / vscale, kSpeedFloor});
    out.push_back({"slip_before", a.slip.before / vscale, a.slip.before_err / vscale, kSpeedFloor});
    for (size_t b = 0; b < a.slip.profile.size(); ++b) {
      const bool ok = a.slip.profile_count[b] >= kMinBinCount;
      out.push_back({"slip_bin_" + std::to_string(b), ok ? a.slip.profile[b] / vscale : kNaN,
                     ok ? a.slip.profile_err[b] / vscale : kNaN, kSpeedFloor});
    }
  } else if (ms.label == "jump" || ms.label == "flutter") {
    SphereImpacts(a, 0, "left", &out);
    SphereImpacts(a, 1, "right", &out);
  }
  return out;
}

}  // namespace dimer::compare
