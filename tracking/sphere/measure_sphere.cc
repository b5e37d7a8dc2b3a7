#include "tracking/sphere/measure_sphere.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "common/error.h"
#include "common/disc_coverage.h"
#include "tracking/sphere/pixel_window.h"
#include "tracking/sphere/rim_fit.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// A sphere must differ from the background by at least this fraction of full scale.
constexpr double kMinContrastFraction = 0.03;
// Fraction of the radius inside which the sphere level is first taken (median).
constexpr double kInnerLevelRadiusR = 0.5;
// Second level estimate for non-uniform spheres (BodyLevel): a low quantile, so the dim parts
// of the body weigh 1 too, but not the minimum (noise, the small dark reflection of the lens).
constexpr double kBodyLevelRadiusR = 0.8;
constexpr double kBodyQuantile = 0.04;
// The sphere's median level is read from every second pixel both ways (a quarter of them,
// ~110, plenty for a median); the body quantile, a low tail, from every pixel.
constexpr int kLevelStride = 2;
// Width of the linear ramp of the symmetric cuts (rod, plate), px: a smooth mask is sampled by
// the pixels with less error than a sharp one (less pixel locking).
constexpr double kMaskRampPx = 2.0;
// Body level (low quantile) and median level closer than this fraction of the contrast: a
// uniform sphere (centroid iterations); farther: a mirror (rim fit).
constexpr double kUniformLevelFraction = 0.15;
// Largest contraction ratio trusted for the centroid's extrapolation (1: no limit, unstable).
constexpr double kMaxContraction = 0.5;
// The window is re-read when the estimate leaves its centre pixel by more than this, px; the
// window circle (radius half - 1) stays inside the window up to 1 px.
constexpr double kRecentreWindowPx = 0.75;
// Rim fit with the radius unknown: starts at the first guess and this many steps outward (the
// fit reaches ~1.5 px from its start, so 2 px steps cover a guess up to ~7 px small).
constexpr int kRadiusStarts = 4;
constexpr double kRadiusStartStepPx = 2.0;
// How far an estimate can be from its window's centre pixel while iterating, px: at most
// kRecentreWindowPx per axis (sqrt 2 x 0.75 = 1.06), with a margin.
constexpr double kCoreShiftPx = 1.25;

const std::pair<Method, const char*> kMethodNames[] = {{Method::kCentroid, "centroid"},
                                                       {Method::kDiscFit, "discfit"},
                                                       {Method::kTemplate, "template"},
                                                       {Method::kAuto, "auto"}};

using Window = PixelWindow;

// The window about a sphere of `radius` px: near the frame's edge, measured while the disc is
// in the frame (pixel_window.h, kEdgeGuardPx).
bool Extract(const cv::Mat& frame, const Eigen::Vector2d& centre, int half, int polarity,
             double radius, Window* w) {
  return ExtractWindow(frame, centre, half, polarity, w, InsideHalf(radius, half));
}

