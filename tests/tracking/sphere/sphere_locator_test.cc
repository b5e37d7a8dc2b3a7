// The locators behind one interface (tracking/sphere/sphere_locator.h): each states its own
// uncertainty, and that uncertainty is the scatter its centres show over noise.
#include "tracking/sphere/sphere_locator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "render/scene_renderer.h"
#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace sphere_locator_test {
namespace {

constexpr double kRadiusPx = 23.75;
constexpr double kNoise = 2.0;  // grey levels

struct Spread {
  Eigen::Vector2d scatter{0, 0};  // standard deviation of the centres over noise, px
  Eigen::Vector2d stated{0, 0};   // RMS of the stated standard deviations, px
  double quality = 0;             // lowest quality
  int found = 0;
};

// Sphere `k` of a dimer tilted by 0.12 rad, located from a prediction 0.3 px off in each of
// `n` frames that differ only in their noise.
Spread OverNoise(const SphereLocator& locator, Lighting lighting, int k, int n,
                 const Eigen::Vector2d& reference_offset = {0, 0}) {
  RenderOptions o;
  o.lighting = lighting;
  o.noise = kNoise;
  o.gradient = 0.0;
  const SceneGeometry s = testing::TiltedDimer(150.3, 200.6, kRadiusPx, 0.12, 3.75);
  const Eigen::Vector2d truth = (k == 0 ? s.left : s.right) + reference_offset;
  SpherePrediction p;
  p.position = truth + Eigen::Vector2d(0.3, -0.3);
  p.precise = true;
  p.radius_px = kRadiusPx;
  p.polarity = lighting == Lighting::kBacklit ? -1 : 1;
  p.noise_sigma = std::sqrt(kNoise * kNoise + 1.0 / 12.0);  // and the 8-bit rounding
  p.other = k == 0 ? s.right : s.left;
  p.plate_row = s.plate_row;
  std::vector<Eigen::Vector2d> c;
  Spread out;
  out.quality = 1;
  for (int i = 0; i < n; ++i) {
    const SphereMeasurement m = locator.Locate(RenderFrame({s}, o, uint64_t(i)), p);
    if (!m.found()) continue;
    c.push_back(m.centre);
    out.stated += m.sigma_px.cwiseAbs2();
    out.quality = std::min(out.quality, m.quality);
  }
  out.found = int(c.size());
  Eigen::Vector2d mean(0, 0);
  for (const auto& v : c) mean += v / double(c.size());
  for (const auto& v : c) out.scatter += (v - mean).cwiseAbs2() / double(c.size() - 1);
  out.scatter = out.scatter.cwiseSqrt();
  out.stated = (out.stated / double(c.size())).cwiseSqrt();
  return out;
}

// With n = 160 frames the measured scatter is itself uncertain by 1 / sqrt(2 n) ~ 6 %: a stated
// uncertainty below 0.8 of it understates it. Above, the centroid errs high by design (its
// masks are left out, and a pixel at a clamp counts as noisy half the time: <= ~1.25,
// measure_sphere.cc CentroidSigma), so the upper bound is 1.5.
void ExpectStatedIsTheScatter(const Spread& s, int n, const std::string& what) {
  std::printf("%s: scatter %.4f %.4f stated %.4f %.4f quality %.3f\n", what.c_str(),
              s.scatter.x(), s.scatter.y(), s.stated.x(), s.stated.y(), s.quality);
  ASSERT_EQ(s.found, n) << what;
  for (int axis = 0; axis < 2; ++axis) {
    const double ratio = s.stated(axis) / s.scatter(axis);
    EXPECT_GT(ratio, 0.8) << what << " axis " << axis;
    EXPECT_LT(ratio, 1.5) << what << " axis " << axis;
  }
  EXPECT_GT(s.quality, 0.9) << what;
}

int Frames() { return std::max(40, int(160 * testing::TestScale())); }

TEST(SphereLocator, StatedUncertaintyMatchesTheScatterOverNoise) {
  const int n = Frames();
  const auto centroid = MakeSilhouetteLocator(Method::kCentroid);
  const auto disc = MakeSilhouetteLocator(Method::kDiscFit);
  ExpectStatedIsTheScatter(OverNoise(*centroid, Lighting::kDisc, 0, n), n, "centroid, disc");
  ExpectStatedIsTheScatter(OverNoise(*centroid, Lighting::kDisc, 1, n), n, "centroid, disc right");
  ExpectStatedIsTheScatter(OverNoise(*centroid, Lighting::kBacklit, 0, n), n, "centroid, backlit left");
  ExpectStatedIsTheScatter(OverNoise(*centroid, Lighting::kBacklit, 1, n), n, "centroid, backlit");
  ExpectStatedIsTheScatter(OverNoise(*disc, Lighting::kDisc, 0, n), n, "discfit, disc");
  ExpectStatedIsTheScatter(OverNoise(*disc, Lighting::kBacklit, 1, n), n, "discfit, backlit");
  // A mirror sphere: the rim fit, whichever the method.
  ExpectStatedIsTheScatter(OverNoise(*centroid, Lighting::kReflect, 0, n), n, "rim, reflect");
  ExpectStatedIsTheScatter(OverNoise(*centroid, Lighting::kReflect, 1, n), n, "rim, reflect right");
}

// The template's stated uncertainty is the information its registration has (the residual
// propagated through the smoothed least squares, RegistrationSigma). The quick step (fast_follow.h)
// solves those least squares and meets the silhouettes' test; ECC scatters 3.0-3.9 times that
// bound on this mirror sphere (1.8-2.4 times on a smooth pattern), its iterations and
// resampling adding their own noise, so for ECC the test holds that the statement is a bound,
// and how far ECC is from it.
void ExpectStatedIsTheBound(const Spread& s, int n, const std::string& what) {
  std::printf("%s: scatter %.4f %.4f stated %.4f %.4f quality %.3f\n", what.c_str(),
              s.scatter.x(), s.scatter.y(), s.stated.x(), s.stated.y(), s.quality);
  ASSERT_EQ(s.found, n) << what;
  for (int axis = 0; axis < 2; ++axis) {
    const double ratio = s.scatter(axis) / s.stated(axis);
    EXPECT_GT(ratio, 0.8) << what << " axis " << axis;
    EXPECT_LT(ratio, 5.0) << what << " axis " << axis;
  }
  EXPECT_GT(s.quality, 0.9) << what;
}

TEST(SphereLocator, TemplateStatesItsScatterAndEccItsBound) {
  // The appearance: the noise-free frame's mirror sphere, reference point at its centre.
  RenderOptions o;
  o.lighting = Lighting::kReflect;
  o.noise = 0;
  o.gradient = 0.0;
  const SceneGeometry s = testing::TiltedDimer(150.3, 200.6, kRadiusPx, 0.12, 3.75);
  const cv::Mat clean = RenderFrame({s}, o, 0);
  auto both = std::make_shared<std::array<Appearance, 2>>();
  for (int k = 0; k < 2; ++k) {
    Appearance& a = (*both)[k];
    a.radius_px = kRadiusPx;
    a.half = int(std::ceil(kRadiusPx + 4));
    const Eigen::Vector2d c = k == 0 ? s.left : s.right;
    const cv::Point at(int(std::lround(c.x())), int(std::lround(c.y())));
    clean(cv::Rect(at.x - a.half, at.y - a.half, 2 * a.half + 1, 2 * a.half + 1))
        .convertTo(a.image, CV_32F);
    a.mask = cv::Mat::ones(a.image.size(), CV_8U);
  }
  const int n = Frames();
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d c = k == 0 ? s.left : s.right;
    const Eigen::Vector2d reference(std::lround(c.x()) - c.x(), std::lround(c.y()) - c.y());
    const std::string side = k == 0 ? ", left" : ", right";
    const auto quick = MakeTemplateLocator(both, k, EccStop{50, 1e-5});
    ExpectStatedIsTheScatter(OverNoise(*quick, Lighting::kReflect, k, n, reference), n,
                             "template, quick step" + side);
    const auto ecc = MakeTemplateLocator(both, k, EccStop{50, 1e-5}, FollowStop{0});
    ExpectStatedIsTheBound(OverNoise(*ecc, Lighting::kReflect, k, n, reference), n,
                           "template, ECC" + side);
  }
}

}  // namespace
}  // namespace sphere_locator_test
}  // namespace dimer::tracking
