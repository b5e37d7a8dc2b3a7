// Simulator speed: simulated plate periods per second on one core, in the drift mode and the
// other modes, with and without output sampling. Target (docs/BENCHMARKS.md): >= 10,000 periods/s in the
// drift mode at default tolerances. Usage: bench_sim_speed [periods]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "sim/simulator.h"

using namespace dimer::sim;

namespace {

struct Row {
  const char* label;
  SimOptions o;
};

double Seconds(const SimOptions& o, SimResult* out) {
  const auto t0 = std::chrono::steady_clock::now();
  RunControls c;
  c.keep_events = o.fps > 0;
  *out = RunSimulation(o, c);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const double periods = argc > 1 ? std::atof(argv[1]) : 20000;
  auto make = [&](double ar, double freq, InitKind init, double fps) {
    SimOptions o;
    o.ar = ar;
    o.freq_hz = freq;
    o.init = init;
    o.fps = fps;
    o.cycles = periods;
    return o;
  };
  const Row rows[] = {
      {"drift A_r 3.9, 25 Hz, events only", make(3.9, 25, InitKind::kDrift, 0)},
      {"drift A_r 3.9, 25 Hz, 2000 samples/s + event log", make(3.9, 25, InitKind::kDrift, 2000)},
      {"drift A_r 6.1, 25 Hz, events only", make(6.1, 25, InitKind::kDrift, 0)},
      {"drift A_r 3.9, 75 Hz, events only", make(3.9, 75, InitKind::kDrift, 0)},
      {"jump A_r 3.9, 25 Hz, events only", make(3.9, 25, InitKind::kJump, 0)},
      {"rest A_r 3.9, 25 Hz, events only", make(3.9, 25, InitKind::kRest, 0)},
  };
  std::printf("| case | periods | events/period | wall s | periods/s | settled |\n");
  std::printf("|---|---:|---:|---:|---:|---|\n");
  for (const Row& row : rows) {
    SimResult r;
    const double s = Seconds(row.o, &r);
    const double n = static_cast<double>(r.periods.size());
    std::printf("| %s | %.0f | %.1f | %.3f | %.0f | %s |\n", row.label, n, r.diag.events / n, s,
                n / s, r.mode.label.c_str());
  }
  return 0;
}
