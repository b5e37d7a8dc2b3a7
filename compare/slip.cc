#include "compare/slip.h"

#include <algorithm>
#include <cmath>

#include "compare/noise.h"

namespace dimer::compare {
namespace {

// Derivative at the centre-weighted position of a quadratic LS fit through frames [a, b].
double LocalSlope(const std::vector<double>& v, long a, long b, long i, double dt) {
  // Centre on i; normal equations of (1, tau, tau^2).
  double s[5] = {0, 0, 0, 0, 0}, r[3] = {0, 0, 0};
  for (long k = a; k <= b; ++k) {
    const double tau = static_cast<double>(k - i);
    double p = 1;
    for (int e = 0; e < 5; ++e) {
      s[e] += p;
      if (e < 3) r[e] += p * v[k];
      p *= tau;
    }
  }
  // Solve the 3x3 system [[s0 s1 s2][s1 s2 s3][s2 s3 s4]] c = r for c1 (Cramer's rule).
  const double det = s[0] * (s[2] * s[4] - s[3] * s[3]) - s[1] * (s[1] * s[4] - s[3] * s[2]) +
                     s[2] * (s[1] * s[3] - s[2] * s[2]);
  if (std::abs(det) < 1e-12) return NAN;
  const double det1 = s[0] * (r[1] * s[4] - s[3] * r[2]) - r[0] * (s[1] * s[4] - s[3] * s[2]) +
                      s[2] * (s[1] * r[2] - r[1] * s[2]);
  return det1 / det / dt;
}

// Derivative noise of the centred quadratic SG filter of half-width h, per unit position noise.
double SlopeNoiseGain(int h) {
  return std::sqrt(3.0 / (h * (h + 1.0) * (2.0 * h + 1.0)));
}

}  // namespace

std::vector<double> SegmentDerivative(const std::vector<double>& v, double dt,
                                      const std::vector<double>& breaks, int h) {
  const long n = static_cast<long>(v.size());
  std::vector<double> out(n, NAN);
  std::vector<double> br = breaks;
  std::sort(br.begin(), br.end());
  long i = 0;
  size_t next = 0;
  while (i < n) {
    // Segment [i, j): finite values, no break strictly inside.
    if (!std::isfinite(v[i])) {
      ++i;
      continue;
    }
    while (next < br.size() && br[next] <= static_cast<double>(i)) ++next;
    const double limit = next < br.size() ? br[next] : static_cast<double>(n);
    long j = i;
    while (j < n && std::isfinite(v[j]) && static_cast<double>(j) < limit) ++j;
    const long len = j - i;
    if (len >= 2 * h + 1) {
      const long w = 2 * h + 1;
      for (long k = i; k < j; ++k) {
        const long a = std::clamp<long>(k - w / 2, i, j - w);
        out[k] = LocalSlope(v, a, a + w - 1, k, dt);
      }
    }
    i = j;
  }
  return out;
}

void PhaseAverage(const std::vector<double>& phase, const std::vector<double>& values, int bins,
                  std::vector<double>* centres, std::vector<double>* mean,
                  std::vector<double>* err, std::vector<int>* count) {
  centres->assign(bins, 0);
  mean->assign(bins, 0);
  err->assign(bins, NAN);
  count->assign(bins, 0);
  std::vector<double> sq(bins, 0);
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || !std::isfinite(phase[i])) continue;
    const int b = std::min(bins - 1, static_cast<int>(phase[i] * bins));
    (*mean)[b] += values[i];
    sq[b] += values[i] * values[i];
    ++(*count)[b];
  }
  for (int b = 0; b < bins; ++b) {
    (*centres)[b] = (b + 0.5) / bins;
    const int c = (*count)[b];
    if (c == 0) {
      (*mean)[b] = NAN;
      continue;
    }
    (*mean)[b] /= c;
    if (c > 1) {
      const double var = std::max(0.0, (sq[b] - c * (*mean)[b] * (*mean)[b]) / (c - 1));
      (*err)[b] = std::sqrt(var / c);
    }
  }
}

