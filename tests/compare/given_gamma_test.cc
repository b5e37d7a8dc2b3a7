// --gamma with a visible plate (compare/analysis.cc, UseGivenGamma): the given Gamma is used,
// the tracked plate's own is kept beside it, and a disagreement beyond 3 sigma and 1 % is
// warned about. The track is a simulation seen as a track (its plate fitted, not read), with its
// plate's motion magnified 3 % as by an edge nearer the camera than the dimer.
#include <gtest/gtest.h>

#include <cmath>

#include "compare/simulate.h"

namespace dimer::compare {
namespace {

// The sample drift as a track whose plate moves `magnify` times the true plate's motion.
SampledRun DriftTrack(double magnify) {
  sim::SimOptions o;
  o.ar = 3.9;
  o.gamma = 0.9;
  o.cycles = 20;
  o.fps = 2000;
  SampledRun run = SimulateAndAnalyze(o, {}, "drift").run;
  run.kind = "track";
  run.sim_freq_hz = run.sim_gamma = kNaN;
  double mean = 0;
  for (double z : run.plate_z) mean += z / run.plate_z.size();
  for (double& z : run.plate_z) z = mean + magnify * (z - mean);
  return run;
}

bool Warned(const Analysis& a, const std::string& what) {
  for (const std::string& w : a.warnings)
    if (w.find(what) != std::string::npos) return true;
  return false;
}

TEST(GivenGamma, ReplacesThePlatesGammaAndStatesBoth) {
  const SampledRun run = DriftTrack(1.03);
  const Analysis fitted = Analyze(run, {});
  ASSERT_EQ(fitted.plate.source, "fit");
  EXPECT_NEAR(fitted.plate.gamma, 0.9 * 1.03, 1e-3) << "the plate's motion, magnified";
  EXPECT_TRUE(std::isnan(fitted.plate.gamma_plate));
  EXPECT_FALSE(Warned(fitted, "--gamma"));

  AnalysisOptions given;
  given.gamma = 0.9;
  const Analysis a = Analyze(run, given);
  EXPECT_EQ(a.plate.source, "fit");
  EXPECT_EQ(a.plate.gamma, 0.9);
  EXPECT_EQ(a.plate.gamma_plate, fitted.plate.gamma);
  EXPECT_EQ(a.plate.freq_hz, fitted.plate.freq_hz) << "the fitted frequency stays";
  EXPECT_EQ(a.plate.phase_rad, fitted.plate.phase_rad) << "the fitted phase stays";
  EXPECT_NEAR(a.plate.amp_m * std::pow(2 * M_PI * a.plate.freq_hz, 2) / kGravity, 0.9, 1e-3);
  EXPECT_TRUE(Warned(a, "--gamma 0.9 is used")) << "3 % apart";
  EXPECT_EQ(a.periods.settled.summary.label, "drift");
}

TEST(GivenGamma, AgreeingWithThePlateIsNotWarned) {
  AnalysisOptions given;
  given.gamma = 0.9;
  const Analysis a = Analyze(DriftTrack(1.0), given);
  EXPECT_EQ(a.plate.gamma, 0.9);
  EXPECT_NEAR(a.plate.gamma_plate, 0.9, 1e-3);
  EXPECT_FALSE(Warned(a, "--gamma"));
}

}  // namespace
}  // namespace dimer::compare
