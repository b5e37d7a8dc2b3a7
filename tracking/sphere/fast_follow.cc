#include "tracking/sphere/fast_follow.h"

#include <opencv2/imgproc.hpp>

#include <Eigen/Cholesky>
#include <array>
#include <cmath>
#include <vector>

#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// The Lanczos kernel's half-width (a = 4: 8 taps, OpenCV's INTER_LANCZOS4).
constexpr int kLanczosA = 4;
using Taps = std::array<float, 2 * kLanczosA>;

// Weights of the taps at offsets -3..4 from the whole pixel below a sample at fraction f of a
// pixel past it: sinc(t) sinc(t / a), normalised to sum to 1 (a flat image stays flat).
Taps LanczosTaps(double f) {
  Taps w{};
  if (f < 1e-7) {
    w[kLanczosA - 1] = 1;
    return w;
  }
  double sum = 0;
  std::array<double, 2 * kLanczosA> d{};
  for (int i = 0; i < 2 * kLanczosA; ++i) {
    const double t = M_PI * (i - (kLanczosA - 1) - f);
    d[i] = std::sin(t) * std::sin(t / kLanczosA) / (t * t);
    sum += d[i];
  }
  for (int i = 0; i < 2 * kLanczosA; ++i) w[i] = float(d[i] / sum);
  return w;
}

// J(x) = patch(x + origin + e) on a size x size grid: the whole part of e moves the origin,
// its fraction is interpolated, rows first, then columns. The caller keeps the taps inside.
void ShiftPatch(const cv::Mat& patch, int origin, const Eigen::Vector2d& e, int size,
                cv::Mat* out, cv::Mat* rows) {
  const int ix = int(std::floor(e.x())), iy = int(std::floor(e.y()));
  const Taps wx = LanczosTaps(e.x() - ix), wy = LanczosTaps(e.y() - iy);
  const int x0 = origin + ix - (kLanczosA - 1), y0 = origin + iy - (kLanczosA - 1);
  const int nrows = size + 2 * kLanczosA - 1;
  rows->create(nrows, size, CV_32F);
  for (int r = 0; r < nrows; ++r) {
    const float* src = patch.ptr<float>(y0 + r) + x0;
    float* dst = rows->ptr<float>(r);
    for (int x = 0; x < size; ++x) {
      float s = 0;
      for (int k = 0; k < 2 * kLanczosA; ++k) s += wx[k] * src[x + k];
      dst[x] = s;
    }
  }
  out->create(size, size, CV_32F);
  for (int y = 0; y < size; ++y) {
    float* dst = out->ptr<float>(y);
    for (int x = 0; x < size; ++x) dst[x] = 0;
    for (int k = 0; k < 2 * kLanczosA; ++k) {
      const float* src = rows->ptr<float>(y + k);
      const float w = wy[k];
      for (int x = 0; x < size; ++x) dst[x] += w * src[x];
    }
  }
}

// The normal equations of one solve: H = sum_M phi phi^T, b = sum_M phi J, sum_M J^2, with
// phi = (A_k, 1, dA_k/dx, dA_k/dy) (A_k with its border, gradients by central differences) and
// J(x) = patch(x + at) over the mask.
struct NormalEquations {
  Eigen::Matrix4d h = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  double jj = 0;
};
NormalEquations Sums(const cv::Mat& shifted, const cv::Mat& mask, const cv::Mat& patch,
                     const cv::Point& at) {
  // Each row's 15 sums in float lanes (the compiler's vectors; the mask a 0/1 factor, not a
  // branch), added into double per row: the order is fixed, so is every bit of the result.
  constexpr int kLanes = 8, kSums = 15;
  NormalEquations e;
  std::array<double, kSums> total{};
  std::vector<float> m(size_t(mask.cols));
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* mk = mask.ptr<uint8_t>(y);
    for (int x = 0; x < mask.cols; ++x) m[size_t(x)] = mk[x] ? 1.0f : 0.0f;
    const float* up = shifted.ptr<float>(y) + 1;
    const float* a = shifted.ptr<float>(y + 1) + 1;
    const float* down = shifted.ptr<float>(y + 2) + 1;
    const float* j = patch.ptr<float>(y + at.y) + at.x;
    float acc[kSums][kLanes] = {};
    int x = 0;
    for (; x + kLanes <= mask.cols; x += kLanes) {
      for (int l = 0; l < kLanes; ++l) {
        const int i = x + l;
        const float w = m[size_t(i)], av = a[i], jv = j[i];
        const float gx = 0.5f * (a[i + 1] - a[i - 1]), gy = 0.5f * (down[i] - up[i]);
        const float wa = w * av, wgx = w * gx, wgy = w * gy, wj = w * jv;
        acc[0][l] += wa * av, acc[1][l] += wa, acc[2][l] += wa * gx, acc[3][l] += wa * gy;
        acc[4][l] += w, acc[5][l] += wgx, acc[6][l] += wgy;
        acc[7][l] += wgx * gx, acc[8][l] += wgx * gy, acc[9][l] += wgy * gy;
        acc[10][l] += wj * av, acc[11][l] += wj, acc[12][l] += wj * gx, acc[13][l] += wj * gy;
        acc[14][l] += wj * jv;
      }
    }
    for (; x < mask.cols; ++x) {  // the row's last pixels, into lane 0
      const float w = m[size_t(x)], av = a[x], jv = j[x];
      const float gx = 0.5f * (a[x + 1] - a[x - 1]), gy = 0.5f * (down[x] - up[x]);
      const float v[kSums] = {av * av, av, av * gx, av * gy, 1, gx, gy, gx * gx, gx * gy,
                              gy * gy, jv * av, jv, jv * gx, jv * gy, jv * jv};
      for (int q = 0; q < kSums; ++q) acc[q][0] += w * v[q];
    }
    for (int q = 0; q < kSums; ++q) {
      double row = 0;
      for (int l = 0; l < kLanes; ++l) row += acc[q][l];
      total[size_t(q)] += row;
    }
  }
  const auto& t = total;
  e.h << t[0], t[1], t[2], t[3],  //
      t[1], t[4], t[5], t[6],     //
      t[2], t[5], t[7], t[8],     //
      t[3], t[6], t[8], t[9];
  e.b << t[10], t[11], t[12], t[13];
  e.jj = t[14];
  return e;
}

