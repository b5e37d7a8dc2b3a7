// The tracker's error locked to the drive's phase (compare/locked_error.h): measured from the
// dimer's length and the resting sphere's height, blind to hops too small to see, and carried
// into the fit so that the truth stays an acceptable fit of a track that carries such an error.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compare/fit.h"
#include "compare/fit_observables.h"
#include "compare/goodness_of_fit.h"
#include "compare/locked_error.h"
#include "compare/simulate.h"

namespace dimer::compare {
namespace {

// A settled drift (A_r 3.9, 100 periods at 2000 frames/s: 80 phase bins).
sim::SimOptions DriftScene() {
  sim::SimOptions o;
  o.ar = 3.9;
  o.eps = 0.6;
  o.mu_hat = 0.12;
  o.cycles = 100;
  return o;
}

const Analysis& Truth() {
  static const Analysis a = SimulateAndAnalyze(DriftScene(), {}, "truth");
  return a;
}

int Bin(const Analysis& a, size_t i, int bins) {
  return std::min(bins - 1, static_cast<int>(a.plate.PhaseFraction(a.run.Time(i)) * bins));
}

// The truth's run with, per sphere, an error that repeats with the drive's phase (white over
// 80 bins: col_sd and row_sd), a frame-to-frame noise (noise_sd) and, on the resting sphere's
// height, `hop` added on every bin whose index is a multiple of 3 (a hop too small to see).
Analysis WithErrors(double col_sd, double row_sd, double noise_sd, double hop = 0) {
  const Analysis& t = Truth();
  SampledRun run = t.run;
  std::mt19937_64 g(7);
  std::normal_distribution<double> n01(0, 1);
  constexpr int kBins = 80;
  const int resting = t.slip.resting_sphere;
  for (int s = 0; s < 2; ++s) {
    std::vector<double> dx(kBins), dz(kBins);
    for (int b = 0; b < kBins; ++b) dx[b] = col_sd * n01(g), dz[b] = row_sd * n01(g);
    for (size_t i = 0; i < run.n; ++i) {
      const int b = Bin(t, i, kBins);
      run.x[s][i] += dx[b] + noise_sd * n01(g);
      run.z[s][i] += dz[b] + noise_sd * n01(g) + (s == resting && b % 3 == 0 ? hop : 0.0);
    }
  }
  for (size_t i = 0; i < run.n; ++i)
    run.theta[i] = std::atan2(run.z[1][i] - run.z[0][i], run.x[1][i] - run.x[0][i]);
  return Analyze(run, t.options);
}

TEST(LockedError, ASimulationHasNone) {
  const Analysis& t = Truth();
  ASSERT_EQ(t.periods.settled.summary.label, "drift");
  const LockedError e = MeasureLockedError(t);
  EXPECT_EQ(e.phase_bins, 80);
  EXPECT_EQ(e.col_m, 0.0);
  EXPECT_EQ(e.row_m, 0.0);
  EXPECT_EQ(e.row_source, "resting_height");
  EXPECT_TRUE(LockedErrorDeviations(t, e, TrackObservables(t), 4).empty());
}

// 4 um locked in each column and row (0.01 px at 0.4 mm/px), beside 4 um of frame-to-frame
// noise whose share of each phase average is taken out.
TEST(LockedError, MeasuresAnErrorThatRepeatsWithTheDrivesPhase) {
  const Analysis a = WithErrors(4e-6, 4e-6, 4e-6);
  ASSERT_EQ(a.periods.settled.summary.label, "drift");
  const LockedError e = MeasureLockedError(a);
  std::printf("col %.2f um over %d bins, row %.2f um over %d bins\n", e.col_m * 1e6, e.length_bins,
              e.row_m * 1e6, e.rest_bins);
  EXPECT_EQ(e.row_source, "resting_height");
  EXPECT_GE(e.rest_bins, 30);
  EXPECT_NEAR(e.col_m, 4e-6, 1.2e-6);
  EXPECT_NEAR(e.row_m, 4e-6, 1.6e-6);
}

// A resting sphere raised on a third of the phases (a hop below the contact threshold): alone,
// the hops read as no error at all, whatever their height (3, 10 or 30 um), since they only ever
// raise it. Beside 2 um of locked row error (read as 2.37 um without hops) they lift the core's
// centre where they are low enough to mix with it: 3.0, 3.6 and 3.0 um, an overstatement,
// never an understatement.
TEST(LockedError, AHopTooSmallToSeeIsNotError) {
  const double alone = MeasureLockedError(WithErrors(0, 2e-6, 0)).row_m;
  EXPECT_NEAR(alone, 2e-6, 0.8e-6);
  for (double hop : {3e-6, 10e-6, 30e-6}) {
    const LockedError e = MeasureLockedError(WithErrors(0, 0, 0, hop));
    ASSERT_EQ(e.row_source, "resting_height");
    EXPECT_EQ(e.row_m, 0.0) << hop;
    const double with = MeasureLockedError(WithErrors(0, 2e-6, 0, hop)).row_m;
    std::printf("hop %.0f um: row %.2f um (%.2f without the hops)\n", hop * 1e6, with * 1e6, alone * 1e6);
    EXPECT_GE(with, 0.9 * alone) << hop;
    EXPECT_LE(with, 2.0 * alone) << hop;
  }
}

// A track with 8 um of locked error in each coordinate (0.02 px at 0.4 mm/px): its slip bins
// are off by several of their standard errors wherever the simulation is right. With the
// locked error's covariance in chi2 the truth is an acceptable fit (chi2 23.5 for 46
// observables less 5 coefficients, p 0.99: the rows' estimate reads high where the resting
// sphere hops; 63, p 0.016, from 32 draws, too few to span the slip bins' covariance); without
// it chi2 at the truth is 182 (p ~ 1e-19).
TEST(LockedError, TheTruthStaysAnAcceptableFitOfATrackWithALockedError) {
  const Analysis a = WithErrors(8e-6, 8e-6, 2e-6);
  ASSERT_EQ(a.periods.settled.summary.label, "drift");
  const LockedError e = MeasureLockedError(a);
  EXPECT_GT(e.col_m, 4e-6);
  EXPECT_GT(e.row_m, 4e-6);
  FitOptions fo;
  const double chi2 = FitChi2(a, DriftScene(), fo);
  int usable = 0;
  for (const Observable& o : TrackObservables(a)) usable += std::isfinite(o.value);
  const double p = ChiSquarePValue(chi2, usable - 5);
  std::printf("chi2 at the truth %.1f for %d observables, p %.3g\n", chi2, usable, p);
  EXPECT_GE(p, kMinFitPValue);
}

}  // namespace
}  // namespace dimer::compare
