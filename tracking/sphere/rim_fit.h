#pragma once
// Centre of a non-uniform (mirror) sphere from its silhouette edge: the rim fit.
//
// Why not the centroid or the uniform disc fit. A polished steel sphere under front light is a
// mirror: its image is the environment (the dim backdrop near the rim, the bright plate over
// most of the lower half, the lamps as small highlights, the lens as a dark spot), fixed relative
// to the centre for a fixed camera and lamps. Anything that weighs the interior (a centroid) or
// assumes one interior level (the disc fit) sees that pattern cut differently by the rod and
// plate masks at every tilt, so its bias changes from frame to frame (0.1-0.4 px noise-free).
// The silhouette edge, on the other hand, is where the sphere ends whatever it reflects.
//
// Model. A pixel near the edge holds bg + (a(theta) - bg) * cover(c, R), where cover is the
// pixel's coverage by the disc with its edge taken as straight across the pixel (closed form,
// no transcendental function; the arc's departure, <= 1/(8R) ~ 0.005 px, is the same all
// round, so a constant offset), bg the background and a(theta) the sphere's level just inside
// the rim in the direction theta: it varies around the circumference (12 grey levels above the
// background at the top, ~100 at the bottom where the plate is reflected), so it is measured per
// angular sector on the ring of fully covered pixels just inside the edge and interpolated in
// angle. Gauss-Newton on (cx, cy, R) over the pixels that straddle the edge, with the rod and the
// plate left out (one-sided: a model fit, unlike a centroid, is not biased by an asymmetric
// mask). Unweighted least squares is the maximum-likelihood fit under Gaussian noise: pixels of
// the bright lower rim dominate, as they should.
//
// Start. Gauss-Newton on the exact edge sees only pixels straddling its current edge, so from
// an uncertain start (acquisition, coarse_start) it first fits a linear radial ramp of 3 px,
// then 1.5 px, which has gradient over a wider band; from a tracker's prediction it goes
// straight to the edge model. With the radius unknown, the caller tries several starting radii
// and keeps the smallest residual (measure_sphere.cc).
//
// Known radius. Where the plate is reflected within a pixel of the rim (most of the lower
// half) the edge cannot be modelled, so only sectors whose ring is as dim as the dimmest one
// (the backdrop) are fitted: the upper arc and the sides. On that arc the centre row and the
// radius are nearly degenerate, which doubles the noise of the row; the sphere's radius is a
// constant of the experiment, so it is fitted once (fit_radius, at acquisition) and then kept.
// An error in it shifts every centre by the same amount: bias, not scatter.
//
// Residual bias. The outermost fraction of a pixel of the rim reflects the backdrop even where
// the ring inside reflects the plate, and a(theta) is a sector average: both are fixed relative
// to the sphere, so they make a constant offset (the bias, reported by the tests), not scatter.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <limits>

namespace dimer::tracking {

struct RimFitInput {
  int polarity = 1;                 // +1 bright sphere, -1 dark
  double plate_row = std::numeric_limits<double>::quiet_NaN();  // plate top surface, px
  Eigen::Vector2d rod_dir{0, 0};    // unit vector toward the other sphere; zero: no rod
  double rod_half_width_px = 0;     // half-width of the corridor left out along the rod
  bool fit_radius = false;          // false: the radius is known and kept (see below)
  // A touching other sphere: pixels within other_clear_px of its centre `other` are not this
  // sphere's rim (NaN or 0: none).
  Eigen::Vector2d other{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
  double other_clear_px = 0;
  bool coarse_start = true;         // false: the start is within ~0.5 px (a tracker's
                                    // prediction), the coarse ramp stages are skipped
};

struct RimFitResult {
  bool ok = false;                  // false: too few usable edge pixels, or diverged
  Eigen::Vector2d centre{0, 0};     // (col, row), px
  double radius_px = 0;
  int iterations = 0;
  int edge_pixels = 0;              // pixels in the last Gauss-Newton pass
  double rms = 0;                   // RMS residual of the last pass, grey levels
  // Standard deviation of `centre` from the last pass (residual variance times the inverse
  // normal matrix), px; NaN when it had no more pixels than unknowns.
  Eigen::Vector2d sigma_px{std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::quiet_NaN()};
};

// Fits the rim of the sphere near (`centre`, `radius_px`) in `frame` (CV_8U or CV_16U).
RimFitResult FitRim(const cv::Mat& frame, const Eigen::Vector2d& centre, double radius_px,
                    const RimFitInput& input);

}  // namespace dimer::tracking