// The median of a window's levels, reordering `v` (no copy per frame); 0 for an empty one.
double MedianInPlaceOrZero(std::vector<float>& v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct Levels {
  double background = 0, sphere = 0;
  bool uniform = true;  // false: `sphere` is the body level of a non-uniform sphere
};

double Quantile(std::vector<float>& v, double q) {
  if (v.empty()) return 0;
  auto it = v.begin() + std::ptrdiff_t(q * double(v.size() - 1));
  std::nth_element(v.begin(), it, v.end());
  return *it;
}

// Every stride-th pixel (both ways) of the window within `r` of c.
void DiscSample(const Window& w, const Eigen::Vector2d& c, double r, int stride,
                std::vector<float>* out) {
  out->clear();
  const double r2 = r * r;
  for (int y = 0; y < w.size; y += stride) {
    const double dy = w.row0 + y - c.y();
    if (dy * dy > r2) continue;
    for (int x = 0; x < w.size; x += stride) {
      const double dx = w.col0 + x - c.x();
      if (dx * dx + dy * dy <= r2) out->push_back(w.at(x, y));
    }
  }
}

// Background: median of the window's outer ring (the rod and plate cross it, but cover less
// than half). Sphere: median of the inner part of the disc (highlights are a small minority).
// A touching other sphere (centre `other`, NaN: none near) can cover a good part of the ring
// (a mirror's bright lower half would pass for background): the ring within `other_clear` of
// its centre is left out.
Levels MeasureLevels(const Window& w, const Eigen::Vector2d& c, double radius,
                     const Eigen::Vector2d& other, double other_clear) {
  thread_local std::vector<float> ring, inner;  // reused: no allocation per frame
  ring.clear();
  const bool near = other.allFinite();
  const auto add = [&](int x, int y) {
    if (near) {
      const double ox = w.col0 + x - other.x(), oy = w.row0 + y - other.y();
      if (ox * ox + oy * oy < other_clear * other_clear) return;
    }
    ring.push_back(w.at(x, y));
  };
  for (int i = 0; i + 1 < w.size; ++i) {
    add(i, 0);
    add(w.size - 1, i);
    add(w.size - 1 - i, w.size - 1);
    add(0, w.size - 1 - i);
  }
  DiscSample(w, c, kInnerLevelRadiusR * radius, kLevelStride, &inner);
  return {MedianInPlaceOrZero(ring), MedianInPlaceOrZero(inner)};
}

// The body level of a non-uniform sphere: a low quantile of the inner disc. On a uniform disc
// it is the interior level less ~1.3 sigma; on a mirror sphere most of the body can be much
// dimmer than its median (the rim reflects the dark backdrop, the bottom the lit plate), and
// normalising by this level makes the whole body weigh 1, so the centroid is that of the
// silhouette, not pulled toward the bright reflections. The inner disc (kBodyLevelRadiusR) stays
// inside the sphere even when the first estimate is off by several pixels.
double BodyLevel(const Window& w, const Eigen::Vector2d& c, double radius) {
  thread_local std::vector<float> body;
  DiscSample(w, c, kBodyLevelRadiusR * radius, 1, &body);
  return Quantile(body, kBodyQuantile);
}

// Point-symmetric mask about the estimate: the rod corridor beyond the inset on both sides,
// and the rows beyond the plate guard with their mirror image above.
// 0 below -ramp/2, 1 above +ramp/2, linear between.
double Ramp(double d, double width = kMaskRampPx) { return std::clamp(d / width + 0.5, 0.0, 1.0); }

// 1 - Ramp(clear - distance of (x, y) from the origin): 0 inside the circle of radius `clear`,
// 1 beyond it, without a sqrt for points clear of the ramp.
double OutsideDisc(double x, double y, double clear) {
  const double d2 = x * x + y * y, outer = clear + 0.5 * kMaskRampPx;
  if (d2 >= outer * outer) return 1.0;
  return 1.0 - Ramp(clear - std::sqrt(d2));
}

struct SymmetricMask {
  Eigen::Vector2d rod_dir{0, 0};
  double rod_half_width = 0, rod_inset = 0;
  double plate_cut = std::numeric_limits<double>::infinity();
  double plate_ramp = kMaskRampPx;  // width of the plate cut's ramp, px
  // A touching other sphere: its disc (radius other_clear about other_rel, the other centre
  // relative to the estimate) and the disc's point mirror image; other_clear 0: none near.
  Eigen::Vector2d other_rel{0, 0};
  double other_clear = 0;
  double operator()(double dx, double dy) const {
    double m = 1.0;
    if (other_clear > 0) {
      m *= OutsideDisc(dx - other_rel.x(), dy - other_rel.y(), other_clear) *
           OutsideDisc(dx + other_rel.x(), dy + other_rel.y(), other_clear);
    }
    if (rod_half_width > 0) {
      const double along = std::abs(dx * rod_dir.x() + dy * rod_dir.y());
      if (along > rod_inset - 0.5 * kMaskRampPx) {  // else short of the rod cut: Ramp is 0
        const double across = std::abs(dx * rod_dir.y() - dy * rod_dir.x());
        m *= 1.0 - Ramp(rod_half_width - across) * Ramp(along - rod_inset);
      }
    }
    if (std::isfinite(plate_cut)) {  // plate_cut is relative to the centre: dy < plate_cut
      m *= Ramp(plate_cut - dy, plate_ramp) * Ramp(plate_cut + dy, plate_ramp);
    }
    return m;
  }
};

// True when the other sphere's left-out disc (OtherClear) can reach a window about `c`: the
// window circle (radius half - 1 <= radius + kWindowMarginPx), the disc fit's band (radius +
// kFitBandPx) and a pixel of recentring are all within radius + kWindowMarginPx + 1.
double OtherClear(double radius) { return radius + kOtherSphereMarginPx; }
bool OtherIsNear(const RefineContext& ctx, double radius, const Eigen::Vector2d& c) {
  if (!ctx.other.allFinite()) return false;
  return (ctx.other - c).norm() - OtherClear(radius) - 0.5 * kMaskRampPx <
         radius + kWindowMarginPx + 1.0;
}

SymmetricMask MakeMask(const RefineContext& ctx, double radius, const Eigen::Vector2d& c,
                       double plate_ramp_px) {
  SymmetricMask m;
  if (OtherIsNear(ctx, radius, c)) {
    m.other_rel = ctx.other - c;
    m.other_clear = OtherClear(radius);
  }
  if (ctx.rod_dir.squaredNorm() > 0) {
    m.rod_dir = ctx.rod_dir.normalized();
    m.rod_half_width = kRodCorridorHalfWidthR * radius;
    m.rod_inset = radius - kRodCutInsetPx;
  }
  if (std::isfinite(ctx.plate_row)) {
    m.plate_ramp = plate_ramp_px;
    const double cut = ctx.plate_row - kPlateGuardPx - 0.5 * plate_ramp_px - c.y();
    if (cut < radius + kWindowMarginPx) m.plate_cut = cut;
  }
  return m;
}

// The centroid's plate cut (CentroidMask). A cut along pixel rows crosses the disc's edge where
// the edge runs nearly along the rows; there the mask's gradient meets edge pixels, whose
// coverage tells how much of the pixel is inside but not where, and that sampling error locked
// a resting sphere to the pixel grid (0.014 px p-p with an 8 px horizontal ramp). This cut is a
// double wedge about the vertical through the estimate instead: inside the wedge the mask falls
// with the distance from the estimate (a ramp in the sphere's interior, where every pixel is
// fully covered), and across the wedge's sides with the angle, i.e. along the edge, never
// across it. Smoothstep ramps (C1), so the sampled sums carry no kink error either.
// Angular ramp width beyond theta_p, where the plate guard row meets the window circle, rad.
constexpr double kWedgeRampRad = 0.3;
// Radial ramp inside the wedge: from kWedgeRadialRampPx short of the plate guard row to it, px.
constexpr double kWedgeRadialRampPx = 6.0;
// Least span of the angular ramp in cos(angle) (the plate cut reaching the horizontal).
constexpr double kMinWedgeCosSpan = 1e-3;

double SmoothStep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Mask about the estimate for the centroid, symmetric in both axes: the rod corridor of
// SymmetricMask and the plate's double wedge. Zero at every point of the window circle at or
// beyond the plate guard row (and at its mirror image above).
struct CentroidMask {
  SymmetricMask rod;  // rod cut only (its plate_cut stays infinite)
  double plate_dist = std::numeric_limits<double>::infinity();  // guard row - estimate row, px
  double cos_in = 1, cos_out = 1;  // wedge: cos of the angle from the vertical, full / no cut
  bool active() const {
    return rod.rod_half_width > 0 || rod.other_clear > 0 || std::isfinite(plate_dist);
  }
  double operator()(double dx, double dy) const {
    double m = rod(dx, dy);
    if (std::isfinite(plate_dist)) {
      const double r2 = dx * dx + dy * dy;
      const double inner = plate_dist - kWedgeRadialRampPx;
      if (inner <= 0 || r2 > inner * inner) {
        const double r = std::sqrt(r2);
        const double radial = SmoothStep((r - inner) / kWedgeRadialRampPx);
        const double u = r > 0 ? std::abs(dy) / r : 1.0;
        m *= 1.0 - radial * SmoothStep((u - cos_out) / (cos_in - cos_out));
      }
    }
    return m;
  }
};

CentroidMask MakeCentroidMask(const RefineContext& ctx, double radius, const Eigen::Vector2d& c,
                              double win_r) {
  CentroidMask m;
  m.rod = MakeMask(ctx, radius, c, kMaskRampPx);
  m.rod.plate_cut = std::numeric_limits<double>::infinity();
  if (std::isfinite(ctx.plate_row)) {
    const double dist = ctx.plate_row - kPlateGuardPx - c.y();
    if (dist < win_r) {
      const double theta_p = std::acos(std::clamp(dist / win_r, 0.0, 1.0));
      m.plate_dist = dist;
      m.cos_in = std::cos(theta_p);
      m.cos_out = std::cos(std::min(theta_p + kWedgeRampRad, 0.5 * std::numbers::pi));
      m.cos_out = std::min(m.cos_out, m.cos_in - kMinWedgeCosSpan);
    }
  }
  return m;
}

// Pixels of positive weight, gathered once per window: the centroid iterations revisit only
// these (the sphere, not the background around it) and need no per-pixel branching on weight.
struct ActivePixels {
  std::vector<float> x, y, w;  // column and row offsets from the window origin, weight
  size_t n = 0;                // entries in use (the vectors only grow: no refill per frame)
  void Reserve(size_t size) {
    if (x.size() < size) x.resize(size), y.resize(size), w.resize(size);
  }
};

// The core: window pixels that every mask keeps at weight 1 for any estimate within
// kCoreShiftPx of the window centre (the window is re-read before the estimate gets further).
// Their moments are summed once per window; iterations revisit only the pixels outside it.
// Moments of the pixels whose weight is not clamped (0 < w < 1, window coordinates): only
// their noise reaches the centroid.
struct UnclampedMoments {
  double n = 0, x = 0, y = 0, xx = 0, yy = 0;
  void Add(int px, int py) {
    n += 1;
    x += px;
    y += py;
    xx += double(px) * px;
    yy += double(py) * py;
  }
};

struct CentroidState {
  Window window;
  Levels levels;
  ActivePixels active;                  // positive-weight pixels outside the core
  double core_w = 0, core_x = 0, core_y = 0;  // sum of w, w x, w y over the core (window coords)
  UnclampedMoments unclamped;           // in the core (no mask reaches it)
};

// Largest distance of a pixel from the window centre at which the masks are 1 for every
// estimate within kCoreShiftPx of it (see the conditions in SymmetricMask and CircleWeight).
double CoreRadius(const RefineContext& ctx, double radius, int half,
                  const Eigen::Vector2d& window_centre) {
  const double window_row = window_centre.y();
  const double win_r = half - 1.0;
  double r = win_r - 1.0 - kCoreShiftPx;
  if (ctx.rod_dir.squaredNorm() > 0) {
    r = std::min(r, radius - kRodCutInsetPx - 0.5 * kMaskRampPx - kCoreShiftPx);
  }
  if (OtherIsNear(ctx, radius, window_centre)) {
    // The other disc is fixed; its mirror image about the estimate moves twice as far.
    r = std::min(r, (ctx.other - window_centre).norm() - OtherClear(radius) -
                        0.5 * kMaskRampPx - 2.0 * kCoreShiftPx);
  }
  if (std::isfinite(ctx.plate_row)) {
    // The plate wedge's radial ramp starts kWedgeRadialRampPx short of the guard row, measured
    // from the estimate (up to kCoreShiftPx away both in the cut's row and in the distance).
    const double dist = ctx.plate_row - kPlateGuardPx - window_row;
    r = std::min(r, dist - kWedgeRadialRampPx - 2.0 * kCoreShiftPx);
  }
  return std::max(0.0, r);
}

void ComputeWeights(CentroidState* s, double core_radius) {
  const double span = s->levels.sphere - s->levels.background;
  const float bg = float(s->levels.background), inv = float(1.0 / span);
  const Window& w = s->window;
  const int half = w.size / 2;
  const int core_r2 = int(std::floor(core_radius * core_radius));
  // Pixels beyond the window circle for every estimate within kCoreShiftPx never count.
  const double outer = half - 1.0 + kCoreShiftPx;
  const int outer_r2 = int(std::ceil(outer * outer));
  ActivePixels& a = s->active;
  a.Reserve(w.v.size());
  size_t n = 0;
  double cw = 0, cx = 0, cy = 0;
  UnclampedMoments un;
  for (int y = 0; y < w.size; ++y) {
    const float* row = &w.v[size_t(y) * w.size];
    const int dy2 = (y - half) * (y - half);
    for (int x = 0; x < w.size; ++x) {
      const float wt = std::min(1.0f, (row[x] - bg) * inv);
      if (!(wt > 0)) continue;
      const int d2 = (x - half) * (x - half) + dy2;
      if (wt < 1.0f && d2 < core_r2) un.Add(x, y);
      if (d2 < core_r2) {
        cw += wt;
        cx += double(wt) * x;
        cy += double(wt) * y;
      } else if (d2 <= outer_r2) {
        a.x[n] = float(x);
        a.y[n] = float(y);
        a.w[n] = wt;
        ++n;
      }
    }
  }
  a.n = n;
  s->unclamped = un;
  s->core_w = cw;
  s->core_x = cx;
  s->core_y = cy;
}

// Window-circle weight: 1 inside win_r - 1, a linear edge of one pixel, 0 beyond.
inline double CircleWeight(double d2, double win_r) {
  if (d2 <= (win_r - 1) * (win_r - 1)) return 1.0;
  return std::clamp(win_r - std::sqrt(d2), 0.0, 1.0);
}

// One centroid step under the symmetric mask centred at c; returns the new centre.
Eigen::Vector2d CentroidStep(const CentroidState& s, const Eigen::Vector2d& c, double win_r,
                             const CentroidMask& mask) {
  const ActivePixels& a = s.active;
  const double bx = s.window.col0 - c.x(), by = s.window.row0 - c.y();
  double sw = s.core_w, sx = bx * s.core_w + s.core_x, sy = by * s.core_w + s.core_y;
  const bool masked = mask.active();
  for (size_t i = 0; i < a.n; ++i) {
    const double dx = bx + a.x[i], dy = by + a.y[i];
    double m = CircleWeight(dx * dx + dy * dy, win_r);
    if (masked) m *= mask(dx, dy);
    const double wm = a.w[i] * m;
    sw += wm;
    sx += wm * dx;
    sy += wm * dy;
  }
  if (sw <= 0) return c;
  return c + Eigen::Vector2d(sx / sw, sy / sw);
}

// Weighted area inside the window circle and above the plate guard (no symmetric cuts). With
// a touching other sphere, pixels nearer its centre than this one's are its own: for two
// equal discs the perpendicular bisector splits their union exactly into the two discs.
double WeightedArea(const CentroidState& s, const Eigen::Vector2d& c, double win_r,
                    const RefineContext& ctx, double radius) {
  double area = s.core_w;  // the core is nearer this centre (CoreRadius)
  const ActivePixels& a = s.active;
  const double bx = s.window.col0 - c.x(), by = s.window.row0 - c.y();
  const double last_row = std::isfinite(ctx.plate_row)
                              ? ctx.plate_row - kPlateGuardPx - s.window.row0
                              : std::numeric_limits<double>::infinity();
  const bool split = OtherIsNear(ctx, radius, c);
  const Eigen::Vector2d o = split ? Eigen::Vector2d(ctx.other - c) : Eigen::Vector2d(0, 0);
  for (size_t i = 0; i < a.n; ++i) {
    if (a.y[i] > last_row) continue;
    const double dx = bx + a.x[i], dy = by + a.y[i];
    if (split && (dx - o.x()) * (dx - o.x()) + (dy - o.y()) * (dy - o.y()) < dx * dx + dy * dy) {
      continue;
    }
    area += a.w[i] * CircleWeight(dx * dx + dy * dy, win_r);
  }
  return area;
}

// Centroid iterations from *centre until converged, keeping the window centred on the
// estimate. False (status kClipped) when the window would leave the frame.
bool Iterate(const cv::Mat& frame, const RefineContext& ctx, double radius, int half,
             bool extrapolate, CentroidState* s, Eigen::Vector2d* centre,
             SphereMeasurement* out) {
  const double win_r = half - 1.0;  // stays inside the window while |c - centre| <= 1 px
  Eigen::Vector2d& c = *centre;
  Eigen::Vector2d window_centre(s->window.col0 + half, s->window.row0 + half);
  Eigen::Vector2d last_step(0, 0);
  for (int it = 0; it < kCentroidMaxIter; ++it) {
    ++out->iterations;
    const Eigen::Vector2d step =
        CentroidStep(*s, c, win_r, MakeCentroidMask(ctx, radius, c, win_r)) - c;
    const double moved = step.norm();
    // The masked centroid is a linear contraction near its fixed point (each step ~0.35 of the
    // last): extrapolate the geometric series with the measured ratio (Aitken), so two or three
    // steps reach the tolerance instead of six or seven.
    double ratio = 0;
    if (extrapolate && last_step.squaredNorm() > 0) {
      ratio = std::clamp(step.dot(last_step) / last_step.squaredNorm(), 0.0, kMaxContraction);
    }
    c += step / (1.0 - ratio);
    last_step = step;
    if ((c - window_centre).cwiseAbs().maxCoeff() > kRecentreWindowPx) {  // keep it centred
      last_step.setZero();
      if (!Extract(frame, c, half, ctx.polarity, radius, &s->window)) {
        out->status = SphereMeasurement::Status::kClipped;
        return false;
      }
      window_centre = {s->window.col0 + half, s->window.row0 + half};
      ComputeWeights(s, CoreRadius(ctx, radius, half, {s->window.col0 + half, s->window.row0 + half}));
    } else if (moved < kCentroidConvergedPx) {
      break;
    }
  }
  return true;
}

// Standard deviation of the centroid at `c` over weighted area `area`: c = sum w x / W, and a
// pixel's weight moves with its noise (sigma / span per grey level) only where it is not
// clamped, so one step's var(F_x) = (sigma / span)^2 sum_unclamped m^2 (x - c_x)^2 / W^2 with m
// the pixel's mask weight. A pixel at a clamp, unclamped half the time, has its rectified noise
// (variance 0.34) counted as 0.5: this errs high. The masks
// are point-symmetric about the estimate, so the centroid is the fixed point c = F(c): noise
// moves it by (I - dF/dc)^-1 dF, and near the plate's cut dF/dc is ~0.5 (the row's scatter
// doubles; SphereLocator.StatedUncertaintyMatchesTheScatterOverNoise, the resting sphere).
Eigen::Vector2d CentroidSigma(const CentroidState& s, const Eigen::Vector2d& c, double area,
                              double noise_sigma, const RefineContext& ctx, double radius,
                              double win_r) {
  const UnclampedMoments& u = s.unclamped;
  const double cx = c.x() - s.window.col0, cy = c.y() - s.window.row0;
  double sxx = std::max(0.0, u.xx - 2 * cx * u.x + u.n * cx * cx);
  double syy = std::max(0.0, u.yy - 2 * cy * u.y + u.n * cy * cy);
  // Outside the core, each unclamped pixel under its mask weight, as CentroidStep weighs it.
  const CentroidMask mask = MakeCentroidMask(ctx, radius, c, win_r);
  const ActivePixels& a = s.active;
  const double bx = s.window.col0 - c.x(), by = s.window.row0 - c.y();
  for (size_t i = 0; i < a.n; ++i) {
    if (!(a.w[i] < 1.0f)) continue;
    const double dx = bx + a.x[i], dy = by + a.y[i];
    double m = CircleWeight(dx * dx + dy * dy, win_r);
    if (mask.active()) m *= mask(dx, dy);
    sxx += m * m * dx * dx;
    syy += m * m * dy * dy;
  }
  const double per_level = noise_sigma / (s.levels.sphere - s.levels.background) / area;
  const auto step = [&](const Eigen::Vector2d& at) {
    return CentroidStep(s, at, win_r, MakeCentroidMask(ctx, radius, at, win_r));
  };
  // F(c) = c at the fixed point, to the iterations' tolerance (kCentroidConvergedPx, far
  // below the probe's effect), so two steps give dF/dc.
  constexpr double kProbePx = 0.05;  // well inside the masks' linear range (ramps of ~1 px)
  Eigen::Matrix2d j;
  j.col(0) = (step(c + Eigen::Vector2d(kProbePx, 0)) - c) / kProbePx;
  j.col(1) = (step(c + Eigen::Vector2d(0, kProbePx)) - c) / kProbePx;
  const Eigen::Matrix2d m = (Eigen::Matrix2d::Identity() - j).inverse();
  const Eigen::Matrix2d cov = per_level * per_level * m *
                              Eigen::Vector2d(sxx, syy).asDiagonal() * m.transpose();
  return {std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1))};
}

