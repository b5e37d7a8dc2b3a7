#include "tracking/sphere/rim_fit.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace rim_fit_test {
namespace {

constexpr double kRadiusPx = 23.75;

struct Case {
  double lift_px, tilt_rad;
  int sphere;
};

// Noise-free mirror spheres over tilts and plate contact, started 1 px off.
std::vector<Eigen::Vector2d> Errors(bool fit_radius, std::vector<double>* radii) {
  RenderOptions o;
  o.lighting = Lighting::kReflect;
  o.noise = 0;
  o.gradient = 0;
  std::vector<Eigen::Vector2d> errors;
  for (double lift : {0.0, 10.0}) {
    for (double tilt : {0.0, 0.15, 0.3}) {
      SceneGeometry s = testing::TiltedDimer(130.3, 195.6, kRadiusPx, tilt, 3.75);
      s.left.y() -= lift;
      s.right.y() -= lift;
      const cv::Mat img = RenderFrame({s}, o, 0);
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d truth = k == 0 ? s.left : s.right, other = k == 0 ? s.right : s.left;
        RimFitInput in;
        in.plate_row = s.plate_row;
        in.rod_dir = (other - truth).normalized();
        in.rod_half_width_px = 0.3 * kRadiusPx;
        in.fit_radius = fit_radius;
        const RimFitResult r = FitRim(img, truth + Eigen::Vector2d(0.8, -0.6),
                                      fit_radius ? kRadiusPx - 1.0 : kRadiusPx, in);
        EXPECT_TRUE(r.ok) << "lift " << lift << " tilt " << tilt << " sphere " << k;
        errors.push_back(r.centre - truth);
        if (radii) radii->push_back(r.radius_px);
      }
    }
  }
  return errors;
}

TEST(RimFit, MirrorSphereOffsetIsTheSameAtEveryTiltAndContact) {
  // The offset (bias) comes from the rim's fixed reflection pattern; what must not change with
  // the tilt (rod mask) or the plate contact is the error itself: max deviation from the mean
  // <= 0.03 px noise free (the scatter target is 0.05 px RMS with noise).
  const std::vector<Eigen::Vector2d> e = Errors(false, nullptr);
  Eigen::Vector2d mean(0, 0);
  for (const auto& x : e) mean += x / double(e.size());
  double worst = 0;
  for (const auto& x : e) worst = std::max(worst, (x - mean).norm());
  std::printf("[ stats    ] rim fit offset (%.4f, %.4f) px, max deviation %.4f px\n", mean.x(),
              mean.y(), worst);
  EXPECT_LE(worst, 0.03);
  EXPECT_LT(mean.norm(), 0.2);
}

TEST(RimFit, FitsTheRadiusOfAMirrorSphere) {
  // Started 1 px small; the silhouette radius is the sphere's (the calibration of --diameter
  // depends on it): within 0.05 px (0.2 %) noise free.
  std::vector<double> radii;
  Errors(true, &radii);
  for (double r : radii) EXPECT_NEAR(r, kRadiusPx, 0.05);
}

TEST(RimFit, NothingThereIsNotOk) {
  RenderOptions o;
  o.lighting = Lighting::kReflect;
  o.noise = 2;
  const SceneGeometry s = testing::TiltedDimer(130, 200, kRadiusPx, 0, 3.75);
  const cv::Mat img = RenderFrame({s}, o, 0);
  RimFitInput in;
  in.plate_row = s.plate_row;
  EXPECT_FALSE(FitRim(img, {400, 60}, kRadiusPx, in).ok);  // background only
  EXPECT_FALSE(FitRim(img, {10, 60}, kRadiusPx, in).ok);   // window leaves the frame
}

}  // namespace
}  // namespace rim_fit_test
}  // namespace dimer::tracking
