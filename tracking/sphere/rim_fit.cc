#include "tracking/sphere/rim_fit.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "common/disc_coverage.h"
#include "tracking/sphere/pixel_window.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// Coarse to fine: Gauss-Newton with a linear ramp edge of these widths (px) first, then the
// straight-edge pixel coverage (0). The 3 px ramp has gradient wherever a start within ~2 px sees the edge.
constexpr double kRampSchedulePx[] = {3.0, 1.5, 0.0};
// Ramp stages stop earlier (their result only starts the next), px.
constexpr double kRampConvergedPx = 1e-2;
// The exact stage stops when the centre moves less than this, px. Measured, each step is
// 0.1-0.25 of the last (linear convergence: the pixel set and the sector levels move with the
// estimate), so what is left after a step below it is < 0.35 x 5e-3 ~ 0.002 px, 25 times below
// the 0.05 px scatter target; 1e-3 cost one more pass per sphere for nothing measurable.
constexpr double kRimConvergedPx = 5e-3;
// Largest step ratio trusted to extrapolate the exact stage's steps (1 would be no limit).
constexpr double kMaxRimContraction = 0.5;
// Damping added to the level parameters' normal equations, (grey levels)^-2 scale: far below
// any sector's information (>= 3 pixels x coverage^2), so it only pins empty sectors.
constexpr double kLevelDamping = 1e-6;
// Angular sectors for the interior level a(theta): 16 sectors of ~9 px of arc, each with ~20
// ring pixels (fewer sectors: less level noise, but coarser interpolation; 12 and 24 measured
// worse at sigma = 2).
constexpr int kRimSectors = 16;
// Ring of fully covered pixels for a(theta): centre distance in [R - kLevelRingOuterPx,
// R - kLevelRingInnerPx] (a pixel is fully inside when d < R - 1/sqrt 2).
constexpr double kLevelRingInnerPx = 0.8, kLevelRingOuterPx = 3.0;
// A sector is fitted only when its ring holds at least this many usable pixels (a quarter of
// a full sector's ~20), so a sector mostly hidden by the rod or plate cannot trade its level against
// the edge position.
constexpr int kMinSectorPixels = 5;
// Sectors fitted: ring contrast at most this multiple of the lower-quartile sector's (see
// SelectSectors).
constexpr double kRimSectorContrastRatio = 2.0;
// Pixels used by Gauss-Newton: up to kEdgeBandPx beyond the straddling ones on each side, so
// the levels are pinned by fully inside and fully outside pixels of the same sector.
constexpr double kEdgeBandPx = 1.5;
// Extra window half-size beyond R for the edge band and starts off by up to kMaxMovePx, px.
constexpr double kRimWindowMarginPx = 7.0;
// A sector whose rim is less than this fraction of full scale above the background carries no
// edge information worth its noise; a fit needs at least this many edge pixels.
constexpr double kMinRimContrastFraction = 0.01;
constexpr int kMinEdgePixels = 40;
// The fit must stay within this of the start, px; further means a wrong blob.
constexpr double kMaxMovePx = 4.0;

using Window = PixelWindow;

bool Extract(const cv::Mat& frame, const Eigen::Vector2d& c, int half, int polarity,
             double radius, Window* w) {
  return ExtractWindow(frame, c, half, polarity, w, InsideHalf(radius, half));
}

// True where a point (offset d from the centre) may be the sphere's rim: not on the plate or
// within its guard, not in the rod corridor. One-sided: the fit is a model, not a centroid.
struct Usable {
  const RimFitInput& in;
  double centre_row;
  double R;
  double centre_col = 0;
  bool RowUsable(double dy) const {
    return !(std::isfinite(in.plate_row) && centre_row + dy + 0.5 > in.plate_row - kPlateGuardPx);
  }
  bool OffRod(double dx, double dy) const {
    if (in.rod_half_width_px > 0) {
      const double along = dx * in.rod_dir.x() + dy * in.rod_dir.y();
      const double across = std::abs(dx * in.rod_dir.y() - dy * in.rod_dir.x());
      if (along > 0 && across < in.rod_half_width_px + 1.0) return false;
    }
    if (in.other_clear_px > 0) {  // a touching other sphere
      const double ox = centre_col + dx - in.other.x(), oy = centre_row + dy - in.other.y();
      if (ox * ox + oy * oy < in.other_clear_px * in.other_clear_px) return false;
    }
    return true;
  }
  bool operator()(double dx, double dy) const { return RowUsable(dy) && OffRod(dx, dy); }
};

