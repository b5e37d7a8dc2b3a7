#include "tracking/sphere/limb_fit.h"

#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "common/median.h"

namespace dimer::tracking {
namespace {

// Pixels vote in the Hough transform when their gradient stands this many robust sigmas above
// the gradient noise; a ray's edge enters the fit under the same condition.
constexpr double kEdgeSigmas = 4.0;
// Radius range searched when the radius is unknown, as fractions of the guess (a front-lit steel
// sphere's silhouette radius can be 20 % short).
constexpr double kRadiusLow = 0.7, kRadiusHigh = 1.5;
// Radius range about a known radius (its pixel scale may be off by a little), px.
constexpr double kKnownRadiusSlackPx = 1.0;
constexpr double kHoughStepPx = 0.5;
constexpr double kRayStepPx = 0.25;
constexpr int kOuterPasses = 3;
constexpr int kGaussNewtonIterations = 12;

struct Gradient {
  cv::Mat gx, gy;   // CV_32F, grey levels per px
  cv::Mat valid;    // CV_8U, 1 where the 3x3 neighbourhood (Sobel's support) is known
  double sigma = 0; // robust noise of one component
};

Gradient GradientOf(const Appearance& a) {
  Gradient g;
  cv::Sobel(a.image, g.gx, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(a.image, g.gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  cv::Mat known = a.mask > 0;
  cv::erode(known, g.valid, cv::Mat::ones(3, 3, CV_8U), cv::Point(-1, -1), 1,
            cv::BORDER_CONSTANT, cv::Scalar(0));
  std::vector<double> c;
  for (int y = 0; y < g.gx.rows; ++y) {
    for (int x = 0; x < g.gx.cols; ++x) {
      if (g.valid.at<uint8_t>(y, x)) c.push_back(std::abs(g.gx.at<float>(y, x)));
    }
  }
  // Most known pixels are inside the sphere or on the backdrop, where the gradient is the
  // averaged noise plus slow shading: the MAD about zero is a conservative noise level.
  g.sigma = c.empty() ? 1e-6 : std::max(1.4826 * MedianOf(c), 1e-6);
  return g;
}

// Bilinear sample of `m` at (x, y); false outside the valid pixels.
bool Sample(const Gradient& g, double x, double y, double* gx, double* gy) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= g.gx.cols || y0 + 1 >= g.gx.rows) return false;
  if (!g.valid.at<uint8_t>(y0, x0) || !g.valid.at<uint8_t>(y0, x0 + 1) ||
      !g.valid.at<uint8_t>(y0 + 1, x0) || !g.valid.at<uint8_t>(y0 + 1, x0 + 1)) {
    return false;
  }
  const double fx = x - x0, fy = y - y0;
  auto at = [&](const cv::Mat& m) {
    return (1 - fy) * ((1 - fx) * m.at<float>(y0, x0) + fx * m.at<float>(y0, x0 + 1)) +
           fy * ((1 - fx) * m.at<float>(y0 + 1, x0) + fx * m.at<float>(y0 + 1, x0 + 1));
  };
  *gx = at(g.gx);
  *gy = at(g.gy);
  return true;
}

// Coarse centre (template pixels) and radius by the gradient Hough transform.
bool HoughCentre(const Gradient& g, double r_low, double r_high, const Eigen::Vector2d& ref,
                 double max_shift, Eigen::Vector2d* centre, double* radius) {
  cv::Mat acc = cv::Mat::zeros(g.gx.size(), CV_64F);
  std::vector<double> strength;
  for (int y = 0; y < g.gx.rows; ++y) {
    for (int x = 0; x < g.gx.cols; ++x) {
      if (!g.valid.at<uint8_t>(y, x)) continue;
      const double m = std::hypot(g.gx.at<float>(y, x), g.gy.at<float>(y, x));
      if (m > kEdgeSigmas * g.sigma) strength.push_back(m);
    }
  }
  if (strength.size() < size_t(kLimbMinRays)) return false;
  // Votes weigh min(|g|, 90th percentile): a few very strong highlight edges do not outvote the
  // limb, which is long.
  std::vector<double> s = strength;
  auto q = s.begin() + std::ptrdiff_t(0.9 * double(s.size() - 1));
  std::nth_element(s.begin(), q, s.end());
  const double cap = *q;
  for (int y = 0; y < g.gx.rows; ++y) {
    for (int x = 0; x < g.gx.cols; ++x) {
      if (!g.valid.at<uint8_t>(y, x)) continue;
      const double ux = g.gx.at<float>(y, x), uy = g.gy.at<float>(y, x);
      const double m = std::hypot(ux, uy);
      if (m <= kEdgeSigmas * g.sigma) continue;
      const double w = std::min(m, cap);
      for (double r = r_low; r <= r_high + 1e-9; r += kHoughStepPx) {
        for (int sign : {-1, 1}) {
          const double vx = x + sign * r * ux / m, vy = y + sign * r * uy / m;
          const int ix = int(std::lround(vx)), iy = int(std::lround(vy));
          if (ix < 0 || iy < 0 || ix >= acc.cols || iy >= acc.rows) continue;
          acc.at<double>(iy, ix) += w;
        }
      }
    }
  }
  cv::GaussianBlur(acc, acc, cv::Size(5, 5), 1.0);
  double best = 0;
  for (int y = 0; y < acc.rows; ++y) {
    for (int x = 0; x < acc.cols; ++x) {
      if (std::hypot(x - ref.x(), y - ref.y()) > max_shift) continue;
      if (acc.at<double>(y, x) > best) {
        best = acc.at<double>(y, x);
        *centre = Eigen::Vector2d(x, y);
      }
    }
  }
  if (!(best > 0)) return false;
  // Radius: the radial derivative summed over the rays, as a function of the radius.
  double best_r = 0, best_sum = 0;
  for (double r = r_low; r <= r_high + 1e-9; r += kHoughStepPx) {
    double sum = 0;
    for (int i = 0; i < kLimbRays; ++i) {
      const double t = 2 * M_PI * i / kLimbRays;
      double gx = 0, gy = 0;
      if (Sample(g, centre->x() + r * std::cos(t), centre->y() + r * std::sin(t), &gx, &gy)) {
        sum += std::abs(gx * std::cos(t) + gy * std::sin(t));
      }
    }
    if (sum > best_sum) {
      best_sum = sum;
      best_r = r;
    }
  }
  *radius = best_r;
  return best_r > 0;
}

struct Edge {
  Eigen::Vector2d p;
  double w;
  int ray;
};

// Per ray from `c`, the sub-pixel peak of |radial derivative| within the band about `r`.
std::vector<Edge> RayEdges(const Gradient& g, const Eigen::Vector2d& c, double r) {
  std::vector<Edge> edges;
  const int n = int(std::lround(2 * kLimbBandPx / kRayStepPx)) + 1;
  std::vector<double> s(n);
  for (int i = 0; i < kLimbRays; ++i) {
    const double t = 2 * M_PI * (i + 0.5) / kLimbRays;
    const Eigen::Vector2d u(std::cos(t), std::sin(t));
    // Samples off the known pixels (the template's border, the rod, the plate) are left out; the
    // peak and both its neighbours must be known.
    std::vector<bool> known(n);
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector2d p = c + (r - kLimbBandPx + j * kRayStepPx) * u;
      double gx = 0, gy = 0;
      known[j] = Sample(g, p.x(), p.y(), &gx, &gy);
      s[j] = known[j] ? std::abs(gx * u.x() + gy * u.y()) : 0.0;
    }
    const int j = int(std::max_element(s.begin(), s.end()) - s.begin());
    if (j == 0 || j == n - 1 || !known[j - 1] || !known[j] || !known[j + 1] ||
        s[j] < kEdgeSigmas * g.sigma) {
      continue;
    }
    const double den = s[j - 1] - 2 * s[j] + s[j + 1];
    const double d = den < 0 ? 0.5 * (s[j - 1] - s[j + 1]) / den : 0.0;
    const double rr = r - kLimbBandPx + (j + d) * kRayStepPx;
    edges.push_back({c + rr * u, s[j] * s[j], i});
  }
  return edges;
}

// Weighted Gauss-Newton circle fit of the free parameters among (column, row, radius); on
// return `c`, `r` and the covariance of (c, r) (zero for fixed ones).
bool FitCircle(const std::vector<Edge>& e, const std::array<bool, 3>& free, Eigen::Vector2d* c,
               double* r, Eigen::Matrix3d* cov) {
  std::vector<int> idx;
  for (int k = 0; k < 3; ++k) {
    if (free[k]) idx.push_back(k);
  }
  const int p = int(idx.size());
  if (int(e.size()) <= p + 2) return false;
  Eigen::MatrixXd normal(p, p);
  for (int it = 0; it < kGaussNewtonIterations; ++it) {
    normal.setZero();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(p);
    for (const Edge& x : e) {
      const Eigen::Vector2d d = x.p - *c;
      const double dist = d.norm();
      if (!(dist > 0)) continue;
      const double full[3] = {-d.x() / dist, -d.y() / dist, -1.0};
      Eigen::VectorXd j(p);
      for (int k = 0; k < p; ++k) j(k) = full[idx[k]];
      const double res = dist - *r;
      normal += x.w * j * j.transpose();
      rhs -= x.w * res * j;
    }
    const Eigen::VectorXd step = normal.ldlt().solve(rhs);
    if (!step.allFinite()) return false;
    for (int k = 0; k < p; ++k) {
      if (idx[k] == 2) {
        *r += step(k);
      } else {
        (*c)(idx[k]) += step(k);
      }
    }
    if (step.norm() < 1e-7) break;
  }
  double chi2 = 0;
  for (const Edge& x : e) {
    const double res = (x.p - *c).norm() - *r;
    chi2 += x.w * res * res;
  }
  const Eigen::MatrixXd inv = normal.inverse() * (chi2 / double(int(e.size()) - p));
  cov->setZero();
  for (int k = 0; k < p; ++k) {
    for (int l = 0; l < p; ++l) (*cov)(idx[k], idx[l]) = inv(k, l);
  }
  return inv.allFinite();
}

// The edges on the circle (c, r): within kLimbOutlierSigmas robust sigmas of the residuals'
// median (and at least kLimbOutlierFloorPx); the others are a highlight or a reflection's
// boundary caught in the band, not the outline.
std::vector<Edge> Inliers(const std::vector<Edge>& edges, const Eigen::Vector2d& c, double r) {
  if (edges.empty()) return {};
  std::vector<double> d;
  for (const Edge& e : edges) d.push_back((e.p - c).norm() - r);
  const double mid = MedianOf(d);
  std::vector<double> dev;
  for (double x : d) dev.push_back(std::abs(x - mid));
  const double cut = std::max(kLimbOutlierFloorPx, kLimbOutlierSigmas * 1.4826 * MedianOf(dev));
  std::vector<Edge> kept;
  for (size_t i = 0; i < edges.size(); ++i) {
    if (std::abs(d[i] - mid) <= cut) kept.push_back(edges[i]);
  }
  return kept;
}

// The column from mirrored pairs of rays (theta and pi - theta about the vertical through `from`,
// the centre's row known or fitted): the two ends of a chord are equally far from the centre
// whatever both edges' common radial bias (the rim reflecting the backdrop places every edge a
// fraction of a pixel inside the outline, but mirrored rays alike), so the centre lies on the
// chord's perpendicular bisector, here met at the centre's row; relative to `from`,
//   column = (x_a + x_b) / 2 + (y_a^2 - y_b^2) / (2 (x_a - x_b)).
// The chord's midpoint alone (the second term dropped) is right only for rays cast from the
// centre itself: cast from a point delta beside it, mirrored rays meet the outline at different
// heights and the midpoint lies delta sin^2(theta) toward that point, so the rays near the top
// only repeat the point they were cast from (cast from the circle fit's centre, two passes left
// about half of that fit's error in the column; the full bisector halves it again on POV-Ray
// front_point, see povray.targets.front_point).
// A radial error e of either edge moves the bisector by e / (2 cos theta): each pair weighs
// cos^2 theta over the sum of its edges' variances (inverse squared contrasts). A pair without
// both edges (the rod's side, one dark side) does not pull the column. False with fewer than
// kLimbMinPairs pairs.
bool PairedColumn(const std::vector<Edge>& edges, const Eigen::Vector2d& from, double* col,
                  double* err, int* pairs) {
  std::vector<const Edge*> by_ray(kLimbRays, nullptr);
  for (const Edge& e : edges) by_ray[e.ray] = &e;
  double sw = 0, swx = 0, swxx = 0;
  int n = 0;
  for (int i = 0; i < kLimbRays; ++i) {
    const int m = ((kLimbRays / 2 - 1 - i) % kLimbRays + kLimbRays) % kLimbRays;
    if (m <= i || !by_ray[i] || !by_ray[m]) continue;  // each pair once
    const Eigen::Vector2d a = by_ray[i]->p - from, b = by_ray[m]->p - from;
    const double chord = a.x() - b.x();
    if (!(std::abs(chord) > 0)) continue;
    const double x = 0.5 * (a.x() + b.x()) + 0.5 * (a.y() * a.y() - b.y() * b.y()) / chord;
    const double cos2 = chord * chord / ((a.norm() + b.norm()) * (a.norm() + b.norm()));
    const double w = cos2 / (1.0 / by_ray[i]->w + 1.0 / by_ray[m]->w);
    sw += w;
    swx += w * x;
    swxx += w * x * x;
    ++n;
  }
  if (n < kLimbMinPairs || !(sw > 0)) return false;
  const double mean = swx / sw;
  *col = from.x() + mean;
  // Standard error of a weighted mean from the weighted scatter of the pairs' columns.
  const double var = std::max(0.0, swxx / sw - mean * mean);
  *err = std::sqrt(var / double(n - 1));
  *pairs = n;
  return true;
}

// The column from mirrored pairs of envelope rays (PairedColumn), cast again from the centre
// moved to it: two passes from `c`. Updates *col and *col_err where the pairs decide; returns
// the last pass's pair count (0 when none did).
int PairedColumnPasses(const Gradient& g, const Eigen::Vector2d& c, double r, double* col,
                       double* col_err) {
  int pairs = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::Vector2d from(*col, c.y());
    double x = 0, xe = 0;
    int n = 0;
    if (!PairedColumn(Inliers(RayEdges(g, from, r), from, r), from, &x, &xe, &n)) break;
    *col = x;
    *col_err = xe;
    pairs = n;
  }
  return pairs;
}