// The correlation coefficient of J with A_k over the mask, from the sums (ECC's criterion).
double Correlation(const NormalEquations& e) {
  const double n = e.h(1, 1);
  const double cov = e.b(0) - e.h(0, 1) * e.b(1) / n;
  const double var_a = e.h(0, 0) - e.h(0, 1) * e.h(0, 1) / n;
  const double var_j = e.jj - e.b(1) * e.b(1) / n;
  if (!(n > 0 && var_a > 0 && var_j > 0)) return 0;
  return cov / std::sqrt(var_a * var_j);
}

// The frame's pixels the quick step can reach about whole pixel g, smoothed like the
// appearance (ECC's residual run's Gaussian); empty where they leave the frame.
cv::Mat SmoothedPatch(const cv::Mat& frame, const cv::Point& g, int half) {
  const int margin = kFollowPatchMarginPx;
  const int side = 2 * (half + margin) + 1;
  const cv::Rect r(g.x - half - margin, g.y - half - margin, side, side);
  if (r.x < 0 || r.y < 0 || r.x + r.width > frame.cols || r.y + r.height > frame.rows) return {};
  cv::Mat patch;
  frame(r).convertTo(patch, CV_32F);
  cv::GaussianBlur(patch, patch, cv::Size(kFollowGaussSize, kFollowGaussSize), 0, 0);
  return patch;
}

// The shift grid's point nearest `e` (px): its whole pixels and its step (kx, ky) in [-K/2, K/2).
struct GridPoint {
  cv::Point whole, step;
  Eigen::Vector2d at(int k) const {
    return {whole.x + double(step.x) / k, whole.y + double(step.y) / k};
  }
};
GridPoint Nearest(const Eigen::Vector2d& e, int k) {
  auto split = [k](double v, int* whole, int* step) {
    const long q = std::lround(v * k) + k / 2;
    *whole = int(q >= 0 ? q / k : -((-q + k - 1) / k));
    *step = int(q - long(*whole) * k) - k / 2;
  };
  GridPoint p;
  split(e.x(), &p.whole.x, &p.step.x);
  split(e.y(), &p.whole.y, &p.step.y);
  return p;
}

// The quick step's answer's standard deviation: RegistrationSigma on the frame's patch about the
// whole pixel nearest it (the quick step's patch held it, so it is inside the frame).
Eigen::Vector2d QuickSigma(const cv::Mat& frame, const Appearance& a, const cv::Mat& mask,
                           const Eigen::Vector2d& at) {
  const cv::Point g(int(std::lround(at.x())), int(std::lround(at.y())));
  const int size = 2 * a.half + 1;
  cv::Mat patch;
  frame(cv::Rect(g.x - a.half, g.y - a.half, size, size)).convertTo(patch, CV_32F);
  return RegistrationSigma(patch, a.image, mask, Eigen::Vector2d(g.x - at.x(), g.y - at.y()),
                           kFollowGaussSize);
}

}  // namespace

FollowModel PrepareFollow(const Appearance& a, int shifts_per_px) {
  FollowModel m;
  if (!a.valid() || shifts_per_px < 1) return m;
  m.half = a.half;
  m.shifts_per_px = shifts_per_px;
  const int k = shifts_per_px, size = 2 * a.half + 1;
  cv::Mat smooth, padded;
  cv::GaussianBlur(a.image, smooth, cv::Size(kFollowGaussSize, kFollowGaussSize), 0, 0);
  // Beyond the appearance its edge repeated (as ECC's Lanczos shift does): the taps reach 4 px
  // past the border pixel.
  constexpr int kPad = kLanczosA + 1;
  cv::copyMakeBorder(smooth, padded, kPad, kPad, kPad, kPad, cv::BORDER_REPLICATE);
  cv::Mat rows;
  for (int ky = -k / 2; ky < k - k / 2; ++ky) {
    for (int kx = -k / 2; kx < k - k / 2; ++kx) {
      // A_k(x) = A(x - step): sampled at x - step, x from -1 (the border) to size.
      cv::Mat out;
      ShiftPatch(padded, kPad - 1, Eigen::Vector2d(-double(kx) / k, -double(ky) / k), size + 2,
                 &out, &rows);
      m.shifted.push_back(out);
    }
  }
  return m;
}

