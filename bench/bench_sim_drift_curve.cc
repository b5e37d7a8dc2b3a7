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

namespace {

// One run's row cells.
struct Cells {
  std::string mode, speed, err, events, last;
};

Cells RunAt(double ar, double f, double periods) {
  SimOptions o;
  o.ar = ar;
  o.freq_hz = f;
  o.cycles = periods;
  o.fps = 0;
  const SimResult r = RunSimulation(o);
  Cells c;
  for (auto it = r.events.rbegin(); it != r.events.rend(); ++it) {
    if ((it->kind == EventKind::kImpact || it->kind == EventKind::kDoubleImpact) &&
        (it->sphere == r.mode.bouncing_sphere || it->sphere == 2)) {
      c.last = ToString(it->kind) + " " + it->detail;
      break;
    }
  }
  const double scale = f / kGravity;
  char buf[64];
  c.mode = r.mode.label;
  std::snprintf(buf, sizeof buf, "%+.4f", r.mode.drift_speed * scale);
  c.speed = buf;
  std::snprintf(buf, sizeof buf, "%.4f", r.mode.drift_speed_err * scale);
  c.err = buf;
  std::snprintf(buf, sizeof buf, "%.1f", r.diag.events / static_cast<double>(r.periods.size()));
  c.events = buf;
  return c;
}

// The three frequencies' values, one where they agree, else joined by " / ".
std::string Joined(const std::string& a, const std::string& b, const std::string& c) {
  return a == b && b == c ? a : a + " / " + b + " / " + c;
}

}  // namespace

int main(int argc, char** argv) {
  const double periods = argc > 1 ? std::atof(argv[1]) : 400;
  const double ars[] = {2.0, 2.5, 3.0, 3.5, 3.9, 4.5, 5.0, 5.5, 5.7, 6.1, 7.0, 8.0, 10.0};
  std::printf("One row per A_r; where the three frequencies differ, their values as 25 / 50 / 75 "
              "Hz.\n\n");
  std::printf("| A_r | mode | <u> f/g, 25 Hz | 50 Hz | 75 Hz | +/- | events/period | last "
              "bouncing-end impact |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---|\n");
  const auto t0 = std::chrono::steady_clock::now();
  for (double ar : ars) {
    const Cells c[3] = {RunAt(ar, 25, periods), RunAt(ar, 50, periods), RunAt(ar, 75, periods)};
    std::printf("| %.1f | %s | %s | %s | %s | %s | %s | %s |\n", ar,
                Joined(c[0].mode, c[1].mode, c[2].mode).c_str(), c[0].speed.c_str(),
                c[1].speed.c_str(), c[2].speed.c_str(),
                Joined(c[0].err, c[1].err, c[2].err).c_str(),
                Joined(c[0].events, c[1].events, c[2].events).c_str(),
                Joined(c[0].last, c[1].last, c[2].last).c_str());
  }
  std::printf("\n%.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return 0;
}
