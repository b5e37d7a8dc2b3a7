// An over-exposed plate over a sequence: the clipped level shared by the frames, and every
// frame's row fitted again at it (tracking/plate/clipped_edge.h).
#include "tracking/plate/clipped_edge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/tracking/plate/clipped_edge_frame.h"
#include "tracking/plate/plate_edge.h"

namespace dimer::tracking {
namespace clipped_edge_test {
namespace {

// One frame of a plate edge at `edge` (dark above, 128 x gain below, blur 0.5 px, noise 2),
// as RefinePlateRow sees it: its row and its clipped profile.
struct Measured {
  double row;
  ClippedEdgeProfile profile;
};

Measured Measure(double edge, double gain, uint64_t seed, double true_psf = 0.5) {
  Measured m;
  m.row = RefinePlateRow(ClippedBlurredEdge(edge, gain, true_psf, seed), 60.5, {}, 0.5,
                         &m.profile);
  return m;
}

// A plate moving across two pixels: the edge at 59.02 + 0.04 i.
std::vector<double> Edges() {
  std::vector<double> e;
  for (int i = 0; i < 50; ++i) e.push_back(59.02 + 0.04 * i);
  return e;
}

std::vector<const ClippedEdgeProfile*> Pointers(const std::vector<Measured>& m) {
  std::vector<const ClippedEdgeProfile*> p;
  for (const Measured& x : m) p.push_back(&x.profile);
  return p;
}

TEST(ClippedEdgeAtLevel, TheKnownLevelPlacesTheEdgeAnywhereInThePixel) {
  // Gain 4 (the plate at twice the clip): where only the blur's spill above the edge pixel is
  // lit, the level alone cannot fix the row; known, it does.
  double worst = 0;
  for (double y : Edges()) {
    const Measured m = Measure(y, 4.0, 21);
    ASSERT_TRUE(m.profile.valid()) << "edge at " << y << ": not taken as clipped";
    const double row = ClippedEdgeRowAtLevel(m.profile, 4.0 * 128.0, 0.5);
    EXPECT_NEAR(row, y, 0.03) << "edge at " << y;
    worst = std::max(worst, std::abs(row - y));
  }
  std::printf("[ stats    ] clipped edge at the true level, gain 4: worst %.4f px\n", worst);
}

TEST(ClippedEdgeSequence, TheSharedLevelIsThePlatesAndEveryRowIsPlaced) {
  for (double gain : {4.0, 10.0}) {
    std::vector<Measured> frames;
    double worst_alone = 0;
    uint64_t seed = 100;
    for (double y : Edges()) {
      frames.push_back(Measure(y, gain, seed++));
      worst_alone = std::max(worst_alone, std::abs(frames.back().row - y));
    }
    const ClippedLevel level = SharedClippedLevel(Pointers(frames), 0.5);
    ASSERT_TRUE(level.found()) << "gain " << gain;
    EXPECT_GE(level.informative, kClippedLevelMinFrames);
    // The level within 3 %: each informative frame brings its own row as an unknown, and the
    // joint fit's level comes out a little low with noise (over 12 noise draws of this sweep:
    // -0.6 +- 0.6 % at gain 4 and 10, -1.9 +- 0.5 % at gain 2.4; clipped_edge.h).
    EXPECT_NEAR(level.value, 128.0 * gain, 0.03 * 128.0 * gain) << "gain " << gain;
    EXPECT_GT(level.err, 0.0);
    EXPECT_LT(level.err, 0.02 * level.value);
    std::vector<double> rows;
    for (const Measured& m : frames) rows.push_back(m.row);
    EXPECT_EQ(RefitClippedRows(Pointers(frames), level, &rows), frames.size());
    double worst = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      EXPECT_NEAR(rows[i], Edges()[i], 0.05) << "gain " << gain << ", edge at " << Edges()[i];
      worst = std::max(worst, std::abs(rows[i] - Edges()[i]));
    }
    // Frame by frame the least light's row is up to the pixel's covered part off.
    EXPECT_GT(worst_alone, 0.2) << "gain " << gain;
    std::printf("[ stats    ] clipped edge, gain %.0f: level %.1f +- %.1f (true %.1f) from %zu "
                "frames; worst row %.4f px (frame by frame %.4f)\n",
                gain, level.value, level.err, 128.0 * gain, level.used, worst, worst_alone);
  }
}

TEST(ClippedEdgeSequence, TheCamerasBlurIsFittedWithTheLevel) {
  // The camera blurs more than the 0.5 px assumed: with that blur the rows are off by up to
  // most of a pixel; fitted with the level, the blur is the camera's and the rows are placed.
  for (double true_psf : {0.6, 0.8}) {
    std::vector<Measured> frames;
    uint64_t seed = 900;
    for (double y : Edges()) frames.push_back(Measure(y, 4.0, seed++, true_psf));
    const ClippedLevel assumed = SharedClippedLevel(Pointers(frames), 0.5);
    std::vector<double> rows_assumed;
    for (const Measured& m : frames) rows_assumed.push_back(m.row);
    RefitClippedRows(Pointers(frames), assumed, &rows_assumed);
    const ClippedLevel fitted =
        SharedClippedLevel(Pointers(frames), 0.5, kClippedLevelMaxFrames, true);
    ASSERT_TRUE(fitted.found());
    EXPECT_TRUE(fitted.psf_fitted);
    EXPECT_FALSE(assumed.psf_fitted);
    EXPECT_NEAR(fitted.psf_sigma, true_psf, 0.05);
    EXPECT_NEAR(fitted.value, 512.0, 0.03 * 512.0) << "blur " << true_psf;
    std::vector<double> rows;
    for (const Measured& m : frames) rows.push_back(m.row);
    RefitClippedRows(Pointers(frames), fitted, &rows);
    double worst = 0, worst_assumed = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      EXPECT_NEAR(rows[i], Edges()[i], 0.05) << "blur " << true_psf << ", edge " << Edges()[i];
      worst = std::max(worst, std::abs(rows[i] - Edges()[i]));
      worst_assumed = std::max(worst_assumed, std::abs(rows_assumed[i] - Edges()[i]));
    }
    EXPECT_GT(worst_assumed, 0.2) << "blur " << true_psf;
    std::printf("[ stats    ] camera blur %.1f: fitted %.3f, level %.1f; worst row %.4f px (blur "
                "0.5 assumed: %.4f)\n", true_psf, fitted.psf_sigma, fitted.value, worst,
                worst_assumed);
  }
}

TEST(ClippedEdgeSequence, TheBlurIsNotFittedFromTooFewFrames) {
  std::vector<Measured> frames;
  for (int i = 0; i < int(kBlurFitMinFrames) - 1; ++i) {
    frames.push_back(Measure(60.1 + 0.02 * i, 4.0, 950 + i));  // two rows lit in each
  }
  const ClippedLevel level =
      SharedClippedLevel(Pointers(frames), 0.5, kClippedLevelMaxFrames, true);
  ASSERT_TRUE(level.found());
  EXPECT_EQ(level.informative, frames.size());
  EXPECT_FALSE(level.psf_fitted);
  EXPECT_EQ(level.psf_sigma, 0.5);
}

TEST(ClippedEdgeSequence, NoLevelWithoutFramesOfTwoLitRows) {
  // A plate at rest with its edge in the upper half of a pixel: one lit row in every frame.
  std::vector<Measured> frames;
  for (int i = 0; i < 10; ++i) frames.push_back(Measure(59.7, 4.0, 300 + i));
  const ClippedLevel level = SharedClippedLevel(Pointers(frames), 0.5);
  EXPECT_FALSE(level.found());
  EXPECT_EQ(level.informative, 0u);
  std::vector<double> rows(frames.size(), 1.0);
  EXPECT_EQ(RefitClippedRows(Pointers(frames), level, &rows), 0u);
  for (double r : rows) EXPECT_EQ(r, 1.0);
}

TEST(ClippedEdgeSequence, AFrameTheSharedLevelDoesNotFitKeepsItsOwnRow) {
  // The plate 1.5 x brighter in one frame (a lamp's flicker) whose edge lights two rows: the
  // shared level cannot fit it, so its own fit stays.
  std::vector<Measured> frames;
  uint64_t seed = 500;
  for (double y : Edges()) frames.push_back(Measure(y, 4.0, seed++));
  const ClippedLevel level = SharedClippedLevel(Pointers(frames), 0.5);
  ASSERT_TRUE(level.found());
  const double y = 60.3;  // pixel 60 a fifth covered: rows 59 and 60 partly lit at gain 6
  const Measured bright = Measure(y, 6.0, 7);
  ASSERT_TRUE(bright.profile.valid());
  std::vector<double> rows{bright.row};
  EXPECT_EQ(RefitClippedRows({&bright.profile}, level, &rows), 0u);
  EXPECT_EQ(rows[0], bright.row);
  EXPECT_NEAR(rows[0], y, 0.05);
}

TEST(ClippedEdgeSequence, FramesWithoutAClippedEdgeAreLeftAsTheyAre) {
  std::vector<Measured> frames;
  uint64_t seed = 700;
  for (double y : Edges()) frames.push_back(Measure(y, 4.0, seed++));
  const ClippedLevel level = SharedClippedLevel(Pointers(frames), 0.5);
  std::vector<const ClippedEdgeProfile*> p = Pointers(frames);
  p[3] = nullptr;  // a frame whose edge did not clip
  std::vector<double> rows(p.size(), -1.0);
  EXPECT_EQ(RefitClippedRows(p, level, &rows), p.size() - 1);
  EXPECT_EQ(rows[3], -1.0);
}

}  // namespace
}  // namespace clipped_edge_test
}  // namespace dimer::tracking
