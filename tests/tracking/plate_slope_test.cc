// A plate edge that slopes across the frame (a camera not quite level): its slope measured from
// the column blocks' rows (PlateEdgeSlope, EstimatePlateSlope), and its row read at any column
// with the blocks lined up along it (RefinePlateRow's slope and reference column).
#include "tracking/plate_slope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "tracking/sphere/appearance_model.h"
#include "tracking/plate/plate_edge.h"
#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {
namespace {

// A dark backdrop over a bright plate whose top edge is the line row = row_at_0 + slope col,
// each pixel's covered fraction exact across its row and integrated along its width by the
// midpoint rule over 64 sub-columns; Gaussian noise `sigma` grey levels, 8 bit.
cv::Mat SlopedEdge(int width, int height, double row_at_0, double slope, double sigma,
                   unsigned seed) {
  cv::Mat img(height, width, CV_8U);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  constexpr int kSub = 64;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      double covered = 0;
      for (int i = 0; i < kSub; ++i) {
        const double x = c - 0.5 + (i + 0.5) / kSub;
        covered += std::clamp(r + 0.5 - (row_at_0 + slope * x), 0.0, 1.0) / kSub;
      }
      img.at<uint8_t>(r, c) =
          cv::saturate_cast<uint8_t>(std::lround(30 + 170 * covered + noise(rng)));
    }
  }
  return img;
}

// Half a degree over 640 columns (5.6 px), both signs, noise-free and at sigma 2: the slope
// within 1e-4 (0.06 px across the frame) and its stated error covering it.
TEST(PlateSlope, TheEdgesSlopeFromItsBlocks) {
  for (double slope : {0.0087, -0.0087, 0.0}) {
    for (double sigma : {0.0, 2.0}) {
      const cv::Mat img = SlopedEdge(640, 120, 60.3, slope, sigma, 7);
      double err = 0;
      const double got = PlateEdgeSlope(img, {{280, 360}}, &err);
      std::printf("[ stats    ] slope %+.4f, noise %.0f: measured %+.6f +- %.6f\n", slope,
                  sigma, got, err);
      EXPECT_NEAR(got, slope, 1e-4);
      EXPECT_LE(std::abs(got - slope), std::max(4 * err, 2e-6));
    }
  }
}

// With the slope given, the row is the edge's at the reference column wherever that is, and the
// spheres' columns left out; read as level (slope 0) it is the row somewhere in the middle of
// the blocks used, up to slope x (half the width) off.
TEST(PlateSlope, TheRowIsReadAtTheReferenceColumn) {
  const double slope = 0.0087, row_at_0 = 58.4;
  const cv::Mat img = SlopedEdge(640, 120, row_at_0, slope, 2.0, 11);
  const std::vector<std::pair<double, double>> spheres = {{150, 210}, {290, 350}};
  double worst = 0;
  for (double col : {0.0, 180.0, 319.5, 500.0, 639.0}) {
    const double want = row_at_0 + slope * col;
    const double got = RefinePlateRow(img, want, spheres, kPlatePsfSigmaPx, nullptr, slope, col);
    worst = std::max(worst, std::abs(got - want));
    EXPECT_NEAR(got, want, 0.02) << "column " << col;
  }
  std::printf("[ stats    ] row at the reference column: worst error %.4f px\n", worst);
  const double level = RefinePlateRow(img, row_at_0 + slope * 180, spheres);
  EXPECT_GT(std::abs(level - (row_at_0 + slope * 180)), 0.5) << "read as level near a sphere";
}

// The sequence's estimate: taken on a half-degree slope, and not on a level plate (its tiny
// measured slope would move nothing and is not applied, so level footage is tracked as before).
TEST(PlateSlope, TakenWhereItMovesTheEdgeAndNotOnALevelPlate) {
  std::vector<cv::Mat> sloped, level;
  for (unsigned i = 0; i < 5; ++i) {
    sloped.push_back(SlopedEdge(640, 120, 60.3 + 0.1 * i, 0.0087, 2.0, 20 + i));
    level.push_back(SlopedEdge(640, 120, 60.3 + 0.1 * i, 0.0, 2.0, 40 + i));
  }
  const PlateSlope s = EstimatePlateSlope(sloped, +1);
  EXPECT_TRUE(s.applied) << s.reason;
  EXPECT_NEAR(s.value, 0.0087, 1e-4) << s.reason;
  EXPECT_EQ(s.frames, 5u);
  const PlateSlope l = EstimatePlateSlope(level, +1);
  EXPECT_FALSE(l.applied) << l.reason;
  EXPECT_EQ(l.value, 0.0);
  EXPECT_LT(std::abs(l.measured), 1e-4);
}

// An appearance of (2 half + 1)^2 pixels, all known, all 0.
Appearance WholeAppearance(int half, double radius_px) {
  Appearance a;
  a.half = half;
  a.radius_px = radius_px;
  a.image = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
  a.mask = cv::Mat::ones(2 * half + 1, 2 * half + 1, CV_8U);
  return a;
}

// A steel sphere mirrors the plate below a horizon that tilts with the plate (8 degrees): it is
// found at its row through the centre column, and the part kept above it (for the outline fit)
// is cut along it, 8 rows lower at the right edge of the appearance than at the left.
TEST(PlateSlope, TheReflectionsHorizonIsFoundAndCutAlongTheSlope) {
  const int half = 30;
  const double radius = 23.75, slope = 0.1405, horizon = 38.0;
  Appearance a = WholeAppearance(half, radius);
  for (int y = 0; y < a.image.rows; ++y) {
    for (int x = 0; x < a.image.cols; ++x) {
      const double h = horizon + slope * (x - half);  // below it: the plate's bright reflection
      a.image.at<float>(y, x) = float(20 + 100 * std::clamp(y + 0.5 - h, 0.0, 1.0));
    }
  }
  EXPECT_NEAR(ReflectionHorizon(a.image, a.mask, half, radius, slope), horizon, 1.0);
  a.horizon_slope = slope;
  const Appearance upper = UpperPart(a);
  auto first_cut = [&](int x) {
    for (int y = 0; y < upper.mask.rows; ++y) {
      if (!upper.mask.at<uint8_t>(y, x)) return y;
    }
    return upper.mask.rows;
  };
  EXPECT_EQ(first_cut(2 * half) - first_cut(0), 8);
  EXPECT_LE(first_cut(half), int(horizon) - HorizonGuard(radius));
}

// The plate's rows are cut from a template column by column along the slope: at the template's
// right edge (30 columns from its centre) the cut starts 4 rows lower at 8 degrees.
TEST(PlateSlope, TheTemplatesPlateCutFollowsTheSlope) {
  const Appearance a = WholeAppearance(30, 23.75);
  MaskContext ctx;
  ctx.plate_row = 120.0;  // under the sphere's column; the template's centre at row 100
  ctx.plate_slope = 0.1405;
  const cv::Mat m = FrameMask(a, Eigen::Vector2d(300, 100), ctx);
  auto first_cut = [&](int x) {
    for (int y = 0; y < m.rows; ++y) {
      if (!m.at<uint8_t>(y, x)) return y;
    }
    return m.rows;
  };
  const int centre = first_cut(30), left = first_cut(0), right = first_cut(60);
  EXPECT_EQ(right - centre, 4);
  EXPECT_EQ(centre - left, 4);
  ctx.plate_slope = 0;
  const cv::Mat level = FrameMask(a, Eigen::Vector2d(300, 100), ctx);
  EXPECT_EQ(cv::countNonZero(level.col(0) != level.col(60)), 0) << "level: the same rows cut";
}

}  // namespace
}  // namespace dimer::tracking
