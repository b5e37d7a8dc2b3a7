// The rows refereed by what a sphere can do (held_rows.h): rest on the plate or fall. Series in
// pixels at 2,000 frames/s and 0.2 mm/px (gravity 0.0123 px per frame^2), a 25 Hz plate of
// 1.25 px amplitude (80 frames a period).
#include "tracking/held_rows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

constexpr double kHeldSeriesGravityPx = 9.81 / (2000.0 * 2000.0 * 2e-4);
constexpr size_t kHeldSeriesFrames = 400;

std::vector<double> SinePlate(double amplitude = 1.25) {
  std::vector<double> p;
  for (size_t i = 0; i < kHeldSeriesFrames; ++i) {
    p.push_back(248.0 + amplitude * std::sin(2 * std::numbers::pi * double(i) / 80.0));
  }
  return p;
}

// `rows` with Gaussian noise of `sigma` px.
std::vector<double> WithNoise(std::vector<double> rows, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  for (double& r : rows) r += n(rng);
  return rows;
}

TEST(HeldRows, ARestingSphereMovesWithThePlate) {
  const std::vector<double> plate = SinePlate();
  // The edge seen 15 % nearer than the dimer: the rows move 0.85 px per px of it.
  for (double scale : {1.0, 0.85}) {
    std::vector<double> rows;
    for (double p : plate) rows.push_back(248.0 - 23.75 + scale * (p - 248.0));
    const HeldRows h = FindHeldRows(WithNoise(rows, 0.03, 1), plate, kHeldSeriesGravityPx);
    EXPECT_GT(h.windows, 0u);
    EXPECT_EQ(h.held, 0u) << "scale " << scale;
  }
}

TEST(HeldRows, AFlyingSphereFalls) {
  // A sphere bouncing once a period, its apex 9.8 px above the plate; and the same flights
  // seen from the apex outward, where they move least.
  const std::vector<double> plate = SinePlate();
  const double v = 0.5 * kHeldSeriesGravityPx * 80.0;
  for (size_t shift : {size_t(0), size_t(40)}) {
    std::vector<double> rows;
    for (size_t i = 0; i < kHeldSeriesFrames; ++i) {
      const double t = double((i + shift) % 80);
      rows.push_back(248.0 - 23.75 - (v * t - 0.5 * kHeldSeriesGravityPx * t * t));
    }
    const HeldRows h = FindHeldRows(WithNoise(rows, 0.03, 2), plate, kHeldSeriesGravityPx);
    EXPECT_GT(h.windows, 0u);
    EXPECT_EQ(h.held, 0u) << "shift " << shift;
  }
}

TEST(HeldRows, RowsThatNeitherRestNorFallAreHeld) {
  // POV-Ray ruler_above_plate without the scale: rows within 0.3 px, 11 px above the plate,
  // while the plate moved 2.6 px.
  const std::vector<double> plate = SinePlate(1.3);
  const std::vector<double> rows = WithNoise(std::vector<double>(kHeldSeriesFrames, 213.6), 0.05, 3);
  const HeldRows h = FindHeldRows(rows, plate, kHeldSeriesGravityPx);
  EXPECT_EQ(h.window_frames, 59u);  // 2 sqrt(2 x 5 px / g), rounded up, and one
  EXPECT_GT(h.windows, 0u);
  EXPECT_EQ(h.held, h.windows);
  EXPECT_LT(h.row_range, 0.4);
  EXPECT_GT(h.plate_range, 2.0);
}

TEST(HeldRows, AStillPlateOrNoScaleDecidesNothing) {
  // A calibration film on a still plate: still rows are a resting sphere's.
  const std::vector<double> still(kHeldSeriesFrames, 248.0);
  const std::vector<double> rows = WithNoise(std::vector<double>(kHeldSeriesFrames, 224.25), 0.03, 4);
  const HeldRows s = FindHeldRows(rows, WithNoise(still, 0.03, 5), kHeldSeriesGravityPx);
  EXPECT_EQ(s.windows, 0u);
  EXPECT_EQ(s.held, 0u);
  // Without gravity in pixels (no frame rate or scale), no window.
  EXPECT_EQ(FindHeldRows(rows, SinePlate(), std::nan("")).window_frames, 0u);
  // A window with a frame where the sphere was not found is not judged.
  std::vector<double> gaps = rows;
  for (size_t i = 0; i < kHeldSeriesFrames; i += 20) gaps[i] = std::nan("");
  EXPECT_EQ(FindHeldRows(gaps, SinePlate(), kHeldSeriesGravityPx).windows, 0u);
}

}  // namespace
}  // namespace dimer::tracking