SphereMeasurement Centroid(const cv::Mat& frame, const Eigen::Vector2d& guess, double radius,
                           const RefineContext& ctx, CentroidState* s) {
  SphereMeasurement out;
  const int half = int(std::ceil(radius + kWindowMarginPx));
  const double win_r = half - 1.0;  // stays inside the window while |c - centre| <= 1 px
  Eigen::Vector2d c = guess;
  if (!Extract(frame, c, half, ctx.polarity, radius, &s->window)) {
    out.status = SphereMeasurement::Status::kClipped;
    return out;
  }
  const Eigen::Vector2d nan2(std::nan(""), std::nan(""));
  s->levels = MeasureLevels(s->window, c, radius, OtherIsNear(ctx, radius, c) ? ctx.other : nan2,
                            OtherClear(radius));
  const double full = frame.depth() == CV_8U ? 255.0 : 65535.0;
  if (s->levels.sphere - s->levels.background < kMinContrastFraction * full) return out;
  // A sphere whose body level (a low quantile) is far below its median is not uniform: a
  // mirror. Its centroid is not its centre (MeasureSphere ends with the rim fit, started from
  // the guess), so it is not iterated: the body-level weights at the guess only give the
  // silhouette's area (found or not) and radius.
  const double body = BodyLevel(s->window, c, radius);
  const double contrast = s->levels.sphere - s->levels.background;
  if (std::abs(body - s->levels.sphere) > kUniformLevelFraction * contrast &&
      body - s->levels.background >= kMinContrastFraction * full) {
    s->levels.sphere = body;
    s->levels.uniform = false;
    ComputeWeights(s, CoreRadius(ctx, radius, half, {s->window.col0 + half, s->window.row0 + half}));
    // From a coarse guess (acquisition: a distance-transform peak can be pixels off) the
    // body-weighted centroid, biased by the reflections but within ~2 px, is a second start
    // for the rim fit. Plain steps: these weights make the contraction irregular.
    if (!ctx.precise_guess && !Iterate(frame, ctx, radius, half, false, s, &c, &out)) return out;
  } else {
    ComputeWeights(s, CoreRadius(ctx, radius, half, {s->window.col0 + half, s->window.row0 + half}));
    if (!Iterate(frame, ctx, radius, half, true, s, &c, &out)) return out;
  }
  const double area = WeightedArea(*s, c, win_r, ctx, radius);
  out.area_fraction = area / (std::numbers::pi * radius * radius);
  out.centre = c;
  out.radius_px = std::sqrt(area / std::numbers::pi);
  if (s->levels.uniform && area > 0 && std::isfinite(ctx.noise_sigma)) {
    out.sigma_px = CentroidSigma(*s, c, area, ctx.noise_sigma, ctx, radius, win_r);
  }
  if (out.area_fraction > 0) out.quality = std::min(out.area_fraction, 1.0 / out.area_fraction);
  const bool ok = out.area_fraction > kMinAreaFraction && out.area_fraction < kMaxAreaFraction;
  out.status = ok ? SphereMeasurement::Status::kFound : SphereMeasurement::Status::kMissing;
  return out;
}

