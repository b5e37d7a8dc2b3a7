// compare benchmark: the speed of the analysis as a user runs it, and the fit's budget against
// its accuracy (docs/BENCHMARKS.md, bench_compare).
//   bench_compare DIMERLAB_BINARY [work_dir]
// 1. A 20,000-frame track (250 periods of the paper's drift at 2000 frames/s, rendered backlit
//    with sensor noise and tracked, 0.4 mm/px): `dimerlab compare track.h5 -o REPORT` wall time
//    from the shell (process start, file reading, report with gnuplot figures), and the
//    in-memory analysis alone (Analyze) on one core. Target: < 2 s on one core.
// 2. A 100-period track of a drift simulated with eps 0.6, mu_hat 0.12 (not the paper's, where
//    the fit starts): the fit at several budgets (multi-start / local evaluations): wall time,
//    simulations, chi2 and the errors of eps and mu_hat; and `dimerlab compare --simulate --fit`
//    end to end at the default budget. Target: < 60 s on 2 cores.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "compare/analysis.h"
#include "compare/fit.h"
#include "sim/sim_file.h"
#include "sim/simulator.h"
#include "render/render.h"
#include "tracking/run_track.h"

using namespace dimer;
using Clock = std::chrono::steady_clock;

namespace {

double Seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

// Simulate, render backlit at 0.4 mm/px (400 x 128) and track: the track file's path.
std::string MakeTrack(const std::string& dir, double cycles, double eps, double mu_hat) {
  std::filesystem::create_directories(dir);
  sim::SimOptions o;
  o.cycles = cycles;
  o.eps = eps;
  o.mu_hat = mu_hat;
  const sim::SimResult r = sim::RunSimulation(o);
  sim::WriteSimFile(dir + "/sim.h5", true, o, r);
  tracking::RenderArgs ra;
  ra.input = dir + "/sim.h5";
  ra.output = dir + "/frames";
  ra.force = true;
  ra.quiet = true;
  ra.m_per_px = 4e-4;
  ra.image.width = 400 + static_cast<int>(2.5 * cycles);  // room for the drift (~0.9 mm = 2.2 px per period)
  ra.image.height = 128;
  ra.image.lighting = tracking::Lighting::kBacklit;
  tracking::RunRender(ra);
  tracking::TrackArgs ta;
  ta.input = ra.output;
  ta.output = dir + "/track.h5";
  ta.force = true;
  ta.quiet = true;
  ta.m_per_px = 4e-4;
  tracking::RunTrack(ta);
  return ta.output;
}

double Shell(const std::string& cmd) {
  const auto t0 = Clock::now();
  if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "failed: %s\n", cmd.c_str());
  return Seconds(t0);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_compare DIMERLAB_BINARY [work_dir]\n");
    return 2;
  }
  const std::string bin = argv[1];
  const std::string work = argc > 2 ? argv[2] : (std::filesystem::temp_directory_path() / "bench_compare").string();
  std::printf("## compare of a 20,000-frame track (250 periods, drift, backlit, 0.4 mm/px)\n\n");
  const std::string big = MakeTrack(work + "/big", 250, 0.65, 0.1);
  {
    const auto run = compare::LoadSampledRun(big);
    const auto t0 = Clock::now();
    const compare::Analysis a = compare::Analyze(run, {});
    const double analyse = Seconds(t0);
    const double cli1 = Shell("taskset -c 0 " + bin + " compare " + big + " -o " + work + "/big_report --force -q > /dev/null");
    const double cli2 = Shell(bin + " compare " + big + " -o " + work + "/big_report --force -q > /dev/null");
    std::printf("| what | frames | s |\n|---|---:|---:|\n");
    std::printf("| Analyze in memory (one thread) | %zu | %.3f |\n", run.n, analyse);
    std::printf("| `dimerlab compare` from the shell, pinned to one core (start, read, analyse, compare.h5, 5 gnuplot figures) | %zu | %.3f |\n", run.n, cli1);
    std::printf("| the same on both cores | %zu | %.3f |\n\n", run.n, cli2);
    std::printf("settled mode %s, <u> f/g = %.5f\n\n", a.periods.settled.summary.label.c_str(), a.drift.scaled);
  }
  std::printf("## --fit on a 100-period track (truth eps 0.6, mu_hat 0.12; start at the paper's 0.65, 0.1)\n\n");
  const std::string track = MakeTrack(work + "/fit", 100, 0.6, 0.12);
  const compare::Analysis a = compare::Analyze(compare::LoadSampledRun(track), {});
  std::printf("| multi-start / local evaluations | simulations | s | chi2 / dof | eps (err %%) | mu_hat (err %%) | mu_hat_s |\n");
  std::printf("|---|---:|---:|---:|---|---|---|\n");
  const int budgets[][2] = {{0, 40}, {50, 60}, {150, 100}, {300, 150}, {600, 300}};
  for (const auto& b : budgets) {
    compare::FitOptions fo;
    fo.global_evaluations = b[0];
    fo.max_evaluations = b[1];
    const compare::FitResult f = compare::FitCoefficients(a, sim::SimOptions{}, fo);
    const auto& e = f.params[0];
    const auto& m = f.params[1];
    std::printf("| %d / %d%s | %d | %.1f | %.2f | %.4f (%+.2f) %s | %.4f (%+.1f) %s | %s |\n", b[0], b[1],
                b[0] == 300 ? " (default)" : "", f.evaluations, f.seconds, f.chi2 / f.dof, e.value,
                100 * (e.value / 0.6 - 1), e.status.c_str(), m.value, 100 * (m.value / 0.12 - 1), m.status.c_str(),
                f.params[2].status.c_str());
  }
  const double cli = Shell(bin + " compare " + track + " --simulate --fit -o " + work + "/fit_report --force -q > /dev/null");
  std::printf("\n`dimerlab compare track.h5 --simulate --fit` (100 periods, default budget, both cores): %.1f s\n", cli);
  return 0;
}
