#pragma once
// The sphere's outline (its limb) in a learnt appearance (template_locator.h): where the sphere
// ends, whatever it reflects. The template method's column offset and, when the scale is not
// given, the sphere's radius come from it (appearance_model.h).
//
// Why the limb. A front-lit steel sphere is a mirror: its image is its surroundings (the lamps as
// highlights, the plate over the lower half), so its brightness pattern says nothing certain
// about where the centre is; lamps to one side, a gain ramp across the frame or a perspective
// camera make that pattern lopsided (a mirror-symmetry axis was pixels off on such footage). The
// outline does not depend on the lighting: a circle of the sphere's radius about the centre
// (under a pinhole camera the projection of a sphere is an ellipse whose centre is within
// (R / f)^2 x (distance from the image centre) of the projected centre: < 0.01 px here). Its
// contrast does depend on the lighting (the bright reflected plate against the dark backdrop in
// the lower half, a faint grey against black in the upper half, nothing where the backdrop is
// reflected at grazing incidence), so each part of the outline is weighed by its contrast.
//
// Method, on the mean appearance (noise already averaged over the learning frames):
//   1. gradient by cv::Sobel; only pixels whose 5x5 neighbourhood is known (not rod, not plate);
//   2. coarse centre by a gradient Hough transform: every pixel with a clear gradient votes at
//      +-R along its gradient for every R in the radius range; the accumulator, smoothed, peaks
//      at the centre within about a pixel (highlights vote in rings and do not pile up);
//   3. per ray from that centre (kLimbRays of them), the edge is the sub-pixel peak of the
//      radial derivative within kLimbBandPx of the radius (whatever its sign: the outline is
//      brighter or darker than the backdrop depending on what it reflects);
//   4. weighted least squares circle fit (Gauss-Newton on centre and, if unknown, radius),
//      weights the squared edge contrast (the position error of an edge is noise / contrast),
//      rays more than kLimbOutlierSigmas robust sigmas off dropped; steps 3-4 repeated from the
//      fitted circle;
//   5. the column from mirrored pairs of envelope rays (theta, pi - theta): each pair's centre
//      column is where its chord's perpendicular bisector meets the centre's row (the chord's
//      midpoint alone is drawn toward the point the rays are cast from, see limb_fit.cc); it
//      needs no radius, when there are enough pairs. Without pairs (one side of the outline
//      dark), the column is the midpoint of the circle fits with the radius held and free, with
//      half their difference in its uncertainty (limb_fit.cc).
// A common inward shift of every edge (the grazing rim reflecting the backdrop: 0.2-0.4 px on the
// POV-Ray steel) cancels in the pairs; it shortens the radius and, where only the lower half has
// edges, moves the row: the template method takes its rows from the plate contact, not from
// here. What does not cancel is a shift that differs between the two sides: where the lamps
// light one side of the rim less, its outline recedes further inside (POV-Ray front_softbox:
// 0.45-0.75 px on the dim side against 0.25-0.35 px on the lit one, the profile's shape alike),
// and the column moves toward the dim side (-0.15 to -0.26 px there). No edge estimator sees the
// outline under a dark band; the uncertainty (half the pairs' and the circle's difference) shows
// it (0.18-0.21 px there, 0.05-0.06 px on front_point).
#include <Eigen/Core>
#include <limits>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {

inline constexpr int kLimbRays = 120;
// Edge search band about the current radius, px (the coarse centre is within ~1 px).
inline constexpr double kLimbBandPx = 3.0;
// Rays further off the circle than this many robust sigmas (and kLimbOutlierFloorPx) are not
// limb: a highlight or a reflection's boundary caught in the search band.
inline constexpr double kLimbOutlierSigmas = 3.0;
inline constexpr double kLimbOutlierFloorPx = 0.5;
// At least this many rays with an edge, on both sides of the vertical, or no fit.
inline constexpr int kLimbMinRays = 12;
// The column comes from mirrored pairs of rays when at least this many pairs have both edges,
// else from the circle fit.
inline constexpr int kLimbMinPairs = 6;

struct LimbFit {
  bool ok = false;
  Eigen::Vector2d centre{0, 0};    // relative to the reference point (half, half), px
  double radius_px = 0;
  // Standard uncertainty (col, row), px; the column's includes half the difference between the
  // pairs' and the circle's answers.
  Eigen::Vector2d centre_err{0, 0};
  // centre_err.x()'s two parts: the scatter of the pairs (or the circle fit's covariance), from
  // this one appearance, and the model's (half the pairs' and the circle's difference, or of the
  // circle fits with the radius held and free). The first assumes independent edges, which
  // neighbouring rays are not; LimbColumnOffset (appearance_model.h) measures the noise instead.
  double col_scatter_err = 0, col_model_err = 0;
  double radius_err = 0;
  int rays = 0;                    // rays whose edge entered the fit
  int pairs = 0;                   // mirrored pairs of rays the column came from (0: the fit)
};

struct LimbFitOptions {
  double radius_px = 0;       // the known radius, or (fit_radius) a guess within ~30 %
  bool fit_radius = false;
  double max_shift_px = 4;    // how far from the reference point the centre (its column, when
                              // the row is given) may be
  // The centre row relative to the reference point when known (the plate contact): only the
  // column (and radius) are fitted, and an outline seen on one side only still gives it. NaN:
  // the row is fitted too.
  double row = std::numeric_limits<double>::quiet_NaN();
  // With the row free, an outline seen on one side only is refused (its column and row trade
  // against each other) unless this is set: the outline transfer (appearance_model.h) fits two
  // spheres' outlines over the same pixels, and the two one-sided arcs err alike.
  bool one_side_ok = false;
};

// Fits the outline of the sphere in `a` (CV_32F appearance with its mask).
LimbFit FitLimb(const Appearance& a, const LimbFitOptions& o);

}  // namespace dimer::tracking
