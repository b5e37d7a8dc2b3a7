#pragma once
// Sub-pixel centre of one sphere near a first guess, by one of two methods (`--method`):
//
//  - centroid: the paper's thresholded intensity-weighted centroid. Each pixel's weight is its
//    level between the local background and sphere levels, clamped to [0, 1]: interior pixels
//    weigh 1 (their noise is clipped away), exterior 0, and an edge pixel its covered fraction,
//    so the weighted centroid is the silhouette's area centroid (intensity variations inside a
//    mirror sphere do not pull it). Anything that is not the sphere (the rod leaving it, the
//    plate below) is masked out by a mask that is point-symmetric about the current estimate:
//    a symmetric mask removes equal parts on both sides and leaves the centroid of a symmetric
//    object unbiased, and iterating makes the estimate the mask's fixed point.
//  - discfit: least squares fit of the exact pixel-coverage disc model (disc_coverage.h) to the
//    pixels within kFitBandPx of the edge: centre, radius and the two levels (Gauss-Newton with
//    Eigen). It is the maximum-likelihood estimate under Gaussian noise for a uniform disc, so it
//    approaches the Cramér-Rao bound; it costs more.
//
// Non-uniform (mirror) spheres, recognised by their levels, end with the rim fit (rim_fit.h)
// whichever the method: a centroid of a mirror image is not the centre of the sphere.
//
// A sphere whose window leaves the frame is `kClipped`; one whose weighted area is far from
// pi R^2 (absent, or merged with something) is `kMissing`. Both are expected outcomes, not errors.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <limits>
#include <string>

namespace dimer::tracking {

// kTemplate and kAuto are sequence-level methods (run_track.h): the learnt appearance is located
// per frame by template_locator.h, and auto chooses per footage (method_choice.h). Given to
// MeasureSphere they measure as kCentroid.
enum class Method { kCentroid, kDiscFit, kTemplate, kAuto };
std::string ToString(Method m);
Method ParseMethod(const std::string& name, const std::string& option = "--method");

struct RefineContext {
  int polarity = 1;                   // +1: spheres brighter than background; -1: darker
  double plate_row = std::numeric_limits<double>::quiet_NaN();  // plate top surface, px
  Eigen::Vector2d rod_dir{0, 0};      // unit vector toward the other sphere; zero: no rod cut
  bool fit_radius = false;            // mirror spheres: fit the radius too (else it is known)
  double radius_start_px = std::numeric_limits<double>::quiet_NaN();  // fit_radius: first guess
  bool precise_guess = false;         // the guess is a tracker's prediction (within ~0.5 px)
  // The other sphere's centre (its prediction or detection; NaN: unknown), of the same radius.
  // Touching or nearly touching spheres (A_r < ~2.2) reach into each other's windows: the other
  // disc widened by kOtherSphereMarginPx is left out of the measurement (for the centroid with
  // its point mirror image, like the rod). Farther apart it changes nothing.
  Eigen::Vector2d other{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
  // The frame's pixel noise, grey levels (precision_bound.h, FrameNoiseSigma): the centroid's
  // stated uncertainty scales with it (NaN: none stated). The fits take theirs from their
  // residuals.
  double noise_sigma = std::numeric_limits<double>::quiet_NaN();
};

struct SphereMeasurement {
  enum class Status { kFound, kClipped, kMissing };
  Status status = Status::kMissing;
  Eigen::Vector2d centre{0, 0};  // (col, row), px
  double radius_px = 0;          // from the weighted area (centroid) or the fit (discfit)
  double area_fraction = 0;      // weighted area / (pi radius_guess^2)
  int iterations = 0;
  bool rim_fit = false;          // non-uniform (mirror) sphere: centre and radius from FitRim
  // Template method: ECC's correlation coefficient of the learnt appearance there, where ECC
  // converged (Located::refined; NaN otherwise).
  double score = std::numeric_limits<double>::quiet_NaN();
  // Standard deviation of `centre` (col, row), px, from the pixels the measurement used: the
  // centroid's from the noise of its unclamped weights, a fit's (disc, rim) from its residual
  // and the inverse of its normal matrix; NaN where it cannot be stated. Within 0.86-1.12 of
  // the scatter over noise (SphereLocator.StatedUncertaintyMatchesTheScatterOverNoise). The
  // template states its registration's bound, which the quick step meets and ECC misses by 2-4
  // times (SphereLocator.TemplateStatesItsScatterAndEccItsBound).
  Eigen::Vector2d sigma_px{std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::quiet_NaN()};
  // How well the sphere matched what the locator expects, 0 to 1: a silhouette's area against
  // pi R^2 (min of the ratio and its inverse), a template's correlation coefficient.
  double quality = std::numeric_limits<double>::quiet_NaN();
  bool found() const { return status == Status::kFound; }
};

// `radius_px` is the expected sphere radius: it sizes the window (radius + kWindowMarginPx) and
// the masks. `frame` is CV_8U or CV_16U, single channel.
SphereMeasurement MeasureSphere(const cv::Mat& frame, const Eigen::Vector2d& guess,
                                double radius_px, const RefineContext& context, Method method);

}  // namespace dimer::tracking
