#include "sim/model.h"

#include <algorithm>
#include <cmath>

#include <sstream>

#include "common/modes.h"
#include "sim/constants.h"
#include "sim/events.h"
#include "sim/state.h"

namespace dimer::sim {

const std::vector<std::pair<std::string, InitKind>>& InitKindNames() {
  static const std::vector<std::pair<std::string, InitKind>> kNames = {
      {"drift", InitKind::kDrift},
      {"jump", InitKind::kJump},
      {"flutter", InitKind::kFlutter},
      {"rest", InitKind::kRest}};
  return kNames;
}

std::string ToString(InitKind k) {
  for (const auto& [name, kind] : InitKindNames()) {
    if (kind == k) return name;
  }
  return "?";
}

namespace {
void Require(std::vector<std::string>& errors, bool ok, const char* flag, double value,
             const char* expected) {
  if (ok) return;
  std::ostringstream s;
  s << flag << ": " << value << ": expected " << expected;
  errors.push_back(s.str());
}
}  // namespace

// The range of each input (docs/FORMATS.md, "Simulation options"): wide enough for any
// experiment of this kind and the extremes the stability tests run (A_r 1.05 and 20, Gamma 3,
// mu 10), narrow enough that no value makes a run take unbounded time or memory
// (SimOptionsLimits.* in tests/sim/simulator_test.cc).
std::vector<std::string> SimOptions::Check() const {
  std::vector<std::string> e;
  auto finite = [](double x) { return std::isfinite(x); };
  Require(e, finite(ar) && ar > 1.0 && ar <= kMaxAr, "--ar", ar,
          "1 < A_r <= 1000 (spheres cannot overlap)");
  Require(e, finite(diameter_m) && diameter_m >= 1e-6 && diameter_m <= 1, "--diameter",
          diameter_m, "a diameter from 1e-6 to 1 m");
  Require(e, finite(freq_hz) && freq_hz >= 1e-2 && freq_hz <= 1e5, "--freq", freq_hz,
          "a frequency from 0.01 to 1e5 Hz");
  Require(e, finite(gamma) && gamma >= 0 && gamma <= kMaxGamma, "--gamma", gamma,
          "0 <= Gamma <= 10");
  Require(e, finite(tilt_deg) && std::abs(tilt_deg) < 90, "--tilt-deg", tilt_deg,
          "|tilt| < 90 degrees");
  Require(e, finite(plate_phase) && std::abs(plate_phase) <= kMaxPhase, "--plate-phase",
          plate_phase, "a fraction of a period, |phase| <= 1e6");
  Require(e, finite(eps) && eps >= 0 && eps <= 1, "--eps", eps, "0 <= eps <= 1");
  Require(e, finite(mu) && mu >= 0 && mu <= kMaxFriction, "--mu", mu, "0 <= mu <= 1000");
  Require(e, finite(mu_s) && mu_s >= mu && mu_s <= kMaxFriction, "--mu-s", mu_s,
          "mu <= mu_s <= 1000");
  Require(e, finite(mu_hat) && mu_hat >= 0 && mu_hat <= kMaxFriction, "--mu-hat", mu_hat,
          "0 <= mu_hat <= 1000");
  Require(e, finite(mu_hat_s) && mu_hat_s >= mu_hat && mu_hat_s <= kMaxFriction, "--mu-hat-s",
          mu_hat_s, "mu_hat <= mu_hat_s <= 1000");
  Require(e, std::isnan(lift) || (finite(lift) && lift >= 0), "--lift", lift,
          "a lift >= 0 (fraction of the diameter)");
  // The lift bound depends on --ar, and the default lift on --freq: when either is already
  // reported, a lift error would only be a knock-on of it (and name a flag never given).
  const bool lift_inputs_ok = (finite(ar) && ar > 1.0) &&
                              (!std::isnan(lift) || (finite(freq_hz) && freq_hz > 0));
  const bool drift_release = init == InitKind::kDrift && !init_state;
  if (drift_release && lift_inputs_ok) {
    const double lift_eff = EffectiveLift();
    Require(e, !(lift_eff >= ar - 1), "--lift", lift_eff,
            std::isnan(lift) ? "lift < A_r - 1 (the default lift, 0.3 d at 25 Hz scaled by "
                               "(25 Hz/f)^2, is too large at this --freq: pass --lift)"
                             : "lift < A_r - 1 (the lifted centre must stay below the top of "
                               "the other sphere)");
  }
  Require(e, finite(release_phase) && std::abs(release_phase) <= kMaxPhase, "--release-phase",
          release_phase, "a fraction of a period, |phase| <= 1e6");
  Require(e, finite(cycles) && cycles > 0 && cycles <= kMaxPeriods, "--cycles", cycles,
          "a number of periods from > 0 to 1e9");
  Require(e, finite(duration_s) && duration_s >= 0, "--duration", duration_s, "a duration >= 0 s");
  if (finite(duration_s) && duration_s > 0 && finite(freq_hz) && freq_hz > 0) {
    Require(e, duration_s * freq_hz <= kMaxPeriods, "--duration", duration_s,
            "at most 1e9 plate periods");
  }
  Require(e, finite(fps) && (fps == 0 || (fps >= kMinFps && fps <= kMaxFps)), "--fps", fps,
          "0 (events only) or a sampling rate from 1e-3 to 1e7 samples/s");
  Require(e, finite(collapse_rel) && collapse_rel > 0 && collapse_rel < 1, "--collapse-vc",
          collapse_rel, "0 < v_c/(g/f) < 1");
  Require(e, finite(contact_tol) && contact_tol >= 1e-14 && contact_tol <= 1e-2,
          "--contact-tol", contact_tol, "1e-14 <= tol <= 1e-2");
  Require(e, finite(gap_tol) && gap_tol >= 1e-16 && gap_tol <= 1e-6, "--gap-tol", gap_tol,
          "1e-16 <= gap tolerance <= 1e-6 m");
  Require(e, max_events_per_period >= 10 && max_events_per_period <= 1e7,
          "--max-events-per-period", max_events_per_period, "10 to 1e7");
  if (init_state) {
    for (double x : *init_state) {
      Require(e, finite(x), "--init-state", x, "six finite numbers x,z,theta,u,v,omega");
    }
  }
  return e;
}

double SimOptions::EstimatedMemoryBytes(bool with_event_log) const {
  // Per sample: its time and lab state, and as much again for the file's chunks, compressed
  // while the run goes on and held until written (run_sim.cc; never more than the raw rows).
  // Per period: the statistics and, when kept, a drift mode's event log.
  const double periods = Duration() * freq_hz;
  const double samples = fps > 0 ? Duration() * fps + 1 : 0;
  const double per_period =
      sizeof(PeriodStats) + (with_event_log ? kEventsPerPeriodEstimate * sizeof(EventRecord) : 0);
  return samples * 2 * (sizeof(double) + sizeof(State)) + periods * per_period;
}

long SimOptions::SampleCount() const {
  if (!(fps > 0)) return 0;
  return static_cast<long>(std::floor(Duration() * fps + kSampleCountSlack)) + 1;
}

double SimOptions::EffectiveLift() const {
  if (!std::isnan(lift)) return lift;
  const double r = kDefaultLiftFreqHz / freq_hz;
  return kDefaultLift * r * r;
}

Model Model::FromOptions(const SimOptions& o) {
  Model m{};
  m.R = 0.5 * o.diameter_m;
  m.A = o.ar - 1.0;
  m.inv_I = 1.0 / (m.R * m.R * (m.A * m.A + 0.4));
  m.omega_p = 2.0 * M_PI * o.freq_hz;
  m.amp = o.gamma * kGravity / (m.omega_p * m.omega_p);
  m.phi0 = 2.0 * M_PI * o.plate_phase;
  m.period = 1.0 / o.freq_hz;
  const double alpha = o.tilt_deg * M_PI / 180.0;
  m.sin_a = std::sin(alpha);
  m.cos_a = std::cos(alpha);
  m.eps = o.eps;
  m.mu = o.mu;
  m.mu_s = o.mu_s;
  m.mu_hat = o.mu_hat;
  m.mu_hat_s = o.mu_hat_s;
  m.restitution = o.restitution;
  m.vel_scale = kGravity / o.freq_hz;
  m.gap_tol = o.gap_tol;
  // Floor: a bounce slower than sqrt(2 g_max gap_tol) rises less than the gap tolerance, so its
  // flight cannot be resolved from contact (position round-off); it is a collapse whatever v_c.
  const double g_max = kGravity + m.amp * m.omega_p * m.omega_p;
  m.v_collapse = std::max(o.collapse_rel * m.vel_scale, std::sqrt(2 * g_max * m.gap_tol));
  m.contact_tol = o.contact_tol;
  return m;
}

double Model::PlateZ(double t) const { return amp * std::sin(omega_p * t + phi0); }
double Model::PlateV(double t) const { return amp * omega_p * std::cos(omega_p * t + phi0); }
double Model::PlateA(double t) const {
  return -amp * omega_p * omega_p * std::sin(omega_p * t + phi0);
}

}  // namespace dimer::sim