// Background: median of the window's border pixels that are usable (not plate, not rod).
double Background(const Window& w, const Eigen::Vector2d& c, const Usable& usable) {
  thread_local std::vector<float> ring;  // reused: no allocation per call
  ring.clear();
  const auto add = [&](int x, int y) {
    if (usable(w.col0 + x - c.x(), w.row0 + y - c.y())) ring.push_back(w.at(x, y));
  };
  for (int i = 0; i < w.size; ++i) add(i, 0), add(i, w.size - 1);  // top and bottom rows
  for (int i = 1; i + 1 < w.size; ++i) add(0, i), add(w.size - 1, i);  // side columns

  if (ring.empty()) return std::nan("");
  std::nth_element(ring.begin(), ring.begin() + ring.size() / 2, ring.end());
  return ring[ring.size() / 2];
}

// Gauss-Newton parameters: centre (2), radius, background, one interior level per sector.
constexpr int kGeomParams = 3;
constexpr int kParams = kGeomParams + 1 + kRimSectors;
using Vec = Eigen::Matrix<double, kParams, 1>;
using Mat = Eigen::Matrix<double, kParams, kParams>;

// Sector index and interpolation weight of the direction (dx, dy) (levels at sector centres).
// Directions are measured by the "diamond angle" (0..4 around the circle, piecewise rational,
// no atan2): sectors need only partition the directions consistently, not be equal in angle.
void SectorOf(double dx, double dy, int* k0, int* k1, double* f) {
  const double s = std::abs(dx) + std::abs(dy);
  double diamond = 0;
  if (s > 0) {
    if (dy >= 0) {
      diamond = dx >= 0 ? dy / s : 1 - dx / s;
    } else {
      diamond = dx < 0 ? 2 - dy / s : 3 + dx / s;
    }
  }
  // t >= -0.5, so truncating t + 1 is floor(t) + 1 (std::floor is a libm call without SSE4.1).
  const double t = diamond * (kRimSectors / 4.0) - 0.5;
  const int k = int(t + 1.0) - 1;
  *f = t - k;
  *k0 = k < 0 ? k + kRimSectors : k;
  *k1 = k + 1 < kRimSectors ? k + 1 : k + 1 - kRimSectors;
}

// Coverage of the unit pixel at offset (dx, dy) from the centre by the disc of radius R, with
// the edge taken as straight across the pixel (the tangent at the nearest edge point): the
// area of {x in the unit square: n.x <= t}, n the radial unit vector, t = R - d. Piecewise
// quadratic in t (a box projected on n), no transcendental function. The arc bulges inward of
// the tangent by at most 1/(8R) ~ 0.005 px over a pixel, the same all round: a constant
// offset of the fitted edge, not scatter.
PixelCoverage EdgeCoverage(double dx, double dy, double R) {
  PixelCoverage p;
  const double d = std::max(1e-9, std::sqrt(dx * dx + dy * dy));
  const double nx = dx / d, ny = dy / d, t = R - d;
  const double a = std::max(std::abs(nx), std::abs(ny)), b = std::min(std::abs(nx), std::abs(ny));
  const double u1 = 0.5 * (a - b), u2 = 0.5 * (a + b);
  double slope = 0;  // d area / d t
  if (t <= -u2) {
    p.area = 0;
  } else if (t >= u2) {
    p.area = 1;
  } else if (t < -u1) {
    p.area = (t + u2) * (t + u2) / (2 * a * b);
    slope = (t + u2) / (a * b);
  } else if (t <= u1) {
    p.area = 0.5 + t / a;
    slope = 1 / a;
  } else {
    p.area = 1 - (u2 - t) * (u2 - t) / (2 * a * b);
    slope = (u2 - t) / (a * b);
  }
  // t = R - |q - c|: dt/dcx = nx, dt/dcy = ny, dt/dR = 1.
  p.d_cx = slope * nx;
  p.d_cy = slope * ny;
  p.d_r = slope;
  return p;
}

