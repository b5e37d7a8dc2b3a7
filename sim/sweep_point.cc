#include "sim/sweep_point.h"

#include <cmath>

#include "common/modes.h"
#include "sim/frames.h"
#include "sim/simulator.h"

namespace dimer::sim {
namespace {

const char* const kImpactTypes[3] = {"continuous_slide", "slip_stick", "slip_reversal"};

// Tallies the impact types of `sphere` (or both, -1) in an impact's detail ("L:slip_stick R:...").
void CountImpactTypes(const std::string& detail, int sphere, std::array<long, 3>* counts) {
  for (int s = 0; s < 2; ++s) {
    if (sphere >= 0 && s != sphere) continue;
    const std::string tag = s == kLeft ? "L:" : "R:";
    const size_t at = detail.find(tag);
    if (at == std::string::npos) continue;
    const std::string rest = detail.substr(at + 2);
    for (int k = 0; k < 3; ++k) {
      if (rest.rfind(kImpactTypes[k], 0) == 0) ++(*counts)[k];
    }
  }
}

}  // namespace

PointResult RunSweepPoint(const SweepSpec& spec, size_t i,
                          const std::function<bool()>& should_stop) {
  const SimOptions o = spec.PointOptions(i);
  RunControls controls;
  // The impact types need the event log. It holds the whole run (the simulator has no window):
  // ~200 bytes per event, ~20 events per period in drift, so ~1 MB for 300 periods but ~0.4 GB
  // per thread for 10^5 periods. Long windows want an event callback in RunControls instead.
  controls.keep_events = true;
  controls.should_stop = should_stop;
  const SimResult r = RunSimulation(o, controls);
  PointResult p;
  if (r.interrupted) return p;  // index -1: not finished
  p.index = static_cast<int64_t>(i);
  const long first = spec.transient, count = spec.periods;
  if (!r.error.empty() || static_cast<long>(r.periods.size()) < first + count ||
      static_cast<long>(r.lab.size()) < first + count + 1) {
    p.error = r.error.empty() ? "the run ended before the window's end" : r.error;
    return p;
  }
  // The window's end state: sample k is at t_start + k T (fps = f), so sample first + count.
  const State& lab = r.lab[first + count];
  std::array<int, 2> dir{};
  for (int s = 0; s < 2; ++s) {
    const double dx = TipLab(r.model, lab, s).x() - TipLab(r.model, lab, 1 - s).x();
    dir[s] = dx >= 0 ? 1 : -1;
  }
  // The drift is measured along the plate, as the simulator measures it (PeriodStats::x_start is
  // the plate frame's x): the window's end in the same frame (SweepTest.PointEqualsSimulation*).
  const double x_end = PlateFromLab(r.model, r.t[first + count], lab).x;
  const ModeSummary ms = ClassifyPeriods(r.periods, static_cast<int>(first),
                                         static_cast<int>(count), r.model.period, x_end, dir);
  p.mode = ms.label;
  p.bouncing_sphere = static_cast<int8_t>(ms.bouncing_sphere);
  p.drift_speed = ms.drift_speed;
  p.drift_speed_err = ms.drift_speed_err;
  p.drift_scaled = ms.drift_speed * o.freq_hz / kGravity;
  p.drift_scaled_err = ms.drift_speed_err * o.freq_hz / kGravity;
  if (spec.init == SweepInit::kDrift) {
    p.drift_survived = ms.mode == Mode::kDrift && ms.bouncing_sphere == kRight ? 1 : 0;
  }
  long events = 0;
  for (long k = first; k < first + count; ++k) events += r.periods[k].events;
  p.events_per_period = static_cast<double>(events) / static_cast<double>(count);
  p.impacts_per_period = ms.impacts_per_period;
  p.rest_fraction = ms.rest_fraction;
  // Impacts inside the window [t_start + first T, t_start + (first + count) T).
  const double t0 = r.t_start + first * r.model.period;
  const double t1 = r.t_start + (first + count) * r.model.period;
  std::array<long, 3> counts{};
  const int sphere = ms.mode == Mode::kDrift ? ms.bouncing_sphere : -1;
  for (const EventRecord& e : r.events) {
    if (e.t < t0 || e.t >= t1) continue;
    if (e.kind != EventKind::kImpact && e.kind != EventKind::kDoubleImpact) continue;
    CountImpactTypes(e.detail, sphere, &counts);
  }
  const long total = counts[0] + counts[1] + counts[2];
  if (total > 0) {
    int best = 0;
    for (int k = 1; k < 3; ++k) {
      if (counts[k] > counts[best]) best = k;
    }
    p.impact_type = kImpactTypes[best];
    p.impact_type_fraction = static_cast<double>(counts[best]) / static_cast<double>(total);
  }
  return p;
}

}  // namespace dimer::sim
