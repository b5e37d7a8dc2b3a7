#include "sim/sweep_point.h"

#include <array>
#include <cmath>
#include <cstring>

#include "common/modes.h"
#include "sim/reference_frames.h"
#include "sim/initial_conditions.h"
#include "sim/simulator.h"

namespace dimer::sim {
namespace {

const char* const kImpactTypes[3] = {"continuous_slide", "slip_stick", "slip_reversal"};

// Impact types per sphere, by how the slip ended, of the impacts inside the measured window,
// tallied as the simulator logs them: the log itself is not kept (RunControls::on_event).
struct ImpactTally {
  double t0 = 0, t1 = 0;  // the window [t0, t1), absolute time, s
  std::array<std::array<long, 3>, 2> counts{};  // [sphere][type]

  // An impact's detail reads "L:slip_stick R:continuous_slide" (either part may be missing).
  void See(const EventRecord& e) {
    if (e.t < t0 || e.t >= t1) return;
    if (e.kind != EventKind::kImpact && e.kind != EventKind::kDoubleImpact) return;
    for (int s = 0; s < 2; ++s) {
      const size_t at = e.detail.find(s == kLeft ? "L:" : "R:");
      if (at == std::string::npos) continue;
      for (int k = 0; k < 3; ++k) {
        if (e.detail.compare(at + 2, std::strlen(kImpactTypes[k]), kImpactTypes[k]) == 0) {
          ++counts[s][k];
        }
      }
    }
  }
  // The bouncing end's (sphere 0 or 1) or both ends' (-1) impacts.
  std::array<long, 3> Of(int sphere) const {
    std::array<long, 3> out{};
    for (int s = 0; s < 2; ++s) {
      if (sphere >= 0 && s != sphere) continue;
      for (int k = 0; k < 3; ++k) out[k] += counts[s][k];
    }
    return out;
  }
};

}  // namespace

PointResult RunSweepPoint(const SweepSpec& spec, size_t i,
                          const std::function<bool()>& should_stop) {
  const SimOptions o = spec.PointOptions(i);
  const long first = spec.transient, count = spec.periods;
  // The window in absolute time, as the run will place it: it starts at its initial
  // condition's t0 (the simulator's t_start) and its periods are the model's.
  ImpactTally tally;
  if (o.Check().empty()) {  // otherwise RunSimulation reports the options
    const Model m = Model::FromOptions(o);
    const double t_start = MakeInitialCondition(m, o).t0;
    tally.t0 = t_start + first * m.period;
    tally.t1 = t_start + (first + count) * m.period;
  }
  RunControls controls;
  // The impact types are tallied as the events come: a kept log would hold the whole run, ~200
  // bytes per event, ~20 events per period in drift (~0.4 GB per thread at 10^5 periods).
  controls.keep_events = false;
  controls.on_event = [&tally](const EventRecord& e) { tally.See(e); };
  controls.should_stop = should_stop;
  const SimResult r = RunSimulation(o, controls);
  PointResult p;
  if (r.interrupted) return p;  // index -1: not finished
  p.index = static_cast<int64_t>(i);
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
  p.orbit_periods = static_cast<int8_t>(ms.orbit_periods);
  const std::array<long, 3> counts = tally.Of(ms.mode == Mode::kDrift ? ms.bouncing_sphere : -1);
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