// Coverage of a pixel: the straight-edge model (ramp_px = 0) or a linear radial ramp of that width, which has
// gradient over a wider band and so pulls a start that is a pixel or two off toward the edge.
PixelCoverage Cover(double col, double row, const Eigen::Vector2d& c, double R, double ramp_px) {
  if (ramp_px <= 0) return EdgeCoverage(col - c.x(), row - c.y(), R);
  const double dx = col - c.x(), dy = row - c.y(), d = std::max(1e-9, std::hypot(dx, dy));
  PixelCoverage p;
  const double t = 0.5 - (d - R) / ramp_px;
  p.area = std::clamp(t, 0.0, 1.0);
  if (t > 0 && t < 1) {
    p.d_cx = dx / d / ramp_px;
    p.d_cy = dy / d / ramp_px;
    p.d_r = 1.0 / ramp_px;
  }
  return p;
}

// Normal equations of one Gauss-Newton pass, accumulated in the structure of the Jacobian: a
// pixel's row is (g0, g1, g2, e) on the geometry and the background, dense, plus two adjacent
// sector levels (k0, k1 = k0 + 1 mod kRimSectors) with weights (h0, h1). So per pixel: the
// dense 4x4 block, each sector's diagonal and its cross terms with the dense block, and the
// coupling of the two adjacent sectors; straight-line code, assembled into the full matrix once
// per pass.
struct NormalEquations {
  std::array<double, 10> dense{};                      // lower triangle of the 4x4 block
  std::array<double, 4> dense_rhs{};
  std::array<double, kRimSectors> diag{}, rhs{}, next{};  // next[k]: sector k with k + 1
  std::array<std::array<double, 4>, kRimSectors> cross{};

  void Add(const std::array<double, 4>& g, int k0, int k1, double h0, double h1, double r) {
    int n = 0;
    for (int u = 0; u < 4; ++u) {
      dense_rhs[u] += g[u] * r;
      for (int v = 0; v <= u; ++v) dense[n++] += g[u] * g[v];
      cross[k0][u] += h0 * g[u];
      cross[k1][u] += h1 * g[u];
    }
    diag[k0] += h0 * h0;
    diag[k1] += h1 * h1;
    next[k0] += h0 * h1;
    rhs[k0] += h0 * r;
    rhs[k1] += h1 * r;
  }

  // Lower triangle of J^T J and J^T r over (cx, cy, R, background, sector levels).
  void Assemble(Mat* jtj, Vec* jtr) const {
    jtj->setZero();
    int n = 0;
    for (int u = 0; u < 4; ++u) {
      (*jtr)(u) = dense_rhs[u];
      for (int v = 0; v <= u; ++v) (*jtj)(u, v) = dense[n++];
    }
    for (int k = 0; k < kRimSectors; ++k) {
      const int row = kGeomParams + 1 + k;
      (*jtr)(row) = rhs[k];
      (*jtj)(row, row) = diag[k];
      for (int u = 0; u < 4; ++u) (*jtj)(row, u) = cross[k][u];
      const int other = kGeomParams + 1 + (k + 1) % kRimSectors;
      (*jtj)(std::max(row, other), std::min(row, other)) += next[k];
    }
  }
};

