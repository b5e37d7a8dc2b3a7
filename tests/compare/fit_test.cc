// The coefficient fit recovers known coefficients from a simulated experiment and reports a
// coefficient the scene does not constrain as unconstrained.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "compare/fit.h"
#include "compare/simulate.h"

namespace dimer::compare {
namespace {

void Print(const FitResult& r) {
  for (const FitParameter& p : r.params) {
    std::printf("%-9s %-14s value %.4f err %.4f range [%.4f, %.4f]\n", p.name.c_str(), p.status.c_str(),
                p.value, p.err, p.range_lo, p.range_hi);
  }
  std::printf("chi2 %.3f dof %d threshold %.3f evaluations %d, %.1f s\n", r.chi2, r.dof, r.threshold,
              r.evaluations, r.seconds);
}

TEST(Fit, RecoversRestitutionAndImpactFrictionFromASimulatedDrift) {
  sim::SimOptions truth;
  truth.ar = 3.9;
  truth.eps = 0.6;
  truth.mu_hat = 0.12;
  truth.cycles = 100;
  const Analysis track = SimulateAndAnalyze(truth, {}, "truth");
  ASSERT_EQ(track.periods.settled.summary.label, "drift");
  sim::SimOptions start;  // the paper's coefficients as the starting point
  const FitResult r = FitCoefficients(track, start, {});
  Print(r);
  const FitParameter& eps = r.params[0];
  const FitParameter& mu_hat = r.params[1];
  const FitParameter& mu_hat_s = r.params[2];
  ASSERT_EQ(eps.status, "constrained");
  EXPECT_NEAR(eps.value, truth.eps, 0.03 * truth.eps);
  ASSERT_EQ(mu_hat.status, "constrained");
  EXPECT_NEAR(mu_hat.value, truth.mu_hat, 0.10 * truth.mu_hat);
  // Every impact of this scene slides through (sim event log: continuous_slide only), so the
  // scene gives mu_hat_s no value; it can only bound it from above (a larger value would make
  // impacts stick, which the track does not show). Never a number, and the truth inside.
  EXPECT_NE(mu_hat_s.status, "constrained");
  EXPECT_TRUE(std::isnan(mu_hat_s.err));
  EXPECT_LE(mu_hat_s.range_lo, truth.mu_hat_s);
  EXPECT_GE(mu_hat_s.range_hi, truth.mu_hat_s);
}

}  // namespace
}  // namespace dimer::compare
