// The speed/accuracy trade of the simulator's three numerical knobs (measure, never
// guess): the impact-location tolerance (--gap-tol), the inelastic-collapse threshold
// (--collapse-vc) and the persistent-contact integration tolerance (--contact-tol). For each,
// the drift speed <u> f/g at A_r = 3.9, 25 Hz (paper parameters), the events per period and
// the run time are printed against the knob, the other two knobs held at their finest values.
// The "converged" reference is the run with all three at their finest. The defaults must be
// within 0.1 % of it. Usage: bench_sim_accuracy [periods] [ar]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "sim/simulator.h"

using namespace dimer::sim;

namespace {

constexpr double kFinestGap = 1e-15, kFinestVc = 1e-7, kFinestContact = 1e-13;

struct Outcome {
  double scaled, events, seconds;
  std::string mode;
};

Outcome Run(SimOptions o) {
  o.fps = 0;
  RunControls c;
  c.keep_events = false;
  const auto t0 = std::chrono::steady_clock::now();
  const SimResult r = RunSimulation(o, c);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {r.mode.drift_speed * o.freq_hz / kGravity,
          r.diag.events / static_cast<double>(r.periods.size()), s, r.mode.label};
}

SimOptions Finest(double periods, double ar) {
  SimOptions o;
  o.cycles = periods;
  o.ar = ar;
  o.gap_tol = kFinestGap;
  o.collapse_rel = kFinestVc;
  o.contact_tol = kFinestContact;
  return o;
}

void Table(const char* knob, const std::vector<double>& values, double dflt, double ref,
           double periods, double ar, void (*set)(SimOptions&, double)) {
  std::printf("\n%s (default %.0e)\n\n", knob, dflt);
  std::printf("| %s | <u> f/g | rel. diff. from converged | events/period | s per 1000 periods |"
              " mode |\n|---:|---:|---:|---:|---:|---|\n", knob);
  for (double v : values) {
    SimOptions o = Finest(periods, ar);
    set(o, v);
    const Outcome out = Run(o);
    std::printf("| %.0e%s | %.6f | %+.2e | %.2f | %.3f | %s |\n", v, v == dflt ? " (default)" : "",
                out.scaled, (out.scaled - ref) / std::abs(ref), out.events,
                1000 * out.seconds / periods, out.mode.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  const double periods = argc > 1 ? std::atof(argv[1]) : 400;
  const double ar = argc > 2 ? std::atof(argv[2]) : 3.9;
  const SimOptions defaults;
  const Outcome ref = Run(Finest(periods, ar));
  const Outcome def = [&] {
    SimOptions o;
    o.cycles = periods;
    o.ar = ar;
    return Run(o);
  }();
  std::printf("A_r %.2f, 25 Hz, Gamma 0.9, %.0f periods (drift speed over the last half)\n", ar,
              periods);
  std::printf("converged (gap %.0e m, v_c %.0e g/f, contact %.0e): <u> f/g = %.8f, "
              "%.2f events/period\n", kFinestGap, kFinestVc, kFinestContact, ref.scaled,
              ref.events);
  std::printf("defaults: <u> f/g = %.8f, relative difference %+.2e (target |diff| <= 1e-3), "
              "%.3f s per 1000 periods\n", def.scaled, (def.scaled - ref.scaled) / std::abs(ref.scaled),
              1000 * def.seconds / periods);
  // The round-off floor of the relative differences: the converged run with the plate's phase
  // shifted by whole periods is the same physics with different rounding. Differences below
  // it (the finest contact_tol rows) are round-off, not the knob.
  double floor_rel = 0;
  for (double shift : {1.0, 2.0, -1.0}) {
    SimOptions o = Finest(periods, ar);
    o.plate_phase = shift;
    floor_rel = std::max(floor_rel, std::abs(Run(o).scaled - ref.scaled) / std::abs(ref.scaled));
  }
  std::printf("round-off floor (converged run, plate phase shifted by -1, 1, 2 periods): "
              "relative difference up to %.1e\n", floor_rel);
  Table("gap_tol [m]", {1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8}, defaults.gap_tol,
        ref.scaled, periods, ar, [](SimOptions& o, double v) { o.gap_tol = v; });
  Table("collapse_vc [g/f]", {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2}, defaults.collapse_rel,
        ref.scaled, periods, ar, [](SimOptions& o, double v) { o.collapse_rel = v; });
  Table("contact_tol", {1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5}, defaults.contact_tol,
        ref.scaled, periods, ar, [](SimOptions& o, double v) { o.contact_tol = v; });
  return 0;
}
