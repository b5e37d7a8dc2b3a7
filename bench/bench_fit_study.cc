// The fit study (docs/BENCHMARKS.md, bench_fit_study): does `compare --fit` recover coefficients
// it was not tuned on, and do its stated intervals hold the truth?
//   bench_fit_study [work_dir]
// Six drift scenes used by no test (A_r 2.5-6, Gamma 0.85-1.1, every coefficient away from the
// paper's), 100 periods each at 2000 samples/s, written as sim files and read back as a track
// is; each fitted at the default budget from the paper's coefficients and from a far start.
// Per fit: each coefficient as the report gives it (value +- half-width of its profile range
// when constrained, a bound, or nothing), whether each range holds the truth, chi2/dof and its
// p-value at the analysis floors as set, the factor the fit scaled them by (fit.h), simulations
// and wall time (one thread), and chi2/dof at the truth itself (FitChi2:
// 0 when the fit's trials reproduce the scene). Then the coverage over all fits.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "compare/fit.h"
#include "compare/sampled_run.h"
#include "sim/sim_file.h"
#include "sim/simulator.h"

using namespace dimer;

namespace {

struct Scene {
  double ar, gamma, eps, mu_hat, mu_hat_s, mu, mu_s;  // in the order of FitResult::params
};

// Each checked to settle in drift from the drift release within 100 periods.
const Scene kScenes[] = {{2.5, 0.9, 0.70, 0.08, 0.15, 0.15, 0.35}, {3.3, 1.0, 0.70, 0.08, 0.15, 0.15, 0.35},
                         {4.2, 0.85, 0.60, 0.12, 0.25, 0.30, 0.50}, {4.8, 1.05, 0.72, 0.07, 0.18, 0.18, 0.30},
                         {5.5, 1.0, 0.55, 0.14, 0.30, 0.30, 0.45},  {6.0, 1.1, 0.62, 0.09, 0.22, 0.35, 0.60}};

sim::SimOptions Coefficients(double eps, double mu_hat, double mu_hat_s, double mu, double mu_s) {
  sim::SimOptions o;
  o.eps = eps, o.mu_hat = mu_hat, o.mu_hat_s = mu_hat_s, o.mu = mu, o.mu_s = mu_s;
  return o;
}

std::string Cell(const compare::FitParameter& p, double truth, bool* holds) {
  char s[96];
  *holds = p.range_lo <= truth && truth <= p.range_hi;
  const char* mark = *holds ? "" : " **misses**";
  if (p.status == "constrained") std::snprintf(s, sizeof s, "%.4f ± %.4f%s", p.value, p.err, mark);
  else if (p.status == "bounded_above") std::snprintf(s, sizeof s, "≤ %.3g%s", p.range_hi, mark);
  else if (p.status == "bounded_below") std::snprintf(s, sizeof s, "≥ %.3g%s", p.range_lo, mark);
  else if (p.status == "unconstrained") std::snprintf(s, sizeof s, "unconstrained");
  else std::snprintf(s, sizeof s, "none");
  return s;
}

struct Tally {
  int fits = 0, acceptable = 0, constrained = 0, covered = 0, bounds = 0, bounds_hold = 0;
  double seconds = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string work = argc > 1 ? argv[1] : (std::filesystem::temp_directory_path() / "bench_fit_study").string();
  std::filesystem::create_directories(work);
  const sim::SimOptions starts[2] = {sim::SimOptions{}, Coefficients(0.85, 0.3, 0.6, 0.6, 1.2)};
  const char* start_names[2] = {"paper's", "far"};
  std::printf("## the fits (truth ε, μ̂, μ̂_s, μ, μ_s; start: the paper's 0.65, 0.1, 0.2, 0.2, 0.4 or far: "
              "0.85, 0.3, 0.6, 0.6, 1.2)\n\n");
  std::printf("| scene: A_r, Γ; truth | start | ε | μ̂ | μ̂_s | μ | μ_s | χ²/dof at the floors | p | floor scale | "
              "χ²/dof at the truth | simulations | s |\n");
  std::printf("|---|---|---|---|---|---|---|---:|---:|---:|---:|---:|---:|\n");
  std::fflush(stdout);
  Tally tally[2];
  for (const Scene& sc : kScenes) {
    sim::SimOptions o = Coefficients(sc.eps, sc.mu_hat, sc.mu_hat_s, sc.mu, sc.mu_s);
    o.ar = sc.ar;
    o.gamma = sc.gamma;
    o.cycles = 100;
    o.fps = 2000;
    char name[64];
    std::snprintf(name, sizeof name, "%s/ar%.1f_g%.2f.h5", work.c_str(), sc.ar, sc.gamma);
    sim::WriteSimFile(name, true, o, sim::RunSimulation(o));
    const compare::Analysis track = compare::Analyze(compare::LoadSampledRun(name), {});
    if (track.periods.settled.summary.label != "drift") {
      std::fprintf(stderr, "%s: settled in %s, not drift\n", name, track.periods.settled.summary.label.c_str());
      return 1;
    }
    const double truth[5] = {sc.eps, sc.mu_hat, sc.mu_hat_s, sc.mu, sc.mu_s};
    const double chi2_truth = compare::FitChi2(track, o, {});
    for (int k = 0; k < 2; ++k) {
      const compare::FitResult f = compare::FitCoefficients(track, starts[k], {});
      Tally& t = tally[k];
      ++t.fits;
      t.acceptable += f.acceptable;
      t.seconds += f.seconds;
      std::string cells;
      for (size_t j = 0; j < f.params.size(); ++j) {
        bool holds = false;
        cells += Cell(f.params[j], truth[j], &holds) + " | ";
        const std::string& st = f.params[j].status;
        if (st == "constrained") ++t.constrained, t.covered += holds;
        if (st == "bounded_above" || st == "bounded_below") ++t.bounds, t.bounds_hold += holds;
      }
      std::printf("| %.1f, %.2f; %.2f, %.2f, %.2f, %.2f, %.2f | %s | %s%.3g | %.3g | %.3g | %.3g | %d | %.0f |\n",
                  sc.ar, sc.gamma, sc.eps, sc.mu_hat, sc.mu_hat_s, sc.mu, sc.mu_s, start_names[k], cells.c_str(),
                  f.chi2_per_dof_at_floors, f.p_value_at_floors, f.floor_scale, chi2_truth / f.dof, f.evaluations,
                  f.seconds);
      std::fflush(stdout);
    }
  }
  std::printf("\n| start | fits | acceptable (p ≥ 0.001) | constrained values | their ranges hold the truth | "
              "bounds | bounds hold the truth | mean s per fit |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int k = 0; k < 2; ++k) {
    const Tally& t = tally[k];
    std::printf("| %s | %d | %d | %d | %d (%.0f %%) | %d | %d | %.0f |\n", start_names[k], t.fits, t.acceptable,
                t.constrained, t.covered, t.constrained ? 100.0 * t.covered / t.constrained : NAN, t.bounds,
                t.bounds_hold, t.seconds / t.fits);
  }
  return 0;
}
