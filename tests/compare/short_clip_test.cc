// Short clips (compare/plate_fit.h): the drive is fitted from 2.5 plate periods of a track that
// starts on the rising plate (two upward crossings of the median, too few for the crossing
// estimate), and a clip under 2 periods is refused with its length in periods. The track is the
// settled part of a simulated drift seen as a camera sees it: the plate's edge tracked to
// 0.06 px at 0.2 mm/px (an amplitude of 1.8 px at 25 Hz, Gamma 0.9).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "common/error.h"
#include "compare/simulate.h"

namespace dimer::compare {
namespace {

constexpr double kMPerPx = 2e-4;
constexpr double kPlateNoisePx = 0.06;

// `periods` plate periods from the start of period 30 (plate phase 0: mid-height, rising).
SampledRun Clip(double periods) {
  sim::SimOptions o;
  o.ar = 3.9;
  o.gamma = 0.9;
  o.freq_hz = 25;
  o.cycles = 34;
  o.fps = 2000;
  const SampledRun full = SimulateAndAnalyze(o, {}, "drift").run;
  const size_t first = 30 * 80, n = static_cast<size_t>(std::lround(periods * 80));
  SampledRun run;
  run.path = "clip.h5";
  run.kind = "track";
  run.dt = full.dt;
  run.t0 = full.Time(first);
  run.n = n;
  run.diameter_m = full.diameter_m;
  run.ar = full.ar;
  run.m_per_px = kMPerPx;
  std::mt19937 rng(37);
  std::normal_distribution<double> noise(0.0, kPlateNoisePx * kMPerPx);
  for (size_t i = first; i < first + n; ++i) {
    for (int s = 0; s < 2; ++s) run.x[s].push_back(full.x[s][i]), run.z[s].push_back(full.z[s][i]);
    run.plate_z.push_back(full.plate_z[i] + noise(rng));
    run.theta.push_back(full.theta[i]);
  }
  return run;
}

TEST(ShortClip, TwoAndAHalfPeriodsGiveTheDrive) {
  const Analysis a = Analyze(Clip(2.5), {});
  ASSERT_EQ(a.plate.source, "fit");
  EXPECT_NEAR(a.plate.freq_hz, 25.0, 0.005 * 25.0);
  EXPECT_NEAR(a.plate.gamma, 0.9, 0.02 * 0.9);
  std::printf("2.5 periods: f %.4f +- %.4f Hz, Gamma %.4f +- %.4f\n", a.plate.freq_hz, a.plate.freq_err,
              a.plate.gamma, a.plate.gamma_err);
}

TEST(ShortClip, UnderTwoPeriodsIsRefusedWithItsLength) {
  try {
    Analyze(Clip(1.5), {});
    FAIL() << "a 1.5-period clip was analysed";
  } catch (const InputError& e) {
    const std::string what = e.what();
    // 120 frames span 119 frame intervals: 1.49 periods.
    EXPECT_NE(what.find("clip.h5: 1.49 plate periods long; at least 2 are needed"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace dimer::compare
