#include "render/scene_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error.h"
#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace {

RenderOptions Options(Lighting l, double noise) {
  RenderOptions o;
  o.lighting = l;
  o.noise = noise;
  o.gradient = 0;
  return o;
}

TEST(SceneRenderer, DeterministicForASeedAndDifferentAcrossSeeds) {
  const SceneGeometry s = testing::TiltedDimer(150.3, 200.2, 23.75, 0.1, 3.75);
  RenderOptions o = Options(Lighting::kReflect, 2.0);
  const cv::Mat a = RenderFrame({s}, o, 7), b = RenderFrame({s}, o, 7);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, RenderFrame({s}, o, 8), cv::NORM_INF), 0.0);  // per-frame noise
  o.seed = 2;
  EXPECT_GT(cv::norm(a, RenderFrame({s}, o, 7), cv::NORM_INF), 0.0);
}

TEST(SceneRenderer, UniformDiscHasTheExactArea) {
  // Noise-free radiance of a disc scene: the excess over the background integrates to
  // pi R^2 (sphere - background) exactly (analytic coverage), wherever the centre falls.
  RenderOptions o = Options(Lighting::kDisc, 0);
  SceneGeometry s = testing::TiltedDimer(150.37, 200.0, 23.75, 0.0, 0.0);
  s.plate_row = 1e9;  // plate out of view
  const cv::Mat rad = RenderRadiance(s, o);
  const double excess = cv::sum(rad)[0] - 0.12 * rad.total();
  EXPECT_NEAR(excess, 2 * std::numbers::pi * 23.75 * 23.75 * (0.80 - 0.12), 1e-2);
}

TEST(SceneRenderer, NoiseHasTheRequestedSigmaAndDepth) {
  RenderOptions o = Options(Lighting::kDisc, 5.0);
  SceneGeometry s = testing::TiltedDimer(-1000, 1e9, 23.75, 0, 0);  // empty frame
  const cv::Mat img = RenderFrame({s}, o, 1);
  cv::Scalar mean, sd;
  cv::meanStdDev(img, mean, sd);
  EXPECT_NEAR(mean[0], 0.12 * 255, 0.1);
  EXPECT_NEAR(sd[0], std::sqrt(25.0 + 1.0 / 12.0), 0.1);  // noise + quantisation
  o.bit_depth = 16;
  EXPECT_EQ(RenderFrame({s}, o, 1).depth(), CV_16U);
}

TEST(SceneRenderer, ReflectLookHasDarkBodyHighlightsAndBrightPlateEdge) {
  RenderOptions o = Options(Lighting::kReflect, 0);
  const SceneGeometry s = testing::TiltedDimer(150, 200, 23.75, 0.0, 3.75);
  const cv::Mat img = RenderFrame({s}, o, 0);
  const int cx = 150, cy = int(200 - 23.75);
  cv::Mat body = img(cv::Rect(cx - 16, cy - 16, 33, 33));
  double lo, hi;
  cv::minMaxLoc(body, &lo, &hi);
  EXPECT_EQ(hi, 255);  // a saturated lamp highlight on the body
  // Most of the body is dark (a mirror of a dim room), far below the highlight.
  EXPECT_LT(cv::mean(body)[0], 0.45 * 255);
  // The brightest row profile is the plate's lit top edge, brighter than the mean body.
  const double edge = cv::mean(img.row(201))[0];
  EXPECT_GT(edge, 0.9 * 255);
  EXPECT_LT(cv::mean(img.row(10))[0], 0.1 * 255);  // dark background
}

TEST(SceneRenderer, CheckReportsEveryBadField) {
  RenderOptions o;
  o.width = 3;
  o.bit_depth = 12;
  try {
    o.Check();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--width"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("--bit-depth 12"), std::string::npos);
  }
  EXPECT_THROW(ParseLighting("sunny"), InputError);
  EXPECT_EQ(ParseLighting(ToString(Lighting::kBacklit)), Lighting::kBacklit);
}

}  // namespace
}  // namespace dimer::tracking