SlipResult AnalyzeSlip(const SampledRun& run, const PlateDrive& plate, const Contacts& contacts,
                       const ModeWindow& settled, int phase_bins, int half_window) {
  SlipResult out;
  const int bouncing_sphere = settled.count > 0 ? settled.summary.bouncing_sphere : -1;
  out.window_periods = settled.count;
  if (settled.count > 0) out.window_t_start = settled.t_start, out.window_t_end = settled.t_end;
  const size_t n = run.n;
  out.U.assign(n, NAN);
  // The resting sphere: the drift's non-bouncing end, else the one resting most.
  int rs = -1;
  if (bouncing_sphere >= 0) {
    rs = 1 - bouncing_sphere;
  } else {
    long c0 = 0, c1 = 0;
    for (size_t i = 0; i < n; ++i) c0 += contacts.sphere[0].resting[i], c1 += contacts.sphere[1].resting[i];
    if (c0 + c1 > 0) rs = c1 > c0 ? 1 : 0;
  }
  out.resting_sphere = rs;
  if (rs < 0) return out;
  // Sign: toward the bouncing end (the other sphere's side).
  long last = static_cast<long>(n) - 1;
  while (last > 0 && !run.Valid(last)) --last;
  out.sign = run.x[1 - rs][last] >= run.x[rs][last] ? 1 : -1;
  // Centre of mass, angle (unwrapped), contact arm.
  std::vector<double> xc(n), zc(n), th(n);
  for (size_t i = 0; i < n; ++i) {
    xc[i] = 0.5 * (run.x[0][i] + run.x[1][i]);
    zc[i] = 0.5 * (run.z[0][i] + run.z[1][i]);
    th[i] = std::atan2(run.z[1][i] - run.z[0][i], run.x[1][i] - run.x[0][i]);
  }
  // Filter width from the measured noise of x_cm and theta.
  const double sx = NoiseSigma(xc), st = NoiseSigma(th);
  const double arm = 0.5 * run.diameter_m * (1.0 + 0.5 * (run.ar - 1.0));  // typical |r_z|
  const double target = kSlipNoiseTarget * kGravity / plate.freq_hz;
  int h = kSlipMinHalfWindow;
  auto noise_at = [&](int hw) {
    return SlopeNoiseGain(hw) / run.dt * std::hypot(sx, arm * st);
  };
  while (h < kSlipMaxHalfWindow && noise_at(h) > target) ++h;
  if (half_window > 0) h = half_window;  // imposed (a simulation seen as the track was)
  out.half_window = h;
  out.velocity_noise = noise_at(h);
  std::vector<double> breaks;
  for (const Impact& imp : contacts.AllImpacts()) breaks.push_back(imp.frame);
  const std::vector<double> u = SegmentDerivative(xc, run.dt, breaks, h);
  const std::vector<double> w = SegmentDerivative(th, run.dt, breaks, h);
  const double radius = 0.5 * run.diameter_m;
  std::vector<double> phase(n, NAN);
  for (size_t i = 0; i < n; ++i) {
    phase[i] = plate.PhaseFraction(run.Time(i));
    const SphereContacts& c = contacts.sphere[rs];
    const double near = std::max(c.threshold_m, kSlipHopRel * run.diameter_m);
    if (!(c.gap[i] - c.level_m <= near)) continue;
    const double rz = run.z[rs][i] - radius - zc[i];
    out.U[i] = out.sign * (u[i] - w[i] * rz);
  }
  // A frame is in the window when its time is in [t_start, t_end) (periods.cc counts so).
  auto in_window = [&](double t) { return t >= out.window_t_start && t < out.window_t_end; };
  std::vector<double> settled_u(n, NAN);
  for (size_t i = 0; i < n; ++i)
    if (in_window(run.Time(i))) settled_u[i] = out.U[i];
  PhaseAverage(phase, settled_u, phase_bins, &out.phase, &out.profile, &out.profile_err,
               &out.profile_count);
  out.profile_frames.assign(phase_bins, 0);
  for (size_t i = 0; i < n; ++i)
    if (in_window(run.Time(i)) && std::isfinite(phase[i]))
      ++out.profile_frames[std::min(phase_bins - 1, static_cast<int>(phase[i] * phase_bins))];
  std::vector<double> centres;
  PhaseAverage(phase, out.U, phase_bins, &centres, &out.whole_profile, &out.whole_profile_err,
               &out.whole_profile_count);
  // After / before the bouncing end's impacts, intervals inside the settled window.
  if (bouncing_sphere >= 0) {
    const auto& imps = contacts.sphere[bouncing_sphere].impacts;
    std::vector<double> a_means, b_means;
    for (size_t k = 0; k + 1 < imps.size(); ++k) {
      if (!in_window(imps[k].t) || !(imps[k + 1].t <= out.window_t_end)) continue;
      const double ta = imps[k].frame, tb = imps[k + 1].frame, mid = 0.5 * (ta + tb);
      double sa = 0, sb = 0;
      int na = 0, nb = 0;
      for (long i = static_cast<long>(std::ceil(ta)); i < tb && i < static_cast<long>(n); ++i) {
        if (!std::isfinite(out.U[i])) continue;
        if (i < mid) sa += out.U[i], ++na;
        else sb += out.U[i], ++nb;
      }
      if (na > 0) a_means.push_back(sa / na);
      if (nb > 0) b_means.push_back(sb / nb);
    }
    auto mean_err = [](const std::vector<double>& v, double* m, double* e) {
      if (v.empty()) return;
      double s = 0, q = 0;
      for (double x : v) s += x;
      *m = s / v.size();
      for (double x : v) q += (x - *m) * (x - *m);
      *e = v.size() > 1 ? std::sqrt(q / (v.size() - 1) / v.size()) : NAN;
    };
    mean_err(a_means, &out.after, &out.after_err);
    mean_err(b_means, &out.before, &out.before_err);
    out.intervals = static_cast<int>(std::min(a_means.size(), b_means.size()));
  }
  return out;
}

}  // namespace dimer::compare
