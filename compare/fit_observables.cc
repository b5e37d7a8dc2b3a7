#include "compare/fit_observables.h"

#include <cmath>
#include <string>

namespace dimer::compare {
namespace {

// Floors: what the analysis itself resolves, so a noise-free track cannot demand more of a
// simulation than the analysis can tell apart.
constexpr double kDriftFloor = 5e-4;     // <u> f / g
constexpr double kSpeedFloor = 2e-3;     // velocities, units of g/f
constexpr double kRatioFloor = 5e-3;     // v_after / -v_before
constexpr double kPhaseFloor = 2e-3;     // periods
constexpr double kModeStatFloor = 0.05;  // impacts per period, rest fractions
constexpr int kMinBinCount = 3;
// A bin of the track's slip profile is compared only where the resting sphere is on the plate
// on at least this share of the bin's frames in the settled window (fit_observables.h). Not
// more: a chaotic drift lifts its resting end off in most bins now and then, and with 0.9
// bench_fit_study's A_r 2.5 kept 18 degrees of freedom of 41 and its fit failed (chi2/dof 5.5,
// 0 at the truth).
constexpr double kContactBinShare = 0.5;

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

std::vector<Observable> FitObservables(const Analysis& a, const std::string& mode, double impact_phase) {
  std::vector<Observable> out;
  const ModeSummary& ms = a.periods.settled.summary;
  const std::string label = mode.empty() ? ms.label : mode;
  const double vscale = kGravity / a.plate.freq_hz;
  if (label == "drift") {
    const int b = ms.bouncing_sphere >= 0 ? ms.bouncing_sphere : (ms.rest_fraction[0] < ms.rest_fraction[1] ? 0 : 1);
    out.push_back({"bouncing_impacts_per_period", ms.impacts_per_period[b], 0, kModeStatFloor});
    out.push_back({"bouncing_rest_fraction", ms.rest_fraction[b], 0, kModeStatFloor});
    out.push_back({"resting_rest_fraction", ms.rest_fraction[1 - b], 0, kModeStatFloor});
    // The drift toward the bouncing end (ClassifyPeriods signs it only in drift).
    double drift = a.drift.scaled, drift_err = a.drift.scaled_err;
    if (ms.bouncing_sphere < 0 && a.run.n > 0) {
      size_t i = a.run.n - 1;
      while (i > 0 && !a.run.Valid(i)) --i;
      drift *= a.run.x[b][i] >= a.run.x[1 - b][i] ? 1 : -1;
    }
    out.push_back({"drift_scaled", drift, drift_err, kDriftFloor});
    SphereImpacts(a, b, "bouncing", &out);
    out.push_back({"slip_after", a.slip.after / vscale, a.slip.after_err / vscale, kSpeedFloor});
    out.push_back({"slip_before", a.slip.before / vscale, a.slip.before_err / vscale, kSpeedFloor});
    // Bins next to the bouncing end's impact are left out: U jumps inside them, so their mean
    // depends on where the frames fall relative to the impact, not on the physics.
    if (!std::isfinite(impact_phase)) {
      for (const Observable& o : out)
        if (o.name == "bouncing_impact_phase") impact_phase = o.value;
    }
    const int nb = static_cast<int>(a.slip.profile.size());
    for (int k = 0; k < a.options.phase_bins; ++k) {
      const double centre = (k + 0.5) / a.options.phase_bins;
      const bool at_impact = std::isfinite(impact_phase) &&
                             std::abs(std::remainder(centre - impact_phase, 1.0)) < 1.5 / a.options.phase_bins;
      const bool ok = k < nb && a.slip.profile_count[k] >= kMinBinCount && !at_impact;
      out.push_back({"slip_bin_" + std::to_string(k), ok ? a.slip.profile[k] / vscale : kNaN,
                     ok ? a.slip.profile_err[k] / vscale : kNaN, kSpeedFloor, k});
    }
  } else if (label == "jump" || label == "flutter") {
    for (int s = 0; s < 2; ++s) {
      const std::string tag = s ? "right" : "left";
      out.push_back({tag + "_impacts_per_period", ms.impacts_per_period[s], 0, kModeStatFloor});
      out.push_back({tag + "_rest_fraction", ms.rest_fraction[s], 0, kModeStatFloor});
    }
    SphereImpacts(a, 0, "left", &out);
    SphereImpacts(a, 1, "right", &out);
  }
  return out;
}

std::vector<Observable> TrackObservables(const Analysis& track) {
  std::vector<Observable> out = FitObservables(track);
  const std::vector<int>& count = track.slip.profile_count;
  const std::vector<int>& frames = track.slip.profile_frames;
  for (Observable& o : out) {
    if (o.slip_bin < 0) continue;
    const size_t k = static_cast<size_t>(o.slip_bin);
    const bool lift_off = k < count.size() && k < frames.size() && count[k] < kContactBinShare * frames[k];
    if (lift_off) o.value = o.err = kNaN;
  }
  return out;
}

}  // namespace dimer::compare
