#include "compare/analysis.h"

#include <cmath>

#include "common/check.h"
#include "common/error.h"
#include "compare/text.h"

namespace dimer::compare {
namespace {

constexpr double kMinPeriods = 2.0;
constexpr double kGFitWarn = 0.02;       // |g_fit/g - 1| above this (and 2 sigma): calibration warning
constexpr double kHarmonicWarn = 0.05;   // a harmonic above 5 % of the drive: not sinusoidal
// --gamma and the tracked plate's Gamma differ: warned beyond 3 sigma and 1 %.
constexpr double kGammaAgreeSigmas = 3.0, kGammaAgreeRel = 0.01;

// The plate amplitude that gives `gamma` at `freq_hz`: Gamma = 4 pi^2 a f^2 / g.
double AmplitudeOfGamma(double gamma, double freq_hz) {
  return gamma * kGravity / std::pow(2 * M_PI * freq_hz, 2);
}

// --gamma with a visible plate: Gamma measured on the plate (an accelerometer) is worth more
// than the amplitude read off its edge, whose pixels per mm differ from the dimer's when the edge
// is nearer or further than the dimer (a POV-Ray film with the front edge 20 mm nearer at 0.7 m:
// Gamma 2.3 % high; `track --plate-m-per-px` mends the edge itself). The fitted frequency and
// phase stay; the amplitude follows the given Gamma.
void UseGivenGamma(double gamma, PlateDrive* p, std::vector<std::string>* warnings) {
  p->gamma_plate = p->gamma;
  p->gamma_plate_err = p->gamma_err;
  p->gamma = gamma;
  p->gamma_err = 0;
  p->amp_m = AmplitudeOfGamma(gamma, p->freq_hz);
  p->amp_err = 0;
  const double diff = p->gamma_plate - gamma;
  if (std::abs(diff) > std::max(kGammaAgreeSigmas * p->gamma_plate_err, kGammaAgreeRel * gamma)) {
    warnings->push_back("--gamma " + Num(gamma) + " is used; the tracked plate moves as Gamma " +
                        Num(p->gamma_plate, 5) + " +- " + Num(p->gamma_plate_err, 2) + " (" +
                        Num(100 * diff / gamma, 3) + " %): an edge nearer the camera than the " +
                        "dimer moves more pixels per mm (track --plate-m-per-px gives its own " +
                        "scale), or --m-per-px or the accelerometer is off");
  }
}

// A drive from --freq/--gamma when the plate is not visible. The phase comes from the lower
// envelope of the spheres (a resting sphere sits on the plate): a sinusoid at the known
// frequency and amplitude fitted to, per phase bin, the lowest sphere bottom seen.
PlateDrive DriveFromOptions(const SampledRun& run, const AnalysisOptions& o) {
  PlateDrive d;
  d.source = "options";
  d.freq_hz = o.freq_hz;
  d.gamma = o.gamma;
  d.amp_m = AmplitudeOfGamma(o.gamma, o.freq_hz);
  d.freq_err = d.gamma_err = d.amp_err = 0;
  constexpr int kBins = 40;
  std::vector<double> low(kBins, INFINITY);
  const double r = 0.5 * run.diameter_m;
  for (size_t i = 0; i < run.n; ++i) {
    const double p = run.Time(i) * o.freq_hz;
    const int b = std::min(kBins - 1, static_cast<int>((p - std::floor(p)) * kBins));
    for (int s = 0; s < 2; ++s)
      if (std::isfinite(run.z[s][i])) low[b] = std::min(low[b], run.z[s][i] - r);
  }
  double ss = 0, sc = 0, m = 0;
  int nb = 0;
  for (int b = 0; b < kBins; ++b) {
    if (!std::isfinite(low[b])) continue;
    const double a = 2 * M_PI * (b + 0.5) / kBins;
    ss += low[b] * std::sin(a), sc += low[b] * std::cos(a), m += low[b], ++nb;
  }
  if (nb > 0 && d.amp_m > 0) {
    d.offset_m = m / nb;
    d.phase_rad = std::atan2(sc, ss);
    if (d.phase_rad < 0) d.phase_rad += 2 * M_PI;
  }
  return d;
}

Drift MeasureDrift(const SampledRun& run, const Periods& p, double travel_mm) {
  Drift d;
  const ModeWindow& w = p.settled;
  if (w.count == 0) return d;
  d.bouncing_sphere = w.summary.bouncing_sphere;
  d.speed = w.summary.drift_speed;
  d.speed_err = w.summary.drift_speed_err;
  const double f = 1.0 / p.period_s;
  d.scaled = d.speed * f / kGravity;
  d.scaled_err = d.speed_err * f / kGravity;
  d.periods = w.count;
  d.travel_mm = travel_mm;
  // Travel time: first frame after the window start whose CM is travel_mm away.
  const double x0 = CentreXAt(run, w.t_start);
  const size_t i0 = static_cast<size_t>(std::ceil((w.t_start - run.t0) / run.dt));
  double moved = 0;
  for (size_t i = i0; i < run.n; ++i) {
    if (!run.Valid(i)) continue;
    moved = std::abs(0.5 * (run.x[0][i] + run.x[1][i]) - x0);
    if (moved >= travel_mm * 1e-3) {
      d.travel_time_s = run.Time(i) - w.t_start;
      d.travel_speed = travel_mm * 1e-3 / d.travel_time_s;
      return d;
    }
  }
  d.travel_note = "the dimer moved " + Num(moved * 1e3, 3) + " mm after the settled window's start, less than " +
                  Num(travel_mm, 3) + " mm: no travel time";
  return d;
}

}  // namespace

std::vector<std::string> AnalysisOptions::Check() const {
  std::vector<std::string> e;
  if (!std::isnan(freq_hz) && !(freq_hz > 0 && std::isfinite(freq_hz)))
    e.push_back("--freq: " + Num(freq_hz) + ": expected a frequency > 0 Hz");
  if (!std::isnan(gamma) && !(gamma > 0 && std::isfinite(gamma)))
    e.push_back("--gamma: " + Num(gamma) + ": expected Gamma > 0");
  if (window_periods < 1) e.push_back("--mode-window: " + std::to_string(window_periods) + ": expected >= 1 period");
  if (phase_bins < 2 || phase_bins > 1000)
    e.push_back("--phase-bins: " + std::to_string(phase_bins) + ": expected 2..1000");
  if (!(travel_mm > 0)) e.push_back("--travel-mm: " + Num(travel_mm) + ": expected > 0 mm");
  return e;
}

AnalysisOptions SeenAsTrack(const Analysis& track, AnalysisOptions base) {
  for (int s = 0; s < 2; ++s) base.min_contact_threshold_m[s] = track.contacts.sphere[s].threshold_m;
  base.slip_half_window = track.slip.half_window;
  return base;
}

Analysis Analyze(const SampledRun& input, const AnalysisOptions& options) {
  DIMER_CHECK(input.x[0].size() == input.n && input.x[1].size() == input.n &&
                  input.z[0].size() == input.n && input.z[1].size() == input.n &&
                  input.plate_z.size() == input.n && input.theta.size() == input.n,
              "a sampled run holds one value per grid frame in every column");
  Analysis a;
  a.run = input;
  a.options = options;
  a.outliers = RejectOutliers(&a.run);
  const SampledRun& run = a.run;
  if (!a.outliers.empty()) {
    std::string list;
    for (size_t k = 0; k < a.outliers.size() && k < 10; ++k)
      list += (k ? ", " : "") + std::to_string(a.outliers[k].frame) + (a.outliers[k].sphere ? "R" : "L");
    a.warnings.push_back(std::to_string(a.outliers.size()) +
                         " tip positions rejected as tracking outliers (frame+sphere: " + list +
                         (a.outliers.size() > 10 ? ", ..." : "") + ")");
  }
  if (run.video_lossy) {
    a.warnings.push_back("the track comes from a lossy video (codec '" + run.video_codec +
                         "'): compression moves the spheres' edges by tenths of a pixel to pixels "
                         "(positions, A_r) and can hide impacts (docs/BENCHMARKS.md, compressed_video.sh)");
  }
  // 1. Plate drive.
  if (run.kind == "sim" && std::isfinite(run.sim_freq_hz) && std::isfinite(run.sim_gamma)) {
    a.plate = PlateFromSim(run);
  } else {
    a.plate = FitPlate(run, options.freq_hz);
    if (a.plate.source != "fit") {
      if (!std::isfinite(options.freq_hz) || !std::isfinite(options.gamma)) {
        throw InputError(run.path + ": no plate motion visible in the track; give the drive with --freq and --gamma");
      }
      a.plate = DriveFromOptions(run, options);
      a.warnings.push_back("no plate motion visible: drive taken from --freq " + Num(options.freq_hz) +
                           " Hz and --gamma " + Num(options.gamma) +
                           ", its phase estimated from the spheres' lowest points");
    } else {
      for (int k = 0; k < 3; ++k) {
        if (a.plate.harmonic_rel[k] > kHarmonicWarn)
          a.warnings.push_back("the drive is not sinusoidal: harmonic " + std::to_string(k + 2) + "f is " +
                               Num(100 * a.plate.harmonic_rel[k], 3) + " % of the fundamental");
      }
      if (std::isfinite(options.gamma)) UseGivenGamma(options.gamma, &a.plate, &a.warnings);
    }
  }
  const double duration = run.Time(run.n - 1) - run.t0;
  if (duration * a.plate.freq_hz < kMinPeriods - 1e-9) {
    throw InputError(run.path + ": " + Num(duration * a.plate.freq_hz, 3) +
                     " plate periods long; at least 2 are needed");
  }
  // 2. Contacts and impacts; 3. free fall; 4. periods and modes; 5. drift; 6. slip.
  a.contacts = FindContacts(run, a.plate, options.min_contact_threshold_m);
  a.free_fall = FitFreeFall(run, a.contacts);
  const double g_dev = std::abs(a.free_fall.g_fit - kGravity);
  if (std::isfinite(g_dev) && g_dev > kGFitWarn * kGravity && g_dev > 2 * a.free_fall.g_fit_err) {
    a.warnings.push_back("fitted free fall g_fit/g = " + Num(a.free_fall.g_fit / kGravity) +
                         ": the length calibration (m/px) is likely off by that factor");
  }
  a.periods = AnalyzePeriods(run, a.plate, a.contacts, options.window_periods);
  a.drift = MeasureDrift(run, a.periods, options.travel_mm);
  a.slip = AnalyzeSlip(run, a.plate, a.contacts, a.periods.settled, options.phase_bins,
                       options.slip_half_window);
  for (int s = 0; s < 2; ++s) {
    size_t missing = 0;
    for (const Gap& g : run.gaps[s]) missing += g.count;
    if (missing > 0)
      a.warnings.push_back(std::string(s ? "right" : "left") + " sphere missing in " + std::to_string(missing) +
                           " frames (" + std::to_string(run.gaps[s].size()) + " gaps); analysed where present");
  }
  return a;
}

}  // namespace dimer::compare