// One Gauss-Newton step on all parameters; returns the number of pixels used.
int Step(const Window& w, const Usable& usable, double ramp_px, bool fit_radius,
         const std::array<bool, kRimSectors>& valid, Vec* p, double* sum_r2,
         Eigen::Vector2d* centre_sigma) {
  const Eigen::Vector2d c((*p)(0), (*p)(1));
  const double R = (*p)(2), bg = (*p)(3);
  const double band = std::max(0.5 * ramp_px, 0.71) + kEdgeBandPx;
  thread_local NormalEquations ne;
  ne = NormalEquations();
  int used = 0;
  *sum_r2 = 0;
  // Only the annulus R +- band is visited: per row, the columns between its outer and inner
  // circles on each side (no scan of the whole window).
  const double outer = R + band, inner = std::max(0.0, R - band);
  const double outer2 = outer * outer, inner2 = inner * inner;
  auto row_ok = [&](double dy) { return usable.RowUsable(dy); };
  ForEachAnnulusPixel(w, c, inner, outer, row_ok, [&](int x, int y, double dx, double dy) {
    const double col = w.col0 + x, row = w.row0 + y;
    const double d2 = dx * dx + dy * dy;
    if (d2 > outer2 || d2 < inner2) return;
    int k0, k1;
    double f;
    SectorOf(dx, dy, &k0, &k1, &f);  // before the rod test: most left-out pixels fail here
    if (!valid[k0] || !valid[k1] || !usable.OffRod(dx, dy)) return;
    const double a = (1 - f) * (*p)(4 + k0) + f * (*p)(4 + k1);
    const PixelCoverage cov = Cover(col, row, c, R, ramp_px);
    const double r = w.at(x, y) - (bg + (a - bg) * cov.area);
    *sum_r2 += r * r;
    ne.Add({(a - bg) * cov.d_cx, (a - bg) * cov.d_cy, (a - bg) * cov.d_r, 1 - cov.area}, k0, k1,
           (1 - f) * cov.area, f * cov.area, r);
    ++used;
  });
  Mat jtj;
  Vec jtr;
  ne.Assemble(&jtj, &jtr);
  // Solved over the free parameters only: a known radius, and the sectors left out (no pixel
  // touches them, so their rows hold only the damping), would take a step of exactly 0. The
  // system shrinks from 20 to ~12 unknowns, and the factorisation with it (~cubic).
  std::array<int, kParams> free;
  int n = 0;
  for (int i = 0; i < kParams; ++i) {
    if ((i == 2 && !fit_radius) || (i > kGeomParams && !valid[i - kGeomParams - 1])) continue;
    free[n++] = i;
  }
  using SubMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kParams, kParams>;
  using SubVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kParams, 1>;
  SubMat a(n, n);  // fixed capacity: no allocation
  SubVec b(n);
  for (int u = 0; u < n; ++u) {
    b(u) = jtr(free[u]);
    for (int v = 0; v <= u; ++v) a(u, v) = jtj(free[u], free[v]);
    // Sectors hidden by the rod or the plate in this pass have no data: a tiny damping keeps
    // them (and only them, in effect) at their current level.
    if (free[u] >= kGeomParams) a(u, u) += kLevelDamping;
  }
  const auto ldlt = a.selfadjointView<Eigen::Lower>().ldlt();
  const SubVec sub = ldlt.solve(b);
  // The centre's standard deviation, s^2 (J^T J)^-1 with s^2 the residual variance: the centre
  // is free parameters 0 and 1.
  if (used > n) {
    const double s2 = *sum_r2 / (used - n);
    for (int axis = 0; axis < 2; ++axis) {
      SubVec e = SubVec::Zero(n);
      e(axis) = 1;
      (*centre_sigma)(axis) = std::sqrt(s2 * ldlt.solve(e)(axis));
    }
  }
  Vec step = Vec::Zero();
  for (int u = 0; u < n; ++u) step(free[u]) = sub(u);
  if (!step.allFinite()) return -1;
  *p += step;
  return used;
}

// Starting sector levels: the mean of the ring of fully covered pixels just inside the rim;
// NaN for sectors without data.
void SectorLevels(const Window& w, const Eigen::Vector2d& c, double R, const Usable& usable,
                  std::array<double, kRimSectors>* level) {
  std::array<double, kRimSectors> sum{};
  std::array<int, kRimSectors> n{};
  const double lo2 = std::pow(R - kLevelRingOuterPx, 2), hi2 = std::pow(R - kLevelRingInnerPx, 2);
  // Only the ring's rows, and in each the columns within its outer circle.
  const double hi = R - kLevelRingInnerPx;
  const int y0 = std::max(0, int(std::ceil(c.y() - hi)) - w.row0);
  const int y1 = std::min(w.size - 1, int(std::floor(c.y() + hi)) - w.row0);
  for (int y = y0; y <= y1; ++y) {
    const double dy = w.row0 + y - c.y();
    const double half = std::sqrt(std::max(0.0, hi2 - dy * dy));
    const int x0 = std::max(0, int(std::ceil(c.x() - half)) - w.col0);
    const int x1 = std::min(w.size - 1, int(std::floor(c.x() + half)) - w.col0);
    const double half_inner = dy * dy < lo2 ? std::sqrt(lo2 - dy * dy) : -1.0;
    for (int x = x0; x <= x1; ++x) {
      const double dx = w.col0 + x - c.x(), d2 = dx * dx + dy * dy;
      if (std::abs(dx) < half_inner) {  // inside the ring: jump to its far side
        x = std::max(x, int(std::floor(c.x() + half_inner)) - w.col0);
        continue;
      }
      if (d2 < lo2 || d2 > hi2 || !usable(dx, dy)) continue;
      int k0, k1;
      double f;
      SectorOf(dx, dy, &k0, &k1, &f);
      const int k = f < 0.5 ? k0 : k1;
      sum[k] += w.at(x, y);
      ++n[k];
    }
  }
  for (int k = 0; k < kRimSectors; ++k) {
    (*level)[k] = n[k] >= kMinSectorPixels ? sum[k] / n[k] : std::nan("");
  }
}