// What the fit sees of a pixel: its level for a uniform sphere, its clamped weight otherwise.
double Data(double v, const Levels& l) {
  if (l.uniform) return v;
  return std::clamp((v - l.background) / (l.sphere - l.background), 0.0, 1.0);
}

// Gauss-Newton on (cx, cy, R, background, sphere level) over the edge band.
void DiscFit(const cv::Mat& frame, const RefineContext& ctx, const Levels& start,
             SphereMeasurement* m) {
  // A non-uniform sphere is fitted through its clamped weights (its silhouette), 0 to 1.
  Eigen::Matrix<double, 5, 1> p;
  p << m->centre.x(), m->centre.y(), m->radius_px, start.uniform ? start.background : 0.0,
      start.uniform ? start.sphere : 1.0;
  const double radius_guess = m->radius_px;
  thread_local Window w;  // read once (re-read only if the fit walks off it): no allocation
  const int half = int(std::ceil(radius_guess + kFitBandPx + 2.0));
  bool have_window = false;
  Eigen::Matrix<double, 5, 5> last_jtj;
  double last_r2 = 0, last_n = 0;
  for (int it = 1; it <= kFitMaxIter; ++it) {
    const Eigen::Vector2d c(p(0), p(1));
    const Eigen::Vector2d window_centre(w.col0 + w.size / 2, w.row0 + w.size / 2);
    if (!have_window || (c - window_centre).cwiseAbs().maxCoeff() > kRecentreWindowPx) {
      if (!Extract(frame, c, half, ctx.polarity, radius_guess, &w)) {
        m->status = SphereMeasurement::Status::kClipped;
        return;
      }
      have_window = true;
    }
    const SymmetricMask mask = MakeMask(ctx, p(2), c, kMaskRampPx);
    Eigen::Matrix<double, 5, 5> jtj = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> jtr = Eigen::Matrix<double, 5, 1>::Zero();
    double sum_r2 = 0, used = 0;
    // Only the band R +- kFitBandPx: per row, the columns between its outer and inner circles.
    const double outer = p(2) + kFitBandPx, inner = std::max(0.0, p(2) - kFitBandPx);
    auto all_rows = [](double) { return true; };
    ForEachAnnulusPixel(w, c, inner, outer, all_rows, [&](int x, int y, double dx, double dy) {
      const double col = w.col0 + x, row = w.row0 + y;
      const double dist = std::sqrt(dx * dx + dy * dy);
      if (std::abs(dist - p(2)) > kFitBandPx) return;
      if (mask(dx, dy) < 1.0) return;  // rod corridor, plate: not part of the disc model
      const double span = p(4) - p(3);
      const bool outside = dist >= p(2) + kPixelHalfDiagonalPx;
      if (outside || dist <= p(2) - kPixelHalfDiagonalPx) {
        // Wholly outside or inside (most of the band; the same tests as DiscPixelCoverage):
        // the Jacobian row is a unit vector on one level, so only that level's diagonal and
        // right-hand side change.
        const int level = outside ? 3 : 4;
        const double r = Data(w.at(x, y), start) - (p(3) + span * (outside ? 0.0 : 1.0));
        jtj(level, level) += 1.0;
        jtr(level) += r;
        sum_r2 += r * r, used += 1;
        return;
      }
      const PixelCoverage cov = DiscPixelCoverage(col, row, c, p(2));
      Eigen::Matrix<double, 5, 1> j;
      j << span * cov.d_cx, span * cov.d_cy, span * cov.d_r, 1.0 - cov.area, cov.area;
      const double r = Data(w.at(x, y), start) - (p(3) + span * cov.area);
      jtj += j * j.transpose();
      jtr += j * r;
      sum_r2 += r * r, used += 1;
    });
    last_jtj = jtj;
    last_r2 = sum_r2;
    last_n = used;
    const Eigen::Matrix<double, 5, 1> step = jtj.ldlt().solve(jtr);
    if (!step.allFinite()) return;  // keep the centroid result
    p += step;
    m->iterations = it;
    if (step.head<2>().norm() < kFitConvergedPx) break;
  }
  m->centre = {p(0), p(1)};
  m->radius_px = p(2);
  // Least squares: covariance s^2 (J^T J)^-1, s^2 the residual variance (noise and whatever
  // the disc model lacks), at the last linearisation.
  if (last_n > 5) {
    const Eigen::Matrix<double, 5, 5> cov = last_jtj.inverse() * (last_r2 / (last_n - 5));
    if (cov.allFinite()) m->sigma_px = {std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1))};
  }
}

}  // namespace

