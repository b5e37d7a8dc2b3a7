#include "compare/locked_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "common/error.h"
#include "compare/slip.h"

namespace dimer::compare {
namespace {

// Phase bins: one per frame of a period (every frame of a settled orbit strobed at a whole
// number of frames per period falls in its own bin), within these bounds.
constexpr int kMinBins = 8;
constexpr int kMaxBins = 400;
constexpr int kMinPerBin = 3;        // frames a bin's average needs
constexpr int kMinEstimateBins = 8;  // bins an estimate needs
// A frame of steady contact: the resting sphere rests on it and on this many frames either side,
// so that a landing's first frames, where the gap still closes, are left out.
constexpr int kSteadyFrames = 3;
// Below this an estimate is a simulation's rounding (1e-17 m), not a camera's error: zero, so
// that a sim file is fitted exactly as without this term.
constexpr double kResolvedM = 1e-9;
constexpr uint64_t kDrawSeed = 20260715;  // any fixed value: the draws, and so the fit, repeat

struct BinStats {
  std::vector<double> mean;    // NaN where a bin has fewer than kMinPerBin frames
  double noise_var = 0;        // mean over the kept bins of var / count (the noise's share)
  int kept = 0;
};

// slip.h's phase average, less the bins of fewer than kMinPerBin frames. `phase` is NaN on the
// frames left out.
BinStats AverageByPhase(const std::vector<double>& v, const std::vector<double>& phase, int bins) {
  std::vector<double> centres, mean, err;
  std::vector<int> count;
  PhaseAverage(phase, v, bins, &centres, &mean, &err, &count);
  BinStats s;
  s.mean.assign(bins, NAN);
  for (int b = 0; b < bins; ++b) {
    if (count[b] < kMinPerBin) continue;
    s.mean[b] = mean[b];
    s.noise_var += err[b] * err[b];
    ++s.kept;
  }
  if (s.kept) s.noise_var /= s.kept;
  return s;
}

// A standard normal from two uniforms: written out, so that the draws are the same with any
// standard library (std::normal_distribution's algorithm is the library's own).
double Normal(std::mt19937_64* g) {
  const double u1 = (static_cast<double>((*g)() >> 11) + 0.5) * 0x1.0p-53;
  const double u2 = static_cast<double>((*g)() >> 11) * 0x1.0p-53;
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

// The spread of `v` below its core: values that a right-sided contamination (hops) leaves alone
// scatter symmetrically about the core's centre, so the root mean square of those below it is
// their standard deviation. The centre is the median of the values not beyond kHopSigmas of
// that spread above it, found again until the set stops changing: with the plain median, hops of
// 10 um on a third of the phases made 2 um of error read as 3.9 um
// (LockedError.AHopTooSmallToSeeIsNotError). 0 when nothing lies below the centre.
double SpreadBelowCore(std::vector<double> v) {
  constexpr double kHopSigmas = 3.0;
  constexpr int kMaxRounds = 20;
  std::sort(v.begin(), v.end());
  size_t top = v.size();  // v[0, top) is the core
  double spread = 0;
  for (int round = 0; round < kMaxRounds && top > 0; ++round) {
    const double centre = top % 2 ? v[top / 2] : 0.5 * (v[top / 2 - 1] + v[top / 2]);
    double q = 0;
    size_t below = 0;
    for (size_t i = 0; i < top && v[i] < centre; ++i) q += (v[i] - centre) * (v[i] - centre), ++below;
    spread = below ? std::sqrt(q / below) : 0.0;
    size_t next = top;
    while (next > 0 && v[next - 1] > centre + kHopSigmas * spread) --next;
    if (next == top) break;
    top = next;
  }
  return spread;
}

}  // namespace

LockedError MeasureLockedError(const Analysis& a) {
  LockedError e;
  const SampledRun& run = a.run;
  if (run.n == 0 || !(a.plate.freq_hz > 0) || !(run.dt > 0)) return e;
  const int bins = std::clamp(static_cast<int>(std::lround(1.0 / (run.dt * a.plate.freq_hz))), kMinBins, kMaxBins);
  e.phase_bins = bins;
  const ModeWindow& w = a.periods.settled;
  std::vector<double> phase(run.n, NAN);
  for (size_t i = 0; i < run.n; ++i) {
    const double t = run.Time(i);
    if (w.count == 0 || (t >= w.t_start && t < w.t_end)) phase[i] = a.plate.PhaseFraction(t);
  }
  // The length: its phase averages spread by the two centres' error along the rod.
  std::vector<double> length(run.n, NAN);
  for (size_t i = 0; i < run.n; ++i)
    if (run.Valid(i)) length[i] = std::hypot(run.x[1][i] - run.x[0][i], run.z[1][i] - run.z[0][i]);
  const BinStats ls = AverageByPhase(length, phase, bins);
  if (ls.kept >= kMinEstimateBins) {
    double mean = 0, q = 0;
    for (double m : ls.mean)
      if (std::isfinite(m)) mean += m / ls.kept;
    for (double m : ls.mean)
      if (std::isfinite(m)) q += (m - mean) * (m - mean);
    const double spread = ls.kept > 1 ? q / (ls.kept - 1) : 0;
    e.col_m = std::sqrt(std::max(0.0, spread - ls.noise_var) / 2);
    if (e.col_m < kResolvedM) e.col_m = 0;
    e.length_bins = ls.kept;
  }
  // The resting sphere's height above the plate over steady contact: only its spread below the
  // core is error (a hop too small to be seen as one only ever raises it; SpreadBelowCore).
  int rs = a.slip.resting_sphere;
  if (rs < 0 && w.summary.bouncing_sphere >= 0) rs = 1 - w.summary.bouncing_sphere;
  e.row_m = e.col_m;
  e.row_source = "length";
  if (rs < 0) return e;
  const SphereContacts& c = a.contacts.sphere[rs];
  std::vector<double> height(run.n, NAN);
  const long n = static_cast<long>(run.n);
  for (long i = kSteadyFrames; i + kSteadyFrames < n; ++i) {
    bool steady = true;
    for (long j = i - kSteadyFrames; j <= i + kSteadyFrames && steady; ++j) steady = c.resting[j] != 0;
    if (steady) height[i] = c.gap[i];
  }
  const BinStats hs = AverageByPhase(height, phase, bins);
  if (hs.kept < kMinEstimateBins) return e;
  std::vector<double> kept;
  for (double m : hs.mean)
    if (std::isfinite(m)) kept.push_back(m);
  const double spread = SpreadBelowCore(kept);
  e.row_m = std::sqrt(std::max(0.0, spread * spread - hs.noise_var));
  if (e.row_m < kResolvedM) e.row_m = 0;
  e.rest_bins = hs.kept;
  e.row_source = "resting_height";
  return e;
}

std::vector<std::vector<double>> LockedErrorDeviations(const Analysis& track, const LockedError& e,
                                                       const std::vector<Observable>& observed,
                                                       int draws) {
  std::vector<std::vector<double>> out;
  if (!(e.col_m > 0 || e.row_m > 0) || e.phase_bins <= 0) return out;
  const SampledRun& run = track.run;
  const int bins = e.phase_bins;
  std::vector<int> bin(run.n, 0);
  for (size_t i = 0; i < run.n; ++i) {
    const double p = track.plate.PhaseFraction(run.Time(i));
    bin[i] = std::isfinite(p) ? std::min(bins - 1, static_cast<int>(p * bins)) : 0;
  }
  const AnalysisOptions seen = SeenAsTrack(track, track.options);
  std::mt19937_64 g(kDrawSeed);
  for (int d = 0; d < draws; ++d) {
    SampledRun moved = run;
    for (int s = 0; s < 2; ++s) {
      std::vector<double> dx(bins), dz(bins);
      for (int b = 0; b < bins; ++b) dx[b] = e.col_m * Normal(&g), dz[b] = e.row_m * Normal(&g);
      for (size_t i = 0; i < run.n; ++i) moved.x[s][i] += dx[bin[i]], moved.z[s][i] += dz[bin[i]];
    }
    for (size_t i = 0; i < run.n; ++i)
      moved.theta[i] = std::atan2(moved.z[1][i] - moved.z[0][i], moved.x[1][i] - moved.x[0][i]);
    std::vector<Observable> o;
    try {
      o = TrackObservables(Analyze(moved, seen));
    } catch (const InputError&) {
      continue;  // a draw the analysis refuses says nothing about the others
    }
    std::vector<double> dev(observed.size(), 0.0);
    for (size_t k = 0; k < observed.size() && k < o.size(); ++k)
      if (o[k].name == observed[k].name && std::isfinite(o[k].value) && std::isfinite(observed[k].value))
        dev[k] = o[k].value - observed[k].value;
    out.push_back(dev);
  }
  return out;
}

}  // namespace dimer::compare
