#include "compare/periods.h"

#include <algorithm>
#include <cmath>

namespace dimer::compare {
namespace {

// A boundary this close to a frame (fraction of a frame) is that frame.
constexpr double kOnFrame = 1e-6;
constexpr double kBoundarySlack = 1e-6;  // of a period

// The period an event at time t belongs to. An impact on a boundary (a jump orbit started at
// an impact has all its impacts there) belongs to the period it starts, whatever the last bits
// of its fitted time say.
long PeriodOf(const SampledRun& run, double period_s, double t) {
  return static_cast<long>(std::floor((t - run.t0) / period_s + kBoundarySlack));
}

}  // namespace

bool SignificantImpact(const Impact& imp, double period_s) {
  const double v = std::isfinite(imp.v_before) ? std::abs(imp.v_before) : imp.speed_bound;
  return !(v <= kSignificantImpactRel * kGravity * period_s);
}

namespace {

double CentreX(const SampledRun& run, long i) { return 0.5 * (run.x[0][i] + run.x[1][i]); }

// Sign of (x of sphere s - x of the other) at the last valid frame at or before t.
std::array<int, 2> BounceDir(const SampledRun& run, double t) {
  long i = std::min<long>(static_cast<long>(run.n) - 1, std::lround((t - run.t0) / run.dt));
  while (i > 0 && !run.Valid(i)) --i;
  const int right_of = run.x[1][i] >= run.x[0][i] ? 1 : -1;
  return {-right_of, right_of};
}

ModeWindow Window(const SampledRun& run, const Periods& p, const std::vector<PeriodStats>& stats,
                  const std::vector<double>& x_bound, int first, int count) {
  ModeWindow w;
  w.first = first;
  w.count = count;
  w.t_start = p.rows[first].t_start;
  w.t_end = w.t_start + count * p.period_s;
  w.summary = ClassifyPeriods(stats, first, count, p.period_s, x_bound[first + count],
                              BounceDir(run, w.t_end));
  return w;
}

}  // namespace

double CentreXAt(const SampledRun& run, double t) {
  const double f = (t - run.t0) / run.dt;
  const long k = std::lround(f);
  if (std::abs(f - k) < kOnFrame && k >= 0 && k < static_cast<long>(run.n)) return CentreX(run, k);
  long a = static_cast<long>(std::floor(f)) - 1;
  a = std::clamp<long>(a, 0, static_cast<long>(run.n) - 4);
  double sum = 0;
  for (long j = a; j < a + 4; ++j) {
    double w = 1;
    for (long m = a; m < a + 4; ++m)
      if (m != j) w *= (f - m) / static_cast<double>(j - m);
    sum += w * CentreX(run, j);
  }
  return sum;
}

Periods AnalyzePeriods(const SampledRun& run, const PlateDrive& plate, const Contacts& contacts,
                       int window_periods) {
  Periods p;
  p.period_s = plate.period();
  const double t_last = run.Time(run.n - 1);
  const long whole = static_cast<long>(std::floor((t_last - run.t0) / p.period_s + kOnFrame));
  std::vector<double> x_bound;
  for (long k = 0; k <= whole; ++k) x_bound.push_back(CentreXAt(run, run.t0 + k * p.period_s));
  for (long k = 0; k < whole; ++k) {
    PeriodRow row;
    row.t_start = run.t0 + k * p.period_s;
    row.stats.x_start = x_bound[k];
    const double t_end = row.t_start + p.period_s;
    // Frames of the period: [t_start, t_end).
    const long a = static_cast<long>(std::ceil((row.t_start - run.t0) / run.dt - kOnFrame));
    const long b = static_cast<long>(std::ceil((t_end - run.t0) / run.dt - kOnFrame));
    int missing = 0;
    for (long i = a; i < b && i < static_cast<long>(run.n); ++i) {
      if (!run.Valid(i)) ++missing;
      for (int s = 0; s < 2; ++s) {
        const SphereContacts& c = contacts.sphere[s];
        if (c.resting[i]) row.stats.rest_time[s] += run.dt;
        if (std::isfinite(c.gap[i])) row.elevation_m[s] = std::max(row.elevation_m[s], c.gap[i] - c.level_m);
      }
    }
    for (int s = 0; s < 2; ++s) {
      for (const Impact& imp : contacts.sphere[s].impacts) {
        if (SignificantImpact(imp, p.period_s) && PeriodOf(run, p.period_s, imp.t) == k) ++row.stats.impacts[s];
      }
    }
    row.energy_gT2 = (row.elevation_m[0] + row.elevation_m[1]) / (kGravity * p.period_s * p.period_s);
    row.missing_fraction = static_cast<double>(missing) / std::max<long>(1, b - a);
    row.complete = row.missing_fraction <= kMaxMissingInPeriod;
    p.rows.push_back(row);
  }
  if (whole == 0) return p;
  p.x_end = x_bound[whole];
  std::vector<PeriodStats> stats;  // the rows' statistics, once (windows only index into them)
  for (const PeriodRow& r : p.rows) stats.push_back(r.stats);
  // Timeline: consecutive windows; a window with an incomplete period is not labelled.
  const int n = static_cast<int>(whole);
  const int w = std::max(1, window_periods);
  for (int first = 0; first + w <= n; first += w) {
    bool ok = true;
    for (int k = first; k < first + w; ++k) ok = ok && p.rows[k].complete;
    if (ok) p.timeline.push_back(Window(run, p, stats, x_bound, first, w));
  }
  // Settled: SettledWindow(n) periods ending at the last complete one, shortened to the
  // complete periods before it (a track whose last frames are lost is judged where it is good).
  int last = n - 1;
  while (last >= 0 && !p.rows[last].complete) --last;
  int first = last + 1, count = 0;
  while (first > 0 && count < SettledWindow(n) && p.rows[first - 1].complete) --first, ++count;
  if (count > 0) p.settled = Window(run, p, stats, x_bound, first, count);
  return p;
}

}  // namespace dimer::compare