std::string ToString(Method m) {
  for (const auto& [value, name] : kMethodNames) {
    if (value == m) return name;
  }
  return "?";
}

Method ParseMethod(const std::string& name, const std::string& option) {
  for (const auto& [value, n] : kMethodNames) {
    if (name == n) return value;
  }
  throw UsageError(option + " '" + name + "': expected auto, centroid, discfit or template");
}

SphereMeasurement MeasureSphere(const cv::Mat& frame, const Eigen::Vector2d& guess,
                                double radius_px, const RefineContext& context, Method method) {
  thread_local CentroidState state;  // buffers reused across calls: no allocation per frame
  SphereMeasurement m = Centroid(frame, guess, radius_px, context, &state);
  if (!m.found()) return m;
  if (!state.levels.uniform) {
    // A mirror sphere: its centroid only starts the rim fit (rim_fit.h), whatever the method.
    RimFitInput in;
    in.polarity = context.polarity;
    in.plate_row = context.plate_row;
    in.fit_radius = context.fit_radius;
    in.coarse_start = !context.precise_guess;
    if (context.rod_dir.squaredNorm() > 0) {
      in.rod_dir = context.rod_dir.normalized();
      in.rod_half_width_px = kRodCorridorHalfWidthR * radius_px;
    }
    if (context.other.allFinite()) {
      in.other = context.other;
      in.other_clear_px = OtherClear(radius_px);
    }
    // Starts: the guess, and the body-weighted centroid unless the guess is a prediction;
    // radius: known, or (acquisition) from the first guess outward, since the thresholded
    // silhouette of a mirror sphere can be a few pixels small (its rim is only ~12 grey levels
    // above the background). The smallest residual wins.
    const double r0 = !context.fit_radius                      ? radius_px
                      : std::isfinite(context.radius_start_px) ? context.radius_start_px
                                                               : m.radius_px;
    const int radius_starts = context.fit_radius ? kRadiusStarts : 1;
    RimFitResult rim;
    for (int s = 0; s < (context.precise_guess ? 1 : 2); ++s) {
      for (int k = 0; k < radius_starts; ++k) {
        const RimFitResult r =
            FitRim(frame, s == 0 ? guess : m.centre, r0 + k * kRadiusStartStepPx, in);
        if (r.ok && (!rim.ok || r.rms < rim.rms)) rim = r;
      }
    }
    if (!rim.ok) {
      m.status = SphereMeasurement::Status::kMissing;
      return m;
    }
    m.centre = rim.centre;
    m.radius_px = rim.radius_px;
    m.sigma_px = rim.sigma_px;
    m.iterations += rim.iterations;
    m.rim_fit = true;
    return m;
  }
  if (method == Method::kDiscFit) DiscFit(frame, context, state.levels, &m);
  return m;
}

}  // namespace dimer::tracking
