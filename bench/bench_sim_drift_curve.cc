// The paper's Fig. 3(a) line: simulated drift speed <u> f/g against A_r at 25, 50 and 75 Hz
// (Gamma = 0.9 and the paper's friction and restitution), with the mode each run settled in and
// the impact types of the bouncing end's last collision. Usage: bench_sim_drift_curve [periods]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "sim/simulator.h"

using namespace dimer::sim;

int main(int argc, char** argv) {
  const double periods = argc > 1 ? std::atof(argv[1]) : 400;
  const double ars[] = {2.0, 2.5, 3.0, 3.5, 3.9, 4.5, 5.0, 5.5, 5.7, 6.1, 7.0, 8.0, 10.0};
  std::printf("| A_r | f (Hz) | mode | <u> f/g | +/- | events/period | last bouncing-end impact |\n");
  std::printf("|---:|---:|---|---:|---:|---:|---|\n");
  const auto t0 = std::chrono::steady_clock::now();
  for (double ar : ars) {
    for (double f : {25.0, 50.0, 75.0}) {
      SimOptions o;
      o.ar = ar;
      o.freq_hz = f;
      o.cycles = periods;
      o.fps = 0;
      const SimResult r = RunSimulation(o);
      std::string last;
      for (auto it = r.events.rbegin(); it != r.events.rend(); ++it) {
        if ((it->kind == EventKind::kImpact || it->kind == EventKind::kDoubleImpact) &&
            (it->sphere == r.mode.bouncing_sphere || it->sphere == 2)) {
          last = ToString(it->kind) + " " + it->detail;
          break;
        }
      }
      const double scale = f / kGravity;
      std::printf("| %.1f | %.0f | %s | %+.4f | %.4f | %.1f | %s |\n", ar, f, r.mode.label.c_str(),
                  r.mode.drift_speed * scale, r.mode.drift_speed_err * scale,
                  r.diag.events / static_cast<double>(r.periods.size()), last.c_str());
    }
  }
  std::printf("\n%.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return 0;
}
