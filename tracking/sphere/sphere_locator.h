#pragma once
// One interface for every way of placing a sphere in one frame: a frame and a prediction in, a
// centre with its own uncertainty and a quality score out. The film-level stages (the
// follower, frame_follower.h) choose a locator once per film and never look inside it:
//
//  - the silhouette locator (measure_sphere.h): the thresholded centroid or the exact disc
//    fit, ending with the rim fit for a mirror sphere;
//  - the template locator (template_locator.h): a learnt appearance registered by ECC, its
//    result the appearance's reference point (the film's offset turns it into the centre).
//
// A prediction is precise when it comes from following (a constant-velocity step, within about
// a pixel) and coarse when it comes from a whole-frame detection; each locator searches as far
// as that needs. Its result states how well it is determined (SphereMeasurement::sigma_px, from
// the pixels it used and their residual) and how well the sphere matched what the locator
// expects (SphereMeasurement::quality, 0 to 1); see each implementation for how.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <array>
#include <limits>
#include <memory>

#include "tracking/sphere/measure_sphere.h"
#include "tracking/sphere/fast_follow.h"
#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {

struct SpherePrediction {
  Eigen::Vector2d position{0, 0};  // where the sphere is expected (col, row), px
  bool precise = false;            // a follower's prediction (true) or a coarse detection
  double radius_px = std::numeric_limits<double>::quiet_NaN();  // the sphere's known radius
  int polarity = 1;  // +1: spheres brighter than background; -1: darker
  // The frame's pixel noise, grey levels (FrameNoiseSigma; NaN: unknown, and the centroid then
  // states no uncertainty).
  double noise_sigma = std::numeric_limits<double>::quiet_NaN();
  // State the centre's uncertainty (SphereMeasurement::sigma_px). It costs ~25 % of a uniform
  // sphere's centroid and ~3 % of a template's registration, so a caller that does not read it
  // leaves it out (the film's follower, FollowerOptions::state_uncertainty).
  bool state_uncertainty = true;
  // The other sphere's expected position (NaN: unknown): the rod toward it and its disc, where
  // the two touch, are left out of the measurement.
  Eigen::Vector2d other{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
  double plate_row = std::numeric_limits<double>::quiet_NaN();  // plate top at this column, px
  double plate_slope = 0;  // rows per column
};

// A learnt appearance is found where its correlation coefficient reaches this (a present sphere
// scores > 0.9 at sigma = 2; an empty window or the plate scores far less).
inline constexpr double kMinTemplateScore = 0.5;

class SphereLocator {
 public:
  virtual ~SphereLocator() = default;
  virtual SphereMeasurement Locate(const cv::Mat& frame, const SpherePrediction& p) const = 0;
};

// Centroid or disc fit (Method::kCentroid, kDiscFit; the sequence-level methods measure as the
// centroid, measure_sphere.h).
std::unique_ptr<SphereLocator> MakeSilhouetteLocator(Method method);

// Appearance `which` of `appearances` (0 left, 1 right) located by the quick step (`follow`,
// fast_follow.h) and by ECC with `ecc` where that fails.
std::unique_ptr<SphereLocator> MakeTemplateLocator(
    std::shared_ptr<const std::array<Appearance, 2>> appearances, int which, const EccStop& ecc,
    const FollowStop& follow = {});

}  // namespace dimer::tracking
