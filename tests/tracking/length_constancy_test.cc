// The whole track refereed by the rigid rod (length_constancy.h): the centres' distance is one
// length in every frame, to its own frame-to-frame noise. A dimer of 137.75 px hopping and
// drifting, its centres with Gaussian noise.
#include "tracking/length_constancy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

constexpr double kRod = 137.75;
constexpr size_t kRodFrames = 100;

// A drifting dimer whose right end hops (up to 16 px), its centres with noise `sigma`; the
// right sphere's row in frames [held_from, held_to) held where it was at held_from.
std::vector<FrameTrack> HoppingDimer(double sigma, unsigned seed, size_t held_from = 0,
                                size_t held_to = 0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  std::vector<FrameTrack> frames;
  Eigen::Vector2d held(0, 0);
  for (size_t i = 0; i < kRodFrames; ++i) {
    const double lift = 16.0 * std::pow(std::sin(std::numbers::pi * double(i) / 60.0), 2);
    const double angle = std::asin(lift / kRod);
    FrameTrack f;
    f.index = i;
    f.found = {true, true};
    f.centre[0] = Eigen::Vector2d(200.0 + 0.05 * double(i), 224.0);
    f.centre[1] = f.centre[0] + kRod * Eigen::Vector2d(std::cos(angle), -std::sin(angle));
    if (i == held_from) held = f.centre[1];
    if (i >= held_from && i < held_to) f.centre[1].y() = held.y();
    for (int k = 0; k < 2; ++k) f.centre[k] += Eigen::Vector2d(n(rng), n(rng));
    frames.push_back(f);
  }
  return frames;
}

TEST(LengthConstancy, ARigidDimerKeepsItsLength) {
  for (double sigma : {0.01, 0.03, 0.1}) {
    const LengthConstancy c = JudgeLengthConstancy(HoppingDimer(sigma, 1));
    EXPECT_EQ(c.frames, kRodFrames);
    EXPECT_NEAR(c.median_px, kRod, 5 * sigma);
    // The length's noise is about the centres' (the two ends' along the rod, sqrt(2) sigma).
    EXPECT_NEAR(c.noise_px, std::sqrt(2.0) * sigma, 0.5 * sigma) << "sigma " << sigma;
    EXPECT_EQ(c.departing, 0u) << "sigma " << sigma << ", worst " << c.worst_px;
  }
}

TEST(LengthConstancy, ASphereHeldWhileItHopsBendsTheLength) {
  // Held over frames 10-50 as the hop rises 16 px: the length bends by up to ~1 px (the row
  // error across the rod is mostly lost from the length), far beyond its 0.04 px noise.
  const std::vector<FrameTrack> frames = HoppingDimer(0.03, 2, 10, 50);
  const LengthConstancy c = JudgeLengthConstancy(frames);
  EXPECT_GT(c.departing, 10u);
  EXPECT_GE(c.first, 10u);
  EXPECT_LT(c.last, 50u);
  EXPECT_GT(c.worst_px, c.tolerance_px);
  EXPECT_DOUBLE_EQ(c.tolerance_px, kLengthDepartMinPx) << "noise " << c.noise_px;
}

TEST(LengthConstancy, ANoisyTrackIsJudgedByItsOwnNoise) {
  // The same hold in centres scattering 0.3 px: a bend within ten times the length's noise is
  // not told from it, and no frame is said to depart.
  const LengthConstancy c = JudgeLengthConstancy(HoppingDimer(0.3, 3, 10, 20));
  EXPECT_GT(c.tolerance_px, 3.0);
  EXPECT_EQ(c.departing, 0u);
}

TEST(LengthConstancy, NotJudgedOnFewFramesOrWithoutConsecutiveOnes) {
  std::vector<FrameTrack> frames = HoppingDimer(0.03, 4, 10, 50);
  frames.resize(kLengthMinFrames - 1);
  EXPECT_TRUE(std::isnan(JudgeLengthConstancy(frames).noise_px));
  // Every other frame skipped: no three consecutive frames to measure the noise on.
  frames = HoppingDimer(0.03, 4, 10, 50);
  for (size_t i = 0; i < frames.size(); ++i) frames[i].index = 2 * i;
  const LengthConstancy c = JudgeLengthConstancy(frames);
  EXPECT_EQ(c.frames, kRodFrames);
  EXPECT_TRUE(std::isnan(c.noise_px));
  EXPECT_EQ(c.departing, 0u);
}

TEST(LengthConstancy, SpheresCutOrNotFoundAreLeftOut) {
  std::vector<FrameTrack> frames = HoppingDimer(0.03, 5);
  frames[30].cut[1] = true;
  frames[30].centre[1].x() += 20;  // a cut sphere's centre is placed otherwise
  frames[31].found[0] = false;
  const std::vector<double> len = DimerLengths(frames);
  EXPECT_TRUE(std::isnan(len[30]));
  EXPECT_TRUE(std::isnan(len[31]));
  const LengthConstancy c = JudgeLengthConstancy(frames);
  EXPECT_EQ(c.frames, kRodFrames - 2);
  EXPECT_EQ(c.departing, 0u);
}

}  // namespace
}  // namespace dimer::tracking