// Sector levels around the current estimate and which sectors are fitted. The grazing rim
// reflects the backdrop behind the sphere, the dimmest part of its image; sectors whose ring is
// much brighter (the plate reflected within a pixel of the rim) hold an unresolved sliver of
// backdrop at the very edge, which the model has no term for, and are left out. Reference: the
// lower quartile of the sector contrasts (the minimum would be a sector half hidden by the rod
// or plate, or half outside a start that is off). False when no sector has contrast.
bool SelectSectors(const Window& w, const Usable& usable, double min_contrast,
                   std::array<bool, kRimSectors>* valid, Vec* p) {
  std::array<double, kRimSectors> level;
  SectorLevels(w, p->head<2>(), (*p)(2), usable, &level);
  std::array<double, kRimSectors> contrasts;
  int n = 0;
  for (int k = 0; k < kRimSectors; ++k) {
    if (std::isfinite(level[k]) && level[k] - (*p)(3) > min_contrast) {
      contrasts[n++] = level[k] - (*p)(3);
    }
  }
  if (n == 0) return false;
  std::nth_element(contrasts.begin(), contrasts.begin() + n / 4, contrasts.begin() + n);
  const double rim = contrasts[n / 4];
  for (int k = 0; k < kRimSectors; ++k) {
    const double contrast = level[k] - (*p)(3);
    (*valid)[k] = std::isfinite(level[k]) && contrast > min_contrast &&
                  contrast <= kRimSectorContrastRatio * rim;
    (*p)(4 + k) = (*valid)[k] ? level[k] : (*p)(3);
  }
  return true;
}

}  // namespace

RimFitResult FitRim(const cv::Mat& frame, const Eigen::Vector2d& centre, double radius_px,
                    const RimFitInput& input) {
  RimFitResult out;
  const int half = int(std::ceil(radius_px + kRimWindowMarginPx));
  const double min_contrast = kMinRimContrastFraction * (frame.depth() == CV_8U ? 255.0 : 65535.0);
  thread_local Window w;
  if (!Extract(frame, centre, half, input.polarity, radius_px, &w)) return out;
  Usable usable{input, centre.y(), radius_px, centre.x()};
  Vec p = Vec::Zero();
  p.head<3>() << centre.x(), centre.y(), radius_px;
  p(3) = Background(w, centre, usable);
  if (!std::isfinite(p(3))) return out;
  std::array<bool, kRimSectors> valid;
  for (const double ramp : kRampSchedulePx) {
    if (ramp > 0 && !input.coarse_start) continue;  // a start within a few tenths of a pixel
    usable.centre_row = p(1);
    usable.centre_col = p(0);
    if (!SelectSectors(w, usable, min_contrast, &valid, &p)) return out;
    Eigen::Vector2d last_move(0, 0);
    for (int i = 0; i < kFitMaxIter; ++i) {
      usable.centre_row = p(1);
      usable.centre_col = p(0);
      const Eigen::Vector2d before = p.head<2>();
      double sum_r2 = 0;
      const int used =
          Step(w, usable, ramp, input.fit_radius, valid, &p, &sum_r2, &out.sigma_px);
      out.rms = used > 0 ? std::sqrt(sum_r2 / used) : 0.0;
      ++out.iterations;
      out.edge_pixels = used;
      if (used < kMinEdgePixels || (p.head<2>() - centre).norm() > kMaxMovePx) {
        return out;
      }
      const Eigen::Vector2d moved = p.head<2>() - before;
      if (moved.norm() < (ramp > 0 ? kRampConvergedPx : kRimConvergedPx)) break;
      if (ramp == 0 && i > 0) {
        // Linear convergence (kRimConvergedPx): the rest of the geometric series of steps,
        // with the measured ratio, is added at once (Aitken) when it is below the tolerance.
        const double ratio = std::clamp(moved.dot(last_move) / last_move.squaredNorm(), 0.0,
                                        kMaxRimContraction);
        const double tail = ratio / (1.0 - ratio);
        if (moved.norm() * tail < kRimConvergedPx) {
          p.head<2>() += tail * moved;
          break;
        }
      }
      last_move = moved;
    }
  }
  out.ok = true;
  out.centre = p.head<2>();
  out.radius_px = p(2);
  return out;
}

}  // namespace dimer::tracking
