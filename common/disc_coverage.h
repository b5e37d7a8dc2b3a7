#pragma once
// Exact area of a disc inside a square pixel, and its derivatives. The renderer uses it for
// anti-aliased sphere silhouettes with no sampling error; the disc fit uses it as its model; the
// benchmark uses its derivatives for the Cramér-Rao bound. One function, three users, so the
// model the fit assumes is exactly the one the renderer draws.
//
// Derivation. Let the disc be centred at the origin with radius R, s(X) = sqrt(R^2 - X^2), and
// F(x, y) = area of {X <= x, Y <= y} inside the disc. For y >= 0,
//   F = integral_{-R}^{x'} [s(X) + min(y, s(X))] dX,   x' = clamp(x, -R, R),
// which splits at X = -c, c (c = sqrt(R^2 - y^2), where s = y) into pieces of the antiderivative
// S(X) = (X s(X) + R^2 asin(X / R)) / 2 and a rectangle. For y < 0, F(x, y) = H(x) - F(x, -y),
// H(x) being the area left of x (reflection Y -> -Y). A pixel's coverage is the inclusion-
// exclusion of F at its four corners. Derivatives: dF/dx is the chord length at X = x below y,
// clamp(y, -s, s) + s, and symmetrically for y; F is homogeneous of degree 2 in (x, y, R), so
// dF/dR = (2F - x dF/dx - y dF/dy) / R.
#include <Eigen/Core>

namespace dimer {

// Half-diagonal of a unit pixel: a pixel whose centre is at least R + this from the disc centre
// is wholly outside (coverage 0, no derivative), at most R - this wholly inside (1).
inline constexpr double kPixelHalfDiagonalPx = 0.70710678118654752;

struct PixelCoverage {
  double area = 0;       // fraction of the unit pixel inside the disc, 0..1
  double d_cx = 0;       // derivative with respect to the disc centre column
  double d_cy = 0;       // ... centre row
  double d_r = 0;        // ... radius
};

// Coverage of the unit pixel centred at (col, row) by the disc centred at `centre` with
// `radius_px`. Pixels entirely inside or outside return at once (no transcendental calls).
double DiscPixelArea(double col, double row, const Eigen::Vector2d& centre, double radius_px);
// Same with the derivatives (used by the fit and the Cramér-Rao bound).
PixelCoverage DiscPixelCoverage(double col, double row, const Eigen::Vector2d& centre,
                                double radius_px);

}  // namespace dimer
