// The contact of a sphere that never rests, from the V its gap to the plate draws at each impact
// (tracking/sphere/impact_vertex.h).
#include "tracking/sphere/impact_vertex.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

// A gap series of bounces every `period` frames: approach at `in` px a frame, rebound at `out`,
// the arms bent by gravity (`bend` px per frame^2, downward), the impact at a fraction of a
// frame that changes from bounce to bounce, plus noise.
std::vector<double> Bounces(int frames, int period, double contact, double in, double out,
                            double bend, double noise, uint64_t seed,
                            std::vector<double>* impacts) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, noise);
  std::vector<double> g(frames);
  for (int i = 0; i < frames; ++i) {
    const int b = i / period;
    const double impact = period * b + period / 2.0 + std::fmod(0.37 * b, 1.0);
    if (impacts && (impacts->empty() || impacts->back() != impact)) impacts->push_back(impact);
    const double dt = i - impact;
    const double lift = dt < 0 ? -in * dt : out * dt;
    g[i] = contact + lift - 0.5 * bend * dt * dt + n(rng);
  }
  return g;
}

TEST(ImpactVertex, TheArmsMeetAtTheContact) {
  std::vector<double> truth;
  const std::vector<double> g = Bounces(800, 80, 3.2, 0.3, 0.2, 0.0, 0.02, 1, &truth);
  const double noise = GapNoise(g);
  EXPECT_NEAR(noise, 0.02, 0.004);
  const std::vector<ImpactVertex> v = ImpactVertices(g, noise);
  ASSERT_EQ(v.size(), truth.size());
  for (size_t k = 0; k < v.size(); ++k) {
    EXPECT_NEAR(v[k].time, truth[k], 0.25) << k;
    EXPECT_EQ(v[k].frame, size_t(std::lround(v[k].time))) << k;
    // The stated uncertainty is the line fits' own: the vertex within 3 of it.
    EXPECT_GT(v[k].err, 0.005) << k;
    EXPECT_LT(v[k].err, 0.05) << k;
    EXPECT_NEAR(v[k].value, 3.2, 3 * v[k].err) << k;
    EXPECT_NEAR(v[k].approach, -0.3, 0.03) << k;
    EXPECT_NEAR(v[k].rebound, 0.2, 0.03) << k;
  }
}

TEST(ImpactVertex, GravityBendsTheArmsByLittle) {
  // 0.4 mm/px at 2000 frames/s: g bends the arms by 0.006 px per frame^2, the plate's
  // acceleration at Gamma 1 as much again. The straight lines' meeting point is lifted by it,
  // noise-free, by less than a tenth of the contact band.
  const std::vector<double> g = Bounces(800, 80, 0.0, 0.3, 0.2, 0.012, 0.0, 1, nullptr);
  const std::vector<ImpactVertex> v = ImpactVertices(g, 0.005);
  ASSERT_EQ(v.size(), 10u);
  for (const ImpactVertex& x : v) {
    EXPECT_GT(x.value, 0.0);
    EXPECT_LT(x.value, 0.03);
  }
}

TEST(ImpactVertex, TheBendTakenOutTheArmsMeetAtTheContact) {
  // 0.1 mm/px at 1000 frames/s: g alone bends the gap by 0.098 px per frame^2. A sphere
  // bouncing elastically at 0.508 px a frame lands every 10.37 frames: straight lines through
  // the arms miss the contact by a tenth of a pixel; with the bend given, the vertices are exact.
  const double bend = -0.098, v0 = 0.508, period = 2 * v0 / -bend, t0 = 3.3;
  std::vector<double> g(400);
  for (size_t i = 0; i < g.size(); ++i) {
    const double tau = std::fmod(double(i) - t0 + 10 * period, period);  // since the last landing
    g[i] = v0 * tau + 0.5 * bend * tau * tau;
  }
  const std::vector<ImpactVertex> straight = ImpactVertices(g, 0.02);
  ASSERT_FALSE(straight.empty());
  for (const ImpactVertex& v : straight) EXPECT_GT(v.value, 0.08);
  const std::vector<ImpactVertex> bent = ImpactVertices(g, 0.02, std::vector<double>(400, bend));
  EXPECT_GE(bent.size(), 30u);
  for (const ImpactVertex& v : bent) {
    EXPECT_NEAR(v.value, 0.0, 1e-9);
    EXPECT_NEAR(std::remainder(v.time - t0, period), 0.0, 1e-9);
  }
}

