#include "compare/plate_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace dimer::compare {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// The frequency scan spans +-kScanHalfWidth / duration around the first estimate (whose error
// is below 1 / duration) in steps of kScanStep / duration, then golden-section search.
constexpr double kScanHalfWidth = 3.0;
// The first estimate where the median's upward crossings are too few (fewer than 3: a clip of
// 2-3 periods that starts on the rising plate has 2): the best sine over a grid of frequencies
// from kGridMinPeriods periods in the clip to a quarter of the sample rate, in steps of
// kGridStep / duration (the rss's dip is ~1 / duration wide), on at most kGridSamples samples
// (a uniform stride; the rate, and with it the grid's top, is the strided one, so no alias).
// Clips under 2 periods are fitted too, so that the analysis can refuse them with their length
// (ShortClip.TwoAndAHalfPeriodsGiveTheDrive, ShortClip.UnderTwoPeriodsIsRefusedWithItsLength).
constexpr double kGridMinPeriods = 1.0;
constexpr double kGridStep = 0.25;
constexpr size_t kGridSamples = 2000;
constexpr double kScanStep = 0.1;
constexpr int kGoldenIterations = 60;
constexpr double kMinSignificance = 5.0;  // amp / amp_err below this: no detectable drive

struct Samples {
  std::vector<double> tau, z;  // tau = t - t_mid (decorrelates phase and frequency)
  double t_mid = 0;
};

struct LinearFit {
  Eigen::Vector3d coef = Eigen::Vector3d::Zero();  // offset, sine, cosine amplitudes
  double rss = 0;
};

LinearFit FitAtFrequency(const Samples& s, double f) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < s.tau.size(); ++i) {
    const double a = kTwoPi * f * s.tau[i];
    const Eigen::Vector3d row(1.0, std::sin(a), std::cos(a));
    ata += row * row.transpose();
    atb += row * s.z[i];
  }
  LinearFit fit;
  fit.coef = ata.ldlt().solve(atb);
  for (size_t i = 0; i < s.tau.size(); ++i) {
    const double a = kTwoPi * f * s.tau[i];
    const double r = s.z[i] - fit.coef(0) - fit.coef(1) * std::sin(a) - fit.coef(2) * std::cos(a);
    fit.rss += r * r;
  }
  return fit;
}

// Upward crossings of the median with hysteresis: a first frequency estimate.
double CrossingFrequency(const Samples& s) {
  std::vector<double> sorted = s.z;
  std::sort(sorted.begin(), sorted.end());
  const double med = sorted[sorted.size() / 2];
  const double h = 0.25 * (sorted[sorted.size() * 95 / 100] - sorted[sorted.size() * 5 / 100]);
  if (!(h > 0)) return kNaN;
  int state = 0, count = 0;
  double first = kNaN, last = kNaN;
  for (size_t i = 0; i < s.z.size(); ++i) {
    const double d = s.z[i] - med;
    if (d < -h) state = -1;
    if (d > h && state == -1) {
      state = 1;
      if (count++ == 0) first = s.tau[i];
      last = s.tau[i];
    }
  }
  return count >= 3 ? (count - 1) / (last - first) : kNaN;
}

double GridFrequency(const Samples& s) {
  Samples d;
  const size_t stride = (s.tau.size() + kGridSamples - 1) / kGridSamples;
  for (size_t i = 0; i < s.tau.size(); i += stride) d.tau.push_back(s.tau[i]), d.z.push_back(s.z[i]);
  const double duration = s.tau.back() - s.tau.front();
  if (d.tau.size() < 8 || !(duration > 0)) return kNaN;
  const double rate = (d.tau.size() - 1) / (d.tau.back() - d.tau.front());
  double best_f = kNaN, best_rss = INFINITY;
  for (double f = kGridMinPeriods / duration; f <= 0.25 * rate; f += kGridStep / duration) {
    const double rss = FitAtFrequency(d, f).rss;
    if (rss < best_rss) best_rss = rss, best_f = f;
  }
  return best_f;
}

double GoldenMinimumInSteps(const Samples& s, double lo, double hi) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi, c = b - r * (b - a), d = a + r * (b - a);
  double fc = FitAtFrequency(s, c).rss, fd = FitAtFrequency(s, d).rss;
  for (int it = 0; it < kGoldenIterations; ++it) {
    if (fc < fd) {
      b = d, d = c, fd = fc, c = b - r * (b - a), fc = FitAtFrequency(s, c).rss;
    } else {
      a = c, c = d, fc = fd, d = a + r * (b - a), fd = FitAtFrequency(s, d).rss;
    }
  }
  return 0.5 * (a + b);
}

// Residual harmonics 2f..4f, relative to the fundamental's amplitude.
std::array<double, 3> Harmonics(const Samples& s, double f, const LinearFit& fit, double amp) {
  std::array<double, 3> out{};
  for (int k = 2; k <= 4; ++k) {
    Eigen::Matrix2d ata = Eigen::Matrix2d::Zero();
    Eigen::Vector2d atb = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < s.tau.size(); ++i) {
      const double a = kTwoPi * f * s.tau[i];
      const double r = s.z[i] - fit.coef(0) - fit.coef(1) * std::sin(a) - fit.coef(2) * std::cos(a);
      const Eigen::Vector2d row(std::sin(k * a), std::cos(k * a));
      ata += row * row.transpose();
      atb += row * r;
    }
    out[k - 2] = ata.ldlt().solve(atb).norm() / amp;
  }
  return out;
}

}  // namespace

