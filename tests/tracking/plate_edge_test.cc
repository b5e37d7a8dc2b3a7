#include "tracking/plate_edge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace {

TEST(PlateEdge, ExactOnABoxSampledStepAtAnySubPixelRow) {
  // The coverage sum has no pixel locking: exact for any edge position within a pixel.
  for (double y = 20.0; y < 21.0; y += 0.05) {
    std::vector<double> p(40);
    for (int r = 0; r < 40; ++r) p[r] = 30 + 170 * std::clamp(r + 0.5 - y, 0.0, 1.0);
    EXPECT_NEAR(EdgeRowInProfile(p, 100, 5.0), 100 + y, 1e-12);
  }
}

TEST(PlateEdge, NoStepNoEdge) {
  std::vector<double> p(40, 50.0);
  EXPECT_TRUE(std::isnan(EdgeRowInProfile(p, 0, 5.0)));
}

class PlateEdgeRendered : public ::testing::TestWithParam<Lighting> {};

TEST_P(PlateEdgeRendered, SubPixelRowOnRenderedFramesWithNoise) {
  // sigma = 2 averaged over ~300 columns: ~0.1 grey level per row, ~0.01 px on the edge.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RenderOptions o;
  o.lighting = GetParam();
  o.noise = 2.0;
  for (int k = 0; k < 10; ++k) {
    const double plate = 195 + 5 * u(rng);
    const SceneGeometry s = testing::TiltedDimer(150 + 20 * u(rng), plate, 23.75, 0.1, 3.75);
    const cv::Mat img = RenderFrame({s}, o, k);
    const double coarse = FindPlateRowCoarse(img);
    EXPECT_NEAR(coarse, plate, 1.0);
    const double fine = RefinePlateRow(img, coarse, {{100, 350}});
    EXPECT_NEAR(fine, plate, 0.03) << ToString(GetParam());
  }
}

INSTANTIATE_TEST_SUITE_P(Lightings, PlateEdgeRendered,
                         ::testing::Values(Lighting::kDisc, Lighting::kBacklit, Lighting::kReflect),
                         [](const auto& p) { return ToString(p.param); });

}  // namespace
}  // namespace dimer::tracking