TEST(ImpactVertex, TheGapBendsWithThePlateLessGravity) {
  // A plate row swinging by 3 px over 80 frames (Gamma ~ 1 at 0.2 mm/px and 2000 frames/s),
  // with 0.013 px of noise; gravity 0.0123 px per frame^2 (0.2 mm/px, 2000 frames/s).
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0, 0.013);
  const double w = 2 * M_PI / 80, g = 9.81 / (2e-4 * 2000.0 * 2000.0);
  std::vector<double> plate(400);
  for (size_t i = 0; i < plate.size(); ++i) plate[i] = 200 - 3 * std::sin(w * double(i)) + n(rng);
  const std::vector<double> bend = GapBend(plate, g);
  ASSERT_EQ(bend.size(), plate.size());
  for (size_t i = kPlateBendHalfWindow; i + kPlateBendHalfWindow < plate.size(); ++i) {
    // The quadratic over 17 frames reads the sine's curvature ~4 % low at its peaks.
    const double exact = 3 * w * w * std::sin(w * double(i)) - g;
    EXPECT_NEAR(bend[i], exact, 0.002) << i;
  }
  // Where the window leaves the film, or holds a lost frame: gravity alone.
  EXPECT_DOUBLE_EQ(bend[0], -g);
  plate[100] = NAN;
  EXPECT_DOUBLE_EQ(GapBend(plate, g)[95], -g);
  EXPECT_DOUBLE_EQ(GapBend(plate, NAN)[95], 0.0);
}

TEST(ImpactVertex, ARestingSphereDrawsNone) {
  // 20,000 frames of a sphere on the plate (noise only) and of one in smooth flight: no V.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0, 0.05);
  std::vector<double> rest(20000), flight(20000);
  for (size_t i = 0; i < rest.size(); ++i) {
    rest[i] = 1.0 + n(rng);
    const double t = std::fmod(double(i), 200.0) - 100.0;  // arcs 200 frames long
    flight[i] = 15.0 - 0.0015 * t * t + n(rng);
  }
  EXPECT_TRUE(ImpactVertices(rest, GapNoise(rest)).empty());
  const std::vector<ImpactVertex> f = ImpactVertices(flight, GapNoise(flight));
  // The arcs meet in a V where each lands and the next leaves, every 200 frames; nowhere else.
  for (const ImpactVertex& v : f) EXPECT_LE(std::abs(std::remainder(v.time, 200.0)), 1.5);
}

TEST(ImpactVertex, ALostFrameInAnArmLeavesThatImpactOut) {
  std::vector<double> truth;
  std::vector<double> g = Bounces(400, 80, 0.0, 0.3, 0.2, 0.0, 0.02, 2, &truth);
  g[size_t(std::lround(truth[1])) + 2] = NAN;  // the second impact's rebound
  const std::vector<ImpactVertex> v = ImpactVertices(g, GapNoise(g));
  ASSERT_EQ(v.size(), truth.size() - 1);
  EXPECT_NEAR(v[1].time, truth[2], 0.2);
}

TEST(ImpactVertex, ArmsWithinTheirNoiseAreNoV) {
  // Landing at 0.05 px a frame in noise of 0.05 px: the slopes are not told from the noise.
  const std::vector<double> g = Bounces(800, 80, 0.0, 0.05, 0.05, 0.0, 0.05, 3, nullptr);
  EXPECT_TRUE(ImpactVertices(g, GapNoise(g)).empty());
  EXPECT_TRUE(ImpactVertices(g, NAN).empty());
}

}  // namespace
}  // namespace dimer::tracking