// One side of the outline only (the far side dark under one-sided light): no pairs cancel
// the edges' inward shift, and with the radius held the column moves toward the seen side
// by that shift (POV-Ray one-sided light: 0.09-0.19 px, stated as 0.04). The same edges
// fitted with the radius free take the shift as uniform around the rim and overshoot
// where it is not (-0.21 px there). The two bracket the column: their midpoint, with half
// their difference as a systematic uncertainty.
void BracketOneSidedColumn(const std::vector<Edge>& edges, bool row_fixed, double r,
                           Eigen::Vector2d* c, double* model_err, double* col_err) {
  Eigen::Vector2d c_free = *c;
  double r_free = r;
  Eigen::Matrix3d cov_free;
  if (FitCircle(edges, {true, !row_fixed, true}, &c_free, &r_free, &cov_free) &&
      std::abs(r_free - r) <= kKnownRadiusSlackPx) {
    const double half = 0.5 * (c_free.x() - c->x());
    c->x() += half;
    *model_err = std::abs(half);
    *col_err = std::hypot(*col_err, half);
  }
}

}  // namespace

LimbFit FitLimb(const Appearance& a, const LimbFitOptions& o) {
  LimbFit out;
  if (!a.valid() || !(o.radius_px > 0)) return out;
  const Gradient g = GradientOf(a);
  const Eigen::Vector2d ref(a.half, a.half);
  const bool row_fixed = std::isfinite(o.row);
  const std::array<bool, 3> free{true, !row_fixed, o.fit_radius};
  const double r_low = o.fit_radius ? kRadiusLow * o.radius_px : o.radius_px - kKnownRadiusSlackPx;
  const double r_high = o.fit_radius ? kRadiusHigh * o.radius_px : o.radius_px + kKnownRadiusSlackPx;
  Eigen::Vector2d c = ref;
  double r = o.radius_px;
  // With the row known, the search is about the centre's row: the row is not part of the
  // shift the reference may be off by (a bouncing sphere's template, framed on its lowest
  // frames, can sit 4 px above its centre; the column is still within max_shift_px).
  const Eigen::Vector2d start = row_fixed ? Eigen::Vector2d(ref.x(), ref.y() + o.row) : ref;
  if (!HoughCentre(g, r_low, r_high, start, o.max_shift_px, &c, &r)) return out;
  if (!o.fit_radius) r = o.radius_px;
  if (row_fixed) c.y() = ref.y() + o.row;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  std::vector<Edge> edges;
  for (int pass = 0; pass < kOuterPasses; ++pass) {
    const std::vector<Edge> rays = RayEdges(g, c, r);
    Eigen::Vector2d c_fit = c;
    double r_fit = r;
    edges = rays;
    if (!FitCircle(edges, free, &c_fit, &r_fit, &cov)) return out;
    edges = Inliers(rays, c_fit, r_fit);
    if (!FitCircle(edges, free, &c_fit, &r_fit, &cov)) return out;
    c = c_fit;
    r = r_fit;
  }
  int left = 0, right = 0;
  for (const Edge& e : edges) (e.p.x() < c.x() ? left : right) += 1;
  const bool both_sides = left >= kLimbMinRays / 4 && right >= kLimbMinRays / 4;
  if (int(edges.size()) < kLimbMinRays || (!both_sides && !row_fixed && !o.one_side_ok) ||
      (row_fixed ? std::abs(c.x() - ref.x()) : (c - ref).norm()) > o.max_shift_px) {
    return out;
  }
  double col = c.x(), col_err = std::sqrt(cov(0, 0));
  const int pairs = PairedColumnPasses(g, c, r, &col, &col_err);
  if (pairs >= kLimbMinPairs) {
    // The pairs and the circle fit answer the same question from different assumptions (equal
    // radial bias on mirrored rays, or every edge on the circle): half their difference is a
    // systematic uncertainty the pairs' scatter does not show.
    out.col_scatter_err = col_err;
    out.col_model_err = 0.5 * std::abs(col - c.x());
    col_err = std::hypot(col_err, out.col_model_err);
    c.x() = col;
  } else {
    out.col_scatter_err = col_err;
  }
  if (pairs < kLimbMinPairs && !o.fit_radius) {
    BracketOneSidedColumn(edges, row_fixed, r, &c, &out.col_model_err, &col_err);
  }
  out.ok = true;
  out.centre = c - ref;
  out.pairs = pairs;
  out.radius_px = r;
  out.centre_err = Eigen::Vector2d(col_err, std::sqrt(cov(1, 1)));
  out.radius_err = std::sqrt(cov(2, 2));
  out.rays = int(edges.size());
  return out;
}

}  // namespace dimer::tracking