double PlateDrive::Z(double t) const {
  if (!std::isfinite(phase_rad)) return offset_m;
  return offset_m + amp_m * std::sin(kTwoPi * freq_hz * t + phase_rad);
}

double PlateDrive::V(double t) const {
  if (!std::isfinite(phase_rad)) return 0.0;
  const double w = kTwoPi * freq_hz;
  return amp_m * w * std::cos(w * t + phase_rad);
}

double PlateDrive::PhaseFraction(double t) const {
  const double p = (kTwoPi * freq_hz * t + (std::isfinite(phase_rad) ? phase_rad : 0.0)) / kTwoPi;
  return p - std::floor(p);
}

PlateDrive PlateFromSim(const SampledRun& run) {
  PlateDrive d;
  d.source = "file";
  d.freq_hz = run.sim_freq_hz;
  d.gamma = run.sim_gamma;
  d.amp_m = run.sim_gamma * kGravity / (kTwoPi * kTwoPi * run.sim_freq_hz * run.sim_freq_hz);
  d.phase_rad = std::fmod(kTwoPi * run.sim_plate_phase, kTwoPi);
  if (d.phase_rad < 0) d.phase_rad += kTwoPi;
  d.freq_err = d.amp_err = d.phase_err = d.gamma_err = 0;
  d.residual_rms_m = 0;
  return d;
}

PlateDrive FitPlate(const SampledRun& run, double freq_guess_hz) {
  PlateDrive d;
  Samples s;
  for (size_t i = 0; i < run.n; ++i) {
    if (std::isfinite(run.plate_z[i])) {
      s.tau.push_back(run.Time(i));
      s.z.push_back(run.plate_z[i]);
    }
  }
  if (s.tau.size() < 16) return d;
  s.t_mid = 0.5 * (s.tau.front() + s.tau.back());
  for (double& t : s.tau) t -= s.t_mid;
  const double duration = s.tau.back() - s.tau.front();
  double f0 = std::isfinite(freq_guess_hz) ? freq_guess_hz : CrossingFrequency(s);
  if (!(f0 > 0)) f0 = GridFrequency(s);
  if (!(f0 > 0) || f0 * duration < kGridMinPeriods) return d;
  // Scan, then refine inside the best step.
  const double step = kScanStep / duration;
  double best_f = f0, best_rss = INFINITY;
  for (double f = f0 - kScanHalfWidth / duration; f <= f0 + kScanHalfWidth / duration; f += step) {
    if (f <= 0) continue;
    const double rss = FitAtFrequency(s, f).rss;
    if (rss < best_rss) best_rss = rss, best_f = f;
  }
  const double f = GoldenMinimumInSteps(s, best_f - step, best_f + step);
  const LinearFit fit = FitAtFrequency(s, f);
  const double amp = std::hypot(fit.coef(1), fit.coef(2));
  const double phase_mid = std::atan2(fit.coef(2), fit.coef(1));
  // Covariance of (offset, A_s, A_c, f) from the Jacobian at the optimum.
  const size_t n = s.tau.size();
  Eigen::Matrix4d jtj = Eigen::Matrix4d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const double a = kTwoPi * f * s.tau[i];
    const double dzdf = kTwoPi * s.tau[i] * (fit.coef(1) * std::cos(a) - fit.coef(2) * std::sin(a));
    const Eigen::Vector4d row(1.0, std::sin(a), std::cos(a), dzdf);
    jtj += row * row.transpose();
  }
  const double var = fit.rss / std::max<double>(1.0, static_cast<double>(n) - 4.0);
  const Eigen::Matrix4d cov = var * jtj.inverse();
  // Amplitude and phase errors by linear propagation from (A_s, A_c).
  const Eigen::Vector2d da(fit.coef(1) / amp, fit.coef(2) / amp);
  const Eigen::Vector2d dp(-fit.coef(2) / (amp * amp), fit.coef(1) / (amp * amp));
  const Eigen::Matrix2d cab = cov.block<2, 2>(1, 1);
  d.freq_hz = f;
  d.freq_err = std::sqrt(cov(3, 3));
  d.amp_m = amp;
  d.amp_err = std::sqrt(da.dot(cab * da));
  d.offset_m = fit.coef(0);
  // Phase at t = 0 of the file: phase_mid - 2 pi f t_mid; its error includes f's through t_mid.
  double ph = std::fmod(phase_mid - kTwoPi * f * s.t_mid, kTwoPi);
  if (ph < 0) ph += kTwoPi;
  d.phase_rad = ph;
  d.phase_err = std::sqrt(dp.dot(cab * dp) + std::pow(kTwoPi * s.t_mid * d.freq_err, 2));
  d.gamma = kTwoPi * kTwoPi * amp * f * f / kGravity;
  d.gamma_err = d.gamma * std::hypot(d.amp_err / amp, 2 * d.freq_err / f);
  d.residual_rms_m = std::sqrt(fit.rss / n);
  d.harmonic_rel = Harmonics(s, f, fit, amp);
  d.frames_used = static_cast<int>(n);
  d.source = amp > kMinSignificance * d.amp_err ? "fit" : "none";
  return d;
}

}  // namespace dimer::compare
