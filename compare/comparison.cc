#include "compare/comparison.h"

#include <cmath>
#include <utility>

#include "common/error.h"
#include "compare/text.h"

namespace dimer::compare {
namespace {

constexpr double kMaxArMismatch = 0.03;    // relative
constexpr double kMaxRateMismatch = 0.01;  // relative: frame rates, drive frequencies

void CheckSameExperiment(const Analysis& a, const Analysis& b) {
  const std::string who = a.run.path + " and " + b.run.path;
  if (std::abs(a.run.ar / b.run.ar - 1) > kMaxArMismatch) {
    throw InputError(who + " show different dimers: A_r " + Num(a.run.ar) + " vs " + Num(b.run.ar));
  }
  if (std::abs(a.run.dt / b.run.dt - 1) > kMaxRateMismatch) {
    throw InputError(who + " have different sample rates: " + Num(a.run.fps()) + " vs " +
                     Num(b.run.fps()) + " frames/s");
  }
  if (std::abs(a.plate.freq_hz / b.plate.freq_hz - 1) > kMaxRateMismatch) {
    throw InputError(who + " have different drive frequencies: " + Num(a.plate.freq_hz) + " vs " +
                     Num(b.plate.freq_hz) + " Hz");
  }
}

// Linear interpolation of v (a grid of `run`) at time t; NaN outside or next to a gap.
double At(const SampledRun& run, const std::vector<double>& v, double t) {
  const double f = (t - run.t0) / run.dt;
  const long k = static_cast<long>(std::floor(f));
  if (k < 0 || k >= static_cast<long>(run.n)) return kNaN;
  const double w = f - k;
  if (w < 1e-9) return v[k];
  if (k + 1 >= static_cast<long>(run.n)) return kNaN;
  return (1 - w) * v[k] + w * v[k + 1];
}

int BouncingDirection(const Analysis& a) {
  // +1: the bouncing end is the one with the larger x (the right one at the end), -1 the left.
  const int b = a.periods.settled.summary.bouncing_sphere;
  if (b < 0) return 0;
  long i = static_cast<long>(a.run.n) - 1;
  while (i > 0 && !a.run.Valid(i)) --i;
  return a.run.x[b][i] >= a.run.x[1 - b][i] ? 1 : -1;
}

}  // namespace

Comparison CompareWithSimulation(const Analysis& track, Analysis sim_analysis) {
  CheckSameExperiment(track, sim_analysis);
  Comparison c;
  c.sim_path = sim_analysis.run.path;
  c.sim = std::move(sim_analysis);
  const Analysis& sim = c.sim;
  const SampledRun& tr = track.run;
  const SampledRun& sr = sim.run;
  // Time: equal plate phase; the whole-period shift that ends the track at the sim's end.
  const double T = track.plate.period();
  const double t_tr_end = tr.Time(tr.n - 1), t_sim_end = sr.Time(sr.n - 1);
  double shift = (sim.plate.phase_rad - track.plate.phase_rad) / (2 * M_PI) * -T;  // phase match
  // Any shift + k T matches the phase; take the largest with t_tr_end + shift <= t_sim_end.
  // (Half a frame of slack: the phase is fitted, so the exact end may come out a hair late.)
  shift += std::floor((t_sim_end + 0.5 * tr.dt - t_tr_end - shift) / T) * T;
  c.time_offset_s = shift;
  // Mirror when the bouncing ends are on opposite sides; never a tilted plate's simulation,
  // whose mirror image is the opposite tilt, another experiment.
  const int dt = BouncingDirection(track), ds = BouncingDirection(sim);
  c.mirrored = dt != 0 && ds != 0 && dt != ds && sr.sim_tilt_deg == 0;
  const double mx = c.mirrored ? -1.0 : 1.0;
  // Heights relative to each plate's mean surface.
  const double z_off = track.plate.offset_m - sim.plate.offset_m;
  std::array<std::vector<double>, 2> sx, sz;  // sim tips at track times (mirrored, not shifted)
  c.t.resize(tr.n);
  for (int s = 0; s < 2; ++s) {
    const int src = c.mirrored ? 1 - s : s;  // identities swap under the mirror
    sx[s].resize(tr.n);
    sz[s].resize(tr.n);
    for (size_t i = 0; i < tr.n; ++i) {
      const double ts = tr.Time(i) + shift;
      c.t[i] = tr.Time(i);
      sx[s][i] = mx * At(sr, sr.x[src], ts);
      sz[s][i] = At(sr, sr.z[src], ts) + z_off;
    }
  }
  // x offset: mean CM difference over the frames both have.
  double sum = 0;
  int cnt = 0;
  for (size_t i = 0; i < tr.n; ++i) {
    const double d = 0.5 * (tr.x[0][i] + tr.x[1][i]) - 0.5 * (sx[0][i] + sx[1][i]);
    if (std::isfinite(d)) sum += d, ++cnt;
  }
  c.x_offset_m = cnt > 0 ? sum / cnt : 0.0;
  c.frames_compared = cnt;
  const ModeWindow& w = track.periods.settled;
  for (int s = 0; s < 2; ++s) {
    c.sim_x[s].resize(tr.n);
    c.sim_z[s] = sz[s];
    c.res_x[s].resize(tr.n);
    c.res_z[s].resize(tr.n);
    double qx = 0, qz = 0;
    int m = 0;
    for (size_t i = 0; i < tr.n; ++i) {
      c.sim_x[s][i] = sx[s][i] + c.x_offset_m;
      c.res_x[s][i] = tr.x[s][i] - c.sim_x[s][i];
      c.res_z[s][i] = tr.z[s][i] - c.sim_z[s][i];
      const double t = tr.Time(i);
      if (t >= w.t_start && t <= w.t_end && std::isfinite(c.res_x[s][i]) && std::isfinite(c.res_z[s][i])) {
        qx += c.res_x[s][i] * c.res_x[s][i];
        qz += c.res_z[s][i] * c.res_z[s][i];
        ++m;
      }
    }
    if (m > 0) c.rms_x[s] = std::sqrt(qx / m), c.rms_z[s] = std::sqrt(qz / m);
  }
  c.modes_agree = track.periods.settled.summary.label == sim.periods.settled.summary.label;
  return c;
}

}  // namespace dimer::compare
