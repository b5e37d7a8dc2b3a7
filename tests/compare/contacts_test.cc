// compare/contacts.h on gaps made here with exact impacts and a camera's noise: a sphere that
// only bounces must not be seen resting at the bottom of its bounces, nor given a contact level
// from them; a sphere that sits between its bounces must still be seen resting.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compare/contacts.h"

namespace dimer::compare {
namespace {

constexpr double kG = 9.81;
constexpr double kFps = 2000;
constexpr double kDiameter = 9.5e-3;
constexpr double kNoise = 35e-6;  // m: the gap noise of the POV-Ray film at 0.4 mm/px

// Sphere 1 hops on a still plate with take-off speed `v0`, sitting `sit_frames` on the plate
// between hops; sphere 0 rests throughout. Gaps with white noise (seeded: reproducible).
// Returns the run; `impacts` gets the true impact times (those 10 frames or more before its end),
// `sitting` whether sphere 1 is on the plate, per frame.
SampledRun HopRun(double v0, int sit_frames, size_t frames, std::vector<double>* impacts,
                  std::vector<uint8_t>* sitting = nullptr) {
  SampledRun run;
  run.kind = "sim";
  run.dt = 1 / kFps;
  run.n = frames;
  run.diameter_m = kDiameter;
  run.plate_z.assign(frames, 0.0);
  run.theta.assign(frames, 0.0);
  const double radius = 0.5 * kDiameter;
  const double flight = 2 * v0 / kG, sit = sit_frames / kFps;
  const double start = 0.37 / kFps;  // impacts between frames, never on one
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, kNoise);
  for (int s = 0; s < 2; ++s) {
    run.x[s].assign(frames, 0.0);
    run.z[s].assign(frames, 0.0);
  }
  // Impacts inside the data, with the frames after them to resolve them.
  for (double t = start; t + flight < (frames - 10) / kFps; t += flight + sit)
    impacts->push_back(t + flight);
  for (size_t i = 0; i < frames; ++i) {
    const double t = run.Time(i);
    double h = 0;  // sphere 1's gap: in flight from start + k (flight + sit)
    if (t >= start) {
      const double tau = std::fmod(t - start, flight + sit);
      if (tau < flight) h = v0 * tau - 0.5 * kG * tau * tau;
    }
    run.x[0][i] = 0, run.x[1][i] = 3.9 * kDiameter;
    run.z[0][i] = radius + noise(rng);
    run.z[1][i] = radius + h + noise(rng);
    if (sitting) sitting->push_back(h == 0);
  }
  return run;
}

PlateDrive StillPlate() {
  PlateDrive p;
  p.source = "file";
  p.offset_m = 0;
  return p;
}

size_t Count(const std::vector<uint8_t>& flags) {
  size_t n = 0;
  for (uint8_t f : flags) n += f;
  return n;
}

// The bottom of a bounce at 0.2 m/s spends 3-5 frames within thr (4 sigma = 0.14 mm) of the
// plate, 7 % of the frames: once counted as rests, a drift's bouncing end looked like neither
// mode's ("irregular") and its contact level was taken from that band, 0.1 mm high.
TEST(Contacts, ABouncingSphereIsNotRestingAtTheBottomOfItsBounces) {
  std::vector<double> truth;
  const SampledRun run = HopRun(0.2, 0, 2400, &truth);
  const Contacts c = FindContacts(run, StillPlate());
  const SphereContacts& hop = c.sphere[1];
  EXPECT_NEAR(hop.noise_m, kNoise, 0.1 * kNoise);
  EXPECT_LE(std::abs(hop.level_m), 0.5 * hop.threshold_m) << "contact level, m";
  EXPECT_LT(static_cast<double>(Count(hop.resting)) / run.n, 0.01) << "frames resting";
  // Tolerances from 60 noise seeds (this one is 7): times within 0.96 frame and speeds within
  // 0.042 m/s at worst (a 20-frame quadratic's end slope at this noise: sigma 0.011 m/s), the
  // mean speed error within 0.006 m/s.
  ASSERT_EQ(hop.impacts.size(), truth.size());
  double mean_error = 0;
  for (size_t k = 0; k < truth.size(); ++k) {
    EXPECT_TRUE(hop.impacts[k].bounce) << "impact " << k;
    EXPECT_NEAR(hop.impacts[k].t, truth[k], 1.5 / kFps) << "impact " << k;
    EXPECT_NEAR(hop.impacts[k].v_before, -0.2, 0.05) << "impact " << k;
    EXPECT_NEAR(hop.impacts[k].v_after, 0.2, 0.05) << "impact " << k;
    mean_error += (hop.impacts[k].v_after - 0.2 - hop.impacts[k].v_before - 0.2) / (2 * truth.size());
  }
  EXPECT_NEAR(mean_error, 0, 0.01) << "mean speed error, m/s";
  // The sphere at rest beside it keeps its rest and its level.
  EXPECT_GT(static_cast<double>(Count(c.sphere[0].resting)) / run.n, 0.99);
  EXPECT_LE(std::abs(c.sphere[0].level_m), kNoise);
}

// A sphere that lands and sits 12 frames before it hops again rests there: the flights on
// either side, fitted as one bounce, would pass 0.3-0.6 mm below the frames it sat for.
TEST(Contacts, ASphereSittingBetweenBouncesIsResting) {
  std::vector<double> truth;
  std::vector<uint8_t> sitting;
  const int sit = 12;
  const SampledRun run = HopRun(0.2, sit, 2400, &truth, &sitting);
  const Contacts c = FindContacts(run, StillPlate());
  const SphereContacts& hop = c.sphere[1];
  ASSERT_EQ(hop.impacts.size(), truth.size());
  for (const Impact& imp : hop.impacts) EXPECT_FALSE(imp.bounce) << "at t = " << imp.t;
  // Every sit is seen resting, with the frames of the landing and the take-off that are within
  // thr of the plate (thr / (v0 dt) = 1.4 frames on each side), and but a frame lost at either end.
  const size_t sat = Count(sitting), sits = sat / sit + 1;
  const size_t edge = static_cast<size_t>(std::ceil(hop.threshold_m / (0.2 / kFps)));
  EXPECT_GE(Count(hop.resting), sat - 2 * sits);
  EXPECT_LE(Count(hop.resting), sat + 2 * edge * sits);
}

}  // namespace
}  // namespace dimer::compare
