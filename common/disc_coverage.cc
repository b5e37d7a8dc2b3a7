#include "common/disc_coverage.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dimer {
namespace {


struct Disc {
  double r, r2;
  double S(double x) const {  // antiderivative of s(X) = sqrt(R^2 - X^2) on [-R, R]
    const double s = std::sqrt(std::max(0.0, r2 - x * x));
    return 0.5 * (x * s + r2 * std::asin(std::clamp(x / r, -1.0, 1.0)));
  }
  // S(-R) = -pi R^2 / 4 with no asin call (asin(-1) is -pi/2 exactly as rounded). S is odd, so
  // F needs only S(x') and S(c): two asin calls per corner instead of up to eight.
  double SMinusR() const { return 0.5 * (r2 * -(0.5 * std::numbers::pi)); }
  // What F needs of one corner column (S at x') and of one corner row (c and S(c) at |y|): a
  // pixel's four corners share two of each, so a pixel costs four asin calls, not eight.
  struct Column {
    double xc, sx;
  };
  struct Row {
    double ay, c, sc;  // c < 0: |y| >= R
  };
  Column AtColumn(double x) const {
    const double xc = std::clamp(x, -r, r);
    return {xc, S(xc)};
  }
  Row AtRow(double y) const {
    const double ay = std::abs(y);
    if (ay >= r) return {ay, -1.0, 0.0};
    const double c = std::sqrt(r2 - ay * ay);
    return {ay, c, S(c)};
  }
  double F(const Column& col, const Row& row, double y) const {  // area X <= x, Y <= y
    const double xc = col.xc, sx = col.sx, s_r = SMinusR();
    const double half = sx - s_r;  // integral of s up to x'
    double upper;                  // F(x, |y|)
    if (row.c < 0) {
      upper = 2.0 * half;
    } else {
      const double c = row.c, sc = row.sc, ay = row.ay;
      const double m = ((xc <= -c ? sx : -sc) - s_r) + ay * (std::clamp(xc, -c, c) + c) +
                       ((xc >= c ? sx : sc) - sc);
      upper = half + m;
    }
    return y < 0 ? 2.0 * half - upper : upper;  // H(x) - F(x, -y), H = 2 half
  }
  double F(double x, double y) const { return F(AtColumn(x), AtRow(y), y); }
  // dF/dx: chord length at X = x with Y <= y.
  double Fx(double x, double y) const {
    if (x <= -r || x >= r) return 0.0;
    const double s = std::sqrt(r2 - x * x);
    return std::clamp(y, -s, s) + s;
  }
};

}  // namespace

double DiscPixelArea(double col, double row, const Eigen::Vector2d& centre, double radius_px) {
  const double dx = col - centre.x(), dy = row - centre.y();
  const double dist = std::sqrt(dx * dx + dy * dy);
  if (dist >= radius_px + kPixelHalfDiagonalPx) return 0.0;
  if (dist <= radius_px - kPixelHalfDiagonalPx) return 1.0;
  const Disc d{radius_px, radius_px * radius_px};
  const double a = d.F(dx + 0.5, dy + 0.5) - d.F(dx - 0.5, dy + 0.5) - d.F(dx + 0.5, dy - 0.5) +
                   d.F(dx - 0.5, dy - 0.5);
  return std::clamp(a, 0.0, 1.0);
}

PixelCoverage DiscPixelCoverage(double col, double row, const Eigen::Vector2d& centre,
                                double radius_px) {
  PixelCoverage out;
  const double dx = col - centre.x(), dy = row - centre.y();
  const double dist = std::sqrt(dx * dx + dy * dy);
  if (dist >= radius_px + kPixelHalfDiagonalPx) return out;
  if (dist <= radius_px - kPixelHalfDiagonalPx) {
    out.area = 1.0;
    return out;
  }
  const Disc d{radius_px, radius_px * radius_px};
  double f = 0, fx = 0, fy = 0, xfx_yfy = 0;
  const Disc::Column cols[2] = {d.AtColumn(dx + 0.5), d.AtColumn(dx - 0.5)};
  const Disc::Row rows[2] = {d.AtRow(dy + 0.5), d.AtRow(dy - 0.5)};
  for (int i = 0; i < 4; ++i) {  // corners with inclusion-exclusion sign
    const double x = dx + ((i & 1) ? -0.5 : 0.5), y = dy + ((i & 2) ? -0.5 : 0.5);
    const double sign = ((i == 0) || (i == 3)) ? 1.0 : -1.0;
    const double cfx = d.Fx(x, y), cfy = d.Fx(y, x);  // F is symmetric in (x, y)
    f += sign * d.F(cols[i & 1], rows[(i >> 1) & 1], y);
    fx += sign * cfx;
    fy += sign * cfy;
    xfx_yfy += sign * (x * cfx + y * cfy);
  }
  out.area = std::clamp(f, 0.0, 1.0);
  out.d_cx = -fx;  // moving the centre right is moving the pixel left
  out.d_cy = -fy;
  out.d_r = (2.0 * f - xfx_yfy) / radius_px;
  return out;
}

}  // namespace dimer