QuickFollow FollowQuickly(const cv::Mat& frame, const FollowModel& m, const cv::Mat& mask,
                          const Eigen::Vector2d& guess, const FollowStop& stop) {
  QuickFollow out;
  out.position = guess;
  if (!m.valid()) return out;
  const int k = m.shifts_per_px;
  const cv::Point g(int(std::lround(guess.x())), int(std::lround(guess.y())));
  const cv::Mat patch = SmoothedPatch(frame, g, m.half);
  if (patch.empty()) return out;
  // The pixels the smoothing does not carry anything cut into (a bright rod or plate beside the
  // mask's edge moved the answer 0.03 px): the mask eroded by the Gaussian's reach, as ECC
  // erodes its input mask.
  cv::Mat inner;
  cv::erode(mask, inner, cv::getStructuringElement(cv::MORPH_RECT,
                                                   {kFollowGaussSize, kFollowGaussSize}));
  Eigen::Vector2d e(guess.x() - g.x, guess.y() - g.y);  // the estimate from whole pixel g
  bool converged = false;
  while (out.iterations < stop.max_iterations && !converged) {
    // The frame is read up to kFollowReachPx from g (and the smoothing's pixel past it).
    if (e.cwiseAbs().maxCoeff() > kFollowReachPx) return out;  // wandered off: ECC decides
    const GridPoint p = Nearest(e, k);
    const cv::Mat& a_k = m.shifted[size_t((p.step.y + k / 2) * k + p.step.x + k / 2)];
    const NormalEquations ne =
        Sums(a_k, inner, patch, p.whole + cv::Point(kFollowPatchMarginPx, kFollowPatchMarginPx));
    const Eigen::LDLT<Eigen::Matrix4d> solve(ne.h);
    if (ne.h(1, 1) < 8 || solve.info() != Eigen::Success) return out;
    const Eigen::Vector4d theta = solve.solve(ne.b);
    out.gain = theta(0);
    out.correlation = Correlation(ne);
    if (!(out.gain > 0) || !theta.allFinite()) return out;  // no likeness of the sphere
    const Eigen::Vector2d remainder = -theta.tail<2>() / out.gain;
    e = p.at(k) + remainder;
    ++out.iterations;
    // Within the grid point's cell, or on the border two cells share (else it would swing).
    converged = remainder.cwiseAbs().maxCoeff() <= kFollowCellFraction / k;
  }
  out.position = Eigen::Vector2d(g.x + e.x(), g.y + e.y());
  out.ok = converged && (out.position - guess).norm() <= kFollowMaxMovePx &&
           out.correlation >= stop.min_correlation;
  return out;
}

std::optional<Located> FollowOnlyQuickly(const cv::Mat& frame, const Appearance& a,
                                         const FollowModel& m, const Eigen::Vector2d& guess,
                                         const MaskContext& ctx, const FollowStop& stop,
                                         int search_px, bool state_sigma) {
  if (!m.valid() || stop.max_iterations <= 0) return std::nullopt;
  Located start;
  start.ok = true;
  start.position = guess;
  if (search_px > 0) start = SearchAppearance(frame, a, guess, search_px, ctx);
  // A sphere at the frame's edge is left to LocateAppearance, which cuts the mask there.
  if (!start.ok || start.at_edge) return std::nullopt;
  const cv::Mat mask = FrameMask(a, start.position, ctx);
  const int size = 2 * a.half + 1;
  if (cv::countNonZero(mask) < kTemplateMinMaskedFraction * size * size) return std::nullopt;
  const QuickFollow q = FollowQuickly(frame, m, mask, start.position, stop);
  if (!q.ok) return std::nullopt;
  Located l;
  l.ok = true;
  l.position = q.position;
  l.refined = q.correlation;
  l.score = search_px > 0 ? start.score : q.correlation;  // as LocateAppearance's
  if (state_sigma) l.sigma = QuickSigma(frame, a, mask, q.position);
  return l;
}

Located FollowAppearance(const cv::Mat& frame, const Appearance& a, const FollowModel& m,
                         const Eigen::Vector2d& guess, const MaskContext& ctx,
                         const FollowStop& stop, const EccStop& ecc, int search_px,
                         bool state_sigma) {
  if (const std::optional<Located> l =
          FollowOnlyQuickly(frame, a, m, guess, ctx, stop, search_px, state_sigma)) {
    return *l;
  }
  return LocateAppearance(frame, a, guess, search_px, ctx, ecc, state_sigma);
}

}  // namespace dimer::tracking
