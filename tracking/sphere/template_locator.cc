#include "tracking/sphere/template_locator.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

#include "tracking/sphere/masked_correlation.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// Rows within this distance above the plate's top surface are left out, px: the pixel's own
// half extent, motion blur, the lit edge's anti-aliasing and the contact shadow.
constexpr double kTemplatePlateGuardPx = 1.5;
// ECC smooths both images with a Gaussian of this size first (OpenCV's default, 5): it cuts
// the noise and the interpolation error of sharp highlights without biasing the shift (both
// images are smoothed alike), and widens the basin the first run starts in.
constexpr int kEccGaussSize = 5;
// The second, residual run of a frame against a learnt appearance smooths less. The appearance
// is a mean of many frames, nearly noise-free; the frame is noisy, and the estimate that uses
// its noise best (least squares against the clean appearance, the Cramér-Rao bound of
// tracking/sphere/precision_bound.h) smooths neither. Smoothing both at 5 blurred the highlights, the
// sharpest detail and most of the information: POV-Ray steel (povray.scatter.CASE) scattered at
// 1.5-1.8x the bound; at 3 the scatter is within 1.0-1.4x of it (under-exposed 40-frame set:
// 0.175 -> 0.135 px against a bound of 0.131). At 1 the soft-box footage lost its way (scatter
// 0.15 px). Registering two appearances (TransferOffset, SymmetryAxis) keeps 5: neither is
// noisy, and what two different spheres share is their coarse structure.
constexpr int kEccFrameGaussSize = 3;
// ECC's answer is kept only if it stays this close to the correlation peak's, px (the quadratic
// peak is within ~0.3 px; further means ECC slid to a neighbouring optimum).
constexpr double kEccMaxMovePx = 1.0;
// Acquisition: the rod's direction is unknown, so a horizontal corridor on both sides of this
// half-width (units of R) is cut; the dimer's tilt stays well inside it near the sphere.
constexpr double kAcquireRodHalfWidthR = 0.45;
// Where a sphere is found pressed against the whole-frame search's bound a radius above the
// plate, it is searched for again down to its reference point's least height above the plate
// in the learning frames (Appearance::lowest_gap_px) less this margin, in radii (learning
// frames that missed the impacts by a frame). Where the reference lies below the centre (5-9 px
// on our renderer's reflect jump films with the flights' samples taken for a rest), a sphere
// touching the plate at a chunk's first frame was found 2.4-3.4 px high at the bound
// (TemplateAcquisition.FindsSpheresTouchingThePlateAtAChunksFirstFrame). Searched so on every
// acquisition, a film tracked with a guessed radius found one sphere twice
// (povray.dimer_length.underexposed's --ar passes).
constexpr double kAcquireGapMarginR = 0.1;
// The whole-frame search (FindAppearance) at half resolution first only for spheres of at least
// this radius (smaller ones are too few pixels at half size), px; the full-resolution windows
// about the coarse peaks are +-kCoarseWindowPx (a coarse peak is off by a pixel of half
// resolution).
constexpr double kCoarseSearchMinRadiusPx = 8;
constexpr int kCoarseWindowPx = 3;
// A sphere at the frame's edge: the template's pixels within this many px of the edge are left
// out besides those beyond it (ECC moves the estimate by up to kEccMaxMovePx; the edge pixel
// row itself can be a sensor's odd one).
constexpr int kEdgeMaskGuardPx = 2;

cv::Mat ToFloat(const cv::Mat& m) {
  cv::Mat f;
  m.convertTo(f, CV_32F);
  return f;
}

bool Inside(const cv::Mat& frame, const cv::Rect& r) {
  return r.x >= 0 && r.y >= 0 && r.x + r.width <= frame.cols && r.y + r.height <= frame.rows;
}

// The frame's pixels in `r`, as float; where `r` leaves the frame, its edge pixels repeated
// (they are masked out: CutAtTheFramesEdge).
cv::Mat FloatPatch(const cv::Mat& frame, const cv::Rect& r) {
  if (Inside(frame, r)) return ToFloat(frame(r));
  const cv::Rect in = r & cv::Rect(0, 0, frame.cols, frame.rows);
  cv::Mat out;
  if (in.empty()) return cv::Mat(r.size(), CV_32F, cv::Scalar(0));
  cv::copyMakeBorder(ToFloat(frame(in)), out, in.y - r.y, r.y + r.height - in.y - in.height,
                     in.x - r.x, r.x + r.width - in.x - in.width, cv::BORDER_REPLICATE);
  return out;
}

// Whether the disc of `radius` px about pixel `g` is in the frame (`view`). A sphere cut by the edge is
// not matched: on partly cut mirror-lit spheres the template's columns scattered 1.4 px, up to
// 7.6 px off, against 0.09 px while the disc was whole (DimerIdentity tests' walks).
bool DiscInside(const cv::Rect& view, const cv::Point& g, double radius) {
  const int r = int(std::ceil(radius));
  return g.x - r >= view.x && g.y - r >= view.y && g.x + r < view.x + view.width &&
         g.y + r < view.y + view.height;
}

// A sphere at the frame's edge: the template's pixels that fall beyond the frame (`view`), or
// within `guard` px of its edge (the search's and ECC's reach), when the template's reference point is
// at frame pixel `g`, are left out; what shows of the sphere is matched.
void CutAtTheFramesEdge(const cv::Rect& view, const cv::Point& g, int half, int guard,
                        cv::Mat* mask) {
  for (int y = 0; y < mask->rows; ++y) {
    const int row = g.y - half + y;
    uint8_t* m = mask->ptr<uint8_t>(y);
    if (row < view.y + guard || row >= view.y + view.height - guard) {
      std::fill(m, m + mask->cols, uint8_t(0));
      continue;
    }
    for (int x = 0; x < mask->cols; ++x) {
      const int col = g.x - half + x;
      if (col < view.x + guard || col >= view.x + view.width - guard) m[x] = 0;
    }
  }
}

// Vertex of the parabola through (-1, a), (0, b), (1, c), clamped to half a pixel.
double Vertex(double a, double b, double c) {
  const double den = a - 2 * b + c;
  if (!(den < 0)) return 0;  // not a maximum (flat or noisy): stay on the whole pixel
  return std::clamp(0.5 * (a - c) / den, -0.5, 0.5);
}

// Whole-pixel peak of a correlation map, sub-pixel by the parabola through its neighbours.
Eigen::Vector2d PeakWithVertex(const cv::Mat& res, const cv::Point& p) {
  double dx = 0, dy = 0;
  if (p.x > 0 && p.x + 1 < res.cols) {
    dx = Vertex(res.at<float>(p.y, p.x - 1), res.at<float>(p.y, p.x), res.at<float>(p.y, p.x + 1));
  }
  if (p.y > 0 && p.y + 1 < res.rows) {
    dy = Vertex(res.at<float>(p.y - 1, p.x), res.at<float>(p.y, p.x), res.at<float>(p.y + 1, p.x));
  }
  return {p.x + dx, p.y + dy};
}

}  // namespace

namespace {

// ECC's cost grows with the image's area, but only the masked pixels and a rim around them
// enter its sums: ECC smooths (kEccGaussSize: 2 px), takes gradients (1 px), samples
// bilinearly (1 px) around the masked pixels moved by the shift. Since the appearance's mask
// may cover only part of the template (the plate's reflection cut, the rod, the plate rows),
// both images are cut to the mask's bounding box widened by this margin: the same sums, on
// fewer pixels. It holds for shifts up to kEccCropMarginPx - 4 px (tests/tracking/
// register_window_test.cc: 0 px of margin is 0.025 px off, 2 px agree); ECC's answer must stay
// within kEccMaxMovePx of a start at most half a pixel off anyway.
constexpr int kEccCropMarginPx = 6;
constexpr double kEccCropMaxShiftPx = kEccCropMarginPx - 4;

// The mask's bounding box widened by kEccCropMarginPx, inside the image.
cv::Rect EccWindow(const cv::Mat& mask) {
  const cv::Rect box = cv::boundingRect(mask);
  const cv::Rect wide(box.x - kEccCropMarginPx, box.y - kEccCropMarginPx,
                      box.width + 2 * kEccCropMarginPx, box.height + 2 * kEccCropMarginPx);
  return wide & cv::Rect(0, 0, mask.cols, mask.rows);
}

// The two ECC runs of RegisterTranslation on `window` (the same rectangle of both images): the
// shift is the same as on the whole images, since both are cut alike. False: ECC did not
// converge, or went further than the window allows (*t untouched then).
bool RegisterInWindow(const cv::Mat& fixed, const cv::Mat& moving, const cv::Mat& mask,
                      const cv::Rect& window, Eigen::Vector2d* t, double* rho,
                      int residual_gauss, const EccStop& ecc) {
  const cv::TermCriteria stop(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                              ecc.max_iterations, ecc.epsilon);
  const bool whole = window == cv::Rect(0, 0, fixed.cols, fixed.rows);
  const cv::Mat fixed_w = fixed(window), moving_w = moving(window), mask_w = mask(window);
  cv::Mat warp = (cv::Mat_<float>(2, 3) << 1, 0, float(t->x()), 0, 1, float(t->y()));
  try {
    cv::findTransformECC(fixed_w, moving_w, warp, cv::MOTION_TRANSLATION, stop, mask_w,
                         kEccGaussSize);
    // ECC warps `moving` bilinearly, and its iterations settle only within a few hundredths of
    // a pixel of the optimum (bilinear interpolation blurs by an amount that depends on the
    // fractional shift). So `moving` is shifted once by ECC's answer with a Lanczos kernel
    // (nearly exact for a band-limited image) and ECC run again from zero: the residual steps
    // are small, and so is their error (on a noisy sphere the scatter falls by a third).
    const double tx = warp.at<float>(0, 2), ty = warp.at<float>(1, 2);
    if (!whole && std::max(std::abs(tx), std::abs(ty)) > kEccCropMaxShiftPx) return false;
    // The shifted window is read from the whole `moving` (the Lanczos kernel reaches 4 px).
    const cv::Mat shift =
        (cv::Mat_<double>(2, 3) << 1, 0, tx + window.x, 0, 1, ty + window.y);
    cv::Mat shifted, shifted_mask;
    cv::warpAffine(moving, shifted, shift, window.size(),
                   cv::INTER_LANCZOS4 | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
    cv::warpAffine(mask, shifted_mask, shift, window.size(),
                   cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::Mat residual = cv::Mat::eye(2, 3, CV_32F);
    const double r = cv::findTransformECC(fixed_w, shifted, residual, cv::MOTION_TRANSLATION,
                                          stop, shifted_mask, residual_gauss);
    const Eigen::Vector2d found(tx + residual.at<float>(0, 2), ty + residual.at<float>(1, 2));
    if (!found.allFinite()) return false;
    if (rho) *rho = r;
    *t = found;
  } catch (const cv::Exception&) {
    return false;
  }
  return true;
}

}  // namespace

bool RegisterTranslation(const cv::Mat& fixed, const cv::Mat& moving, const cv::Mat& mask,
                         Eigen::Vector2d* t, double* rho, int residual_gauss,
                         const EccStop& stop) {
  const cv::Rect whole(0, 0, fixed.cols, fixed.rows);
  const cv::Rect window = EccWindow(mask);
  // A start too far for the window, or an ECC run that went too far in it: the whole images.
  if (window != whole && std::max(std::abs(t->x()), std::abs(t->y())) <= 1.0 &&
      RegisterInWindow(fixed, moving, mask, window, t, rho, residual_gauss, stop)) {
    return true;
  }
  return RegisterInWindow(fixed, moving, mask, whole, t, rho, residual_gauss, stop);
}

namespace {

// The pixels of `a` about and beyond its disc's rim where the film's still background
// (Appearance::still) differs from the background the appearance learnt there: background it
// did not learn at this place. Beyond the rim the appearance holds that background itself; on
// the rim, whose blur mixes the sphere with what is behind it, it is read just beyond the rim
// on the same ray (kept where the appearance did not learn it). Inside, the sphere hides it.
void CutStillBackground(const Appearance& a, const Eigen::Vector2d& position, cv::Mat* mask) {
  const StillBackground& still = *a.still;
  const cv::Point g(int(std::lround(position.x())), int(std::lround(position.y())));
  const double inner = std::max(0.0, a.radius_px - kStillRimPx);
  const double outer = a.radius_px + kStillRimPx;
  for (int y = 0; y < mask->rows; ++y) {
    const int r = g.y + y - a.half;
    if (r < 0 || r >= still.level.rows) continue;
    uint8_t* row = mask->ptr<uint8_t>(y);
    const float* level = still.level.ptr<float>(r);
    const double dy = y - a.half;
    for (int x = 0; x < mask->cols; ++x) {
      const int c = g.x + x - a.half;
      if (!row[x] || c < 0 || c >= still.level.cols || std::isnan(level[c])) continue;
      const double dx = x - a.half;
      const double d2 = dx * dx + dy * dy;
      if (d2 <= inner * inner) continue;  // the sphere's own
      int bx = x, by = y;                 // where the appearance holds the background
      if (d2 <= outer * outer) {
        const double scale = (outer + 1.0) / std::sqrt(d2);
        bx = a.half + int(std::lround(dx * scale));
        by = a.half + int(std::lround(dy * scale));
        if (bx < 0 || by < 0 || bx >= mask->cols || by >= mask->rows ||
            !a.mask.at<uint8_t>(by, bx)) {
          continue;
        }
      }
      if (std::abs(double(level[c]) - a.image.at<float>(by, bx)) > still.spread) row[x] = 0;
    }
  }
}

}  // namespace

cv::Mat FrameMask(const Appearance& a, const Eigen::Vector2d& position, const MaskContext& ctx) {
  cv::Mat m = a.mask.clone();
  const bool rod = ctx.rod_dir.squaredNorm() > 0;
  const Eigen::Vector2d dir = rod ? Eigen::Vector2d(ctx.rod_dir.normalized()) : Eigen::Vector2d(0, 0);
  const double rod_half = kRodCorridorHalfWidthR * a.radius_px;
  const double rod_inset = a.radius_px - kRodCutInsetPx;
  const double last_row = std::isfinite(ctx.plate_row) ? ctx.plate_row - kTemplatePlateGuardPx
                                                       : std::numeric_limits<double>::infinity();
  // The other sphere's disc only when it can reach the template (touching spheres).
  const double other_r = a.radius_px + kOtherSphereMarginPx;
  const double other_r2 = other_r * other_r;
  const bool other_cut = ctx.other.allFinite() && ctx.other.norm() < other_r + 1.5 * a.half;
  for (int y = 0; y < m.rows; ++y) {
    uint8_t* row = m.ptr<uint8_t>(y);
    const double dy = y - a.half;
    if (ctx.plate_slope != 0 && std::isfinite(last_row)) {
      // A sloping plate: its rows cut column by column.
      for (int x = 0; x < m.cols; ++x) {
        if (position.y() + dy > last_row + ctx.plate_slope * (x - a.half)) row[x] = 0;
      }
    } else if (position.y() + dy > last_row) {
      std::fill(row, row + m.cols, uint8_t(0));
      continue;
    }
    if (other_cut) {
      for (int x = 0; x < m.cols; ++x) {
        const double ox = x - a.half - ctx.other.x(), oy = dy - ctx.other.y();
        if (ox * ox + oy * oy < other_r2) row[x] = 0;
      }
    }
    if (!rod) continue;
    for (int x = 0; x < m.cols; ++x) {
      const double dx = x - a.half;
      const double along = dx * dir.x() + dy * dir.y();
      const double across = std::abs(dx * dir.y() - dy * dir.x());
      if (along > rod_inset && across < rod_half) row[x] = 0;
    }
  }
  if (a.still) CutStillBackground(a, position, &m);
  return m;
}

namespace {

// TM_CCOEFF_NORMED divides by the window's spread. Where the frame is flat, as a background
// clipped at black or a lossy video's smoothed background is, that spread is 0 and OpenCV gives
// NaN or +-inf; nearly flat, values past +-1. None of them is a correlation (which lies in
// [-1, 1]): all read as -1, no match; an inf in a flat corner of H.264 or MJPEG frames would
// outscore both spheres in every frame (see FindAppearance.AFlatRegionOfTheFrameIsNoMatch).
void KeepCorrelations(cv::Mat* res) {
  constexpr double kRoundOff = 1e-3;  // float sums can pass 1 by round-off on a perfect match
  const cv::Mat valid = (*res >= -1.0 - kRoundOff) & (*res <= 1.0 + kRoundOff);  // NaN: false
  res->setTo(-1.0, ~valid);
}

}  // namespace

Eigen::Vector2d RegistrationSigma(const cv::Mat& fixed, const cv::Mat& moving, const cv::Mat& mask,
                                  const Eigen::Vector2d& t, int gauss_size) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const cv::Matx23d shift(1, 0, t.x(), 0, 1, t.y());
  cv::Mat warped, m;
  cv::warpAffine(moving, warped, shift, fixed.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  cv::warpAffine(mask, m, shift, fixed.size(), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, 0);
  // The residual of fixed ~ alpha + beta warped over the mask, on the pixels as they are: its
  // variance s^2 counts the noise and whatever of the sphere's look the appearance lacks.
  double n = 0, sw = 0, sf = 0, sww = 0, swf = 0, sff = 0;
  for (int y = 0; y < fixed.rows; ++y) {
    const uint8_t* mr = m.ptr<uint8_t>(y);
    const float* wr = warped.ptr<float>(y);
    const float* fr = fixed.ptr<float>(y);
    for (int x = 0; x < fixed.cols; ++x) {
      if (!mr[x]) continue;
      const double wv = wr[x], fv = fr[x];
      n += 1, sw += wv, sf += fv, sww += wv * wv, swf += wv * fv, sff += fv * fv;
    }
  }
  const double vw = sww - sw * sw / n, cwf = swf - sw * sf / n, vf = sff - sf * sf / n;
  if (!(n > 4) || !(vw > 0) || !(cwf != 0)) return {nan, nan};
  const double beta = cwf / vw;
  const double s2 = std::max(0.0, vf - beta * cwf) / (n - 4);
  // ECC fits the images smoothed by its Gaussian: least squares on K*F against K*A(x + t). Its
  // shift is A^-1 sum g (K n) = A^-1 sum (K g) n, with g the smoothed appearance's gradient over
  // the mask and A = sum g g^T, so cov = s^2 / beta^2 A^-1 B A^-1, B = sum (K g)(K g)^T: the
  // smoothing that steadies ECC costs the high-frequency part of the rim's information.
  cv::Mat smooth, gx, gy;
  cv::GaussianBlur(warped, smooth, cv::Size(gauss_size, gauss_size), 0, 0);
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 1, 0.5);  // central differences
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 1, 0.5);
  cv::Mat inside;
  cv::erode(m, inside, cv::Mat(), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, 0);
  gx.setTo(0, inside == 0);
  gy.setTo(0, inside == 0);
  cv::Mat hx, hy;
  cv::GaussianBlur(gx, hx, cv::Size(gauss_size, gauss_size), 0, 0, cv::BORDER_CONSTANT);
  cv::GaussianBlur(gy, hy, cv::Size(gauss_size, gauss_size), 0, 0, cv::BORDER_CONSTANT);
  Eigen::Matrix2d a, b;
  a << gx.dot(gx), gx.dot(gy), gx.dot(gy), gy.dot(gy);
  b << hx.dot(hx), hx.dot(hy), hx.dot(hy), hy.dot(hy);
  if (!(a.determinant() > 0)) return {nan, nan};
  const Eigen::Matrix2d ai = a.inverse();
  const Eigen::Matrix2d cov = s2 / (beta * beta) * ai * b * ai;
  return {std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1))};
}

namespace {

// The mask's pixels within `radius` of its centre pixel (`half`, `half`): the sphere's disc.
int DiscPixels(const cv::Mat& mask, int half, double radius) {
  int n = 0;
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = 0; x < mask.cols; ++x) {
      n += m[x] && (x - half) * (x - half) + (y - half) * (y - half) <= radius * radius;
    }
  }
  return n;
}

// LocateAppearance's first stage: the frame's mask for the template at `guess` (*mask) and, with
// search_px > 0, the whole-pixel correlation peak (out->score) refined by the parabola
// (out->position; the guess without a search). A sphere cut by the frame's edge is refused
// unless `min_in_view` > 0, and then kept where at least that fraction of its appearance's
// pixels is in view. False: nothing to refine (out says why).
bool Peak(const cv::Mat& frame, const Appearance& a, const Eigen::Vector2d& guess, int search_px,
          const MaskContext& ctx, Located* out, cv::Mat* mask, double min_in_view = 0,
          const cv::Rect* cut_view = nullptr) {
  const cv::Rect view = cut_view ? *cut_view : cv::Rect(0, 0, frame.cols, frame.rows);
  const int size = 2 * a.half + 1;
  const cv::Point g(int(std::lround(guess.x())), int(std::lround(guess.y())));
  const cv::Rect search(g.x - a.half - search_px, g.y - a.half - search_px, size + 2 * search_px,
                        size + 2 * search_px);
  const bool at_edge = (search & view) != search;
  const bool cut = at_edge && !DiscInside(view, g, a.radius_px + kEdgeMaskGuardPx + search_px);
  if (cut && !(min_in_view > 0)) {
    out->clipped = true;
    return false;
  }
  *mask = FrameMask(a, guess, ctx);
  const int whole = cut ? DiscPixels(*mask, a.half, a.radius_px) : 0;
  if (at_edge) CutAtTheFramesEdge(view, g, a.half, search_px + kEdgeMaskGuardPx, mask);
  if (cut && !(DiscPixels(*mask, a.half, a.radius_px) >= min_in_view * whole)) {
    out->clipped = true;
    return false;
  }
  if (cv::countNonZero(*mask) < kTemplateMinMaskedFraction * size * size * (cut ? 0.5 : 1.0)) {
    out->clipped = at_edge;
    return false;
  }
  out->at_edge = at_edge;
  out->position = guess;
  if (search_px > 0) {
    // Template pixels outside the mask weigh nothing in the masked correlation: the template,
    // its mask and the window are cut to the mask's bounding box (same map, fewer pixels).
    const cv::Rect box = cv::boundingRect(*mask);
    const cv::Rect window(search.x + box.x, search.y + box.y, box.width + 2 * search_px,
                          box.height + 2 * search_px);
    cv::Mat res;
    const int places = (2 * search_px + 1) * (2 * search_px + 1);
    if (places <= kDirectCorrelationMaxPlaces) {
      MaskedCorrelation(FloatPatch(frame, window), a.image(box), (*mask)(box), &res);
    } else {
      cv::matchTemplate(FloatPatch(frame, window), a.image(box), res, cv::TM_CCOEFF_NORMED,
                        (*mask)(box));
    }
    KeepCorrelations(&res);
    double best = 0;
    cv::Point at;
    cv::minMaxLoc(res, nullptr, &best, nullptr, &at);
    out->score = best;
    const Eigen::Vector2d peak = PeakWithVertex(res, at);
    out->position = {search.x + peak.x() + a.half, search.y + peak.y() + a.half};
  }
  return true;
}

}  // namespace

Located SearchAppearance(const cv::Mat& frame, const Appearance& a, const Eigen::Vector2d& guess,
                         int search_px, const MaskContext& ctx) {
  Located out;
  cv::Mat mask;
  out.ok = Peak(frame, a, guess, search_px, ctx, &out, &mask) && search_px > 0;
  return out;
}

namespace {

// LocateAppearance's second stage: ECC from Peak's answer (out->position) with its `mask` (cut
// for `guess`); `out` takes ECC's answer where it converged within kEccMaxMovePx.
Located RefineByEcc(const cv::Mat& frame, const Appearance& a, const Eigen::Vector2d& guess,
                    int search_px, const MaskContext& ctx, const EccStop& stop, bool state_sigma,
                    const cv::Mat& mask, Located out) {
  const int size = 2 * a.half + 1;
  const bool at_edge = out.at_edge;
  const Eigen::Vector2d start = out.position;

  // ECC: the frame patch is ECC's template, the appearance its input image, so that the
  // appearance's mask (input mask) moves with the sphere. It finds t with A(x + t) = F(x): the
  // reference point, at (half, half) in A, is at (half, half) - t in F.
  const cv::Point g2(int(std::lround(start.x())), int(std::lround(start.y())));
  const cv::Rect patch(g2.x - a.half, g2.y - a.half, size, size);
  out.position = start;
  out.ok = search_px > 0;  // without the search, only a converged ECC counts
  const cv::Mat frame_patch = FloatPatch(frame, patch);
  // Following (no search) refines from the guess itself, whose mask is already cut.
  cv::Mat refine_mask = start == guess ? mask : FrameMask(a, start, ctx);
  if (at_edge && start != guess) {
    CutAtTheFramesEdge(cv::Rect(0, 0, frame.cols, frame.rows), g2, a.half, kEdgeMaskGuardPx,
                       &refine_mask);
  }
  Eigen::Vector2d t(g2.x - start.x(), g2.y - start.y());
  double rho = 0;
  if (!RegisterTranslation(frame_patch, a.image, refine_mask, &t, &rho, kEccFrameGaussSize,
                           stop)) {
    return out;  // ECC did not converge: the correlation peak stands
  }
  const Eigen::Vector2d refined(g2.x - t.x(), g2.y - t.y());
  if ((refined - start).norm() <= kEccMaxMovePx) {
    out.position = refined;
    out.refined = rho;
    if (state_sigma) {
      out.sigma = RegistrationSigma(frame_patch, a.image, refine_mask, t, kEccFrameGaussSize);
    }
    if (search_px == 0) out.ok = true, out.score = rho;
  }
  return out;
}

}  // namespace

Located LocateAppearance(const cv::Mat& frame, const Appearance& a, const Eigen::Vector2d& guess,
                         int search_px, const MaskContext& ctx, const EccStop& stop,
                         bool state_sigma) {
  Located out;
  cv::Mat mask;
  if (!Peak(frame, a, guess, search_px, ctx, &out, &mask)) return out;
  return RefineByEcc(frame, a, guess, search_px, ctx, stop, state_sigma, mask, out);
}

Located SearchCutAppearance(const cv::Mat& frame, const Appearance& a,
                            const Eigen::Vector2d& guess, const MaskContext& ctx,
                            double min_in_view) {
  Located out;
  cv::Mat mask;
  out.ok = Peak(frame, a, guess, 1, ctx, &out, &mask, min_in_view);
  return out;
}

Located LocateCutAppearance(const cv::Mat& frame, const Appearance& a,
                            const Eigen::Vector2d& guess, const MaskContext& ctx,
                            double min_in_view, const EccStop& stop, const cv::Rect* view) {
  Located out;
  cv::Mat mask;
  if (!Peak(frame, a, guess, 0, ctx, &out, &mask, min_in_view, view)) return out;
  return RefineByEcc(frame, a, guess, 0, ctx, stop, true, mask, out);
}

namespace {

// The correlation coefficient of `templ` over `mask` at every whole pixel of `image`.
cv::Mat CorrelationMap(const cv::Mat& image, const cv::Mat& templ, const cv::Mat& mask) {
  cv::Mat res;
  cv::matchTemplate(image, templ, res, cv::TM_CCOEFF_NORMED, mask);
  KeepCorrelations(&res);
  return res;
}

// CorrelationMap computed only where it can peak: first at half resolution (cv::pyrDown of the
// frame, the template and its mask), then at full resolution in a window of +-kCoarseWindowPx
// about each of the `candidates` best coarse peaks, `suppress_px` (full px) apart; -1
// elsewhere. A sphere's peak is among them, as a half-size sphere still correlates with its
// half-size appearance (what it costs and finds: kCoarseCandidates).
cv::Mat SearchCoarseToFine(const cv::Mat& image, const cv::Mat& templ, const cv::Mat& mask,
                           double suppress_px, int candidates) {
  cv::Mat small_image, small_templ, mask_f, small_mask_f;
  cv::pyrDown(image, small_image);
  cv::pyrDown(templ, small_templ);
  mask.convertTo(mask_f, CV_32F);
  cv::pyrDown(mask_f, small_mask_f);
  // A coarse pixel is matched only where its whole smoothing kernel is known.
  const cv::Mat small_mask = small_mask_f >= 0.999f;
  if (small_image.rows < small_templ.rows || small_image.cols < small_templ.cols ||
      cv::countNonZero(small_mask) == 0) {
    return CorrelationMap(image, templ, mask);
  }
  cv::Mat res(image.rows - templ.rows + 1, image.cols - templ.cols + 1, CV_32F, cv::Scalar(-1));
  cv::Mat coarse = CorrelationMap(small_image, small_templ, small_mask / 255);
  for (int k = 0; k < candidates; ++k) {
    cv::Point at;
    cv::minMaxLoc(coarse, nullptr, nullptr, nullptr, &at);
    cv::circle(coarse, at, std::max(1, int(std::lround(0.5 * suppress_px))), cv::Scalar(-2.0),
               cv::FILLED);
    const cv::Rect window = cv::Rect(2 * at.x - kCoarseWindowPx, 2 * at.y - kCoarseWindowPx,
                                     2 * kCoarseWindowPx + 1, 2 * kCoarseWindowPx + 1) &
                            cv::Rect(0, 0, res.cols, res.rows);
    if (window.empty()) continue;
    const cv::Mat part = CorrelationMap(image(cv::Rect(window.x, window.y,
                                                       window.width + templ.cols - 1,
                                                       window.height + templ.rows - 1)),
                                        templ, mask);
    cv::Mat into = res(window);
    cv::max(into, part, into);
  }
  return res;
}

}  // namespace

double AcquireReach(const Appearance& a) {
  return std::isfinite(a.lowest_gap_px)
             ? std::clamp(a.lowest_gap_px - kAcquireGapMarginR * a.radius_px, 0.0, a.radius_px)
             : a.radius_px;
}

namespace {

// FindAppearance's search for reference points down to `reach` above the plate; `at_bound`:
// whether a peak found lies on the lowest row searched.
std::vector<Located> SearchAbovePlate(const cv::Mat& frame, const Appearance& a, double plate_row,
                                      double reach, double min_separation_px, double min_score,
                                      int coarse_candidates, bool* at_bound) {
  std::vector<Located> found;
  *at_bound = false;
  const int size = 2 * a.half + 1;
  // A resting sphere's template reaches below the plate: rows from `reach` - guard below the
  // reference are cut, and the frame is searched down to where such a template ends.
  cv::Mat mask = a.mask.clone();
  const double rod_half = kAcquireRodHalfWidthR * a.radius_px;
  const double rod_inset = a.radius_px - kRodCutInsetPx;
  for (int y = 0; y < size; ++y) {
    const double dy = y - a.half;
    for (int x = 0; x < size; ++x) {
      const double dx = x - a.half;
      if (dy > reach - kTemplatePlateGuardPx ||
          (std::abs(dx) > rod_inset && std::abs(dy) < rod_half)) {
        mask.at<uint8_t>(y, x) = 0;
      }
    }
  }
  int rows = frame.rows;
  if (std::isfinite(plate_row)) {
    rows = std::min(rows, int(std::ceil(plate_row - reach)) + a.half + 2);
  }
  if (rows < size || frame.cols < size) return found;
  const cv::Mat image = ToFloat(frame(cv::Rect(0, 0, frame.cols, rows)));
  cv::Mat res = coarse_candidates > 0 && a.radius_px >= kCoarseSearchMinRadiusPx
                    ? SearchCoarseToFine(image, a.image, mask, 0.5 * min_separation_px,
                                         coarse_candidates)
                    : CorrelationMap(image, a.image, mask);
  for (int k = 0; k < 2; ++k) {
    double best = 0;
    cv::Point at;
    cv::minMaxLoc(res, nullptr, &best, nullptr, &at);
    if (best < min_score) break;
    Located l;
    l.ok = true;
    l.score = best;
    const Eigen::Vector2d peak = PeakWithVertex(res, at);
    l.position = {peak.x() + a.half, peak.y() + a.half};
    found.push_back(l);
    *at_bound = *at_bound || (rows < frame.rows && at.y == res.rows - 1);
    cv::circle(res, at, int(std::ceil(min_separation_px)), cv::Scalar(-2.0), cv::FILLED);
  }
  return found;
}

}  // namespace

std::vector<Located> FindAppearance(const cv::Mat& frame, const Appearance& a, double plate_row,
                                    double min_separation_px, double min_score,
                                    int coarse_candidates) {
  // Down to a radius above the plate, as for a reference point at the sphere's centre; where a
  // sphere is found pressed against that bound and the learning frames put the reference
  // point lower (AcquireReach), down to there.
  bool at_bound = false;
  std::vector<Located> found = SearchAbovePlate(frame, a, plate_row, a.radius_px,
                                                min_separation_px, min_score, coarse_candidates,
                                                &at_bound);
  const double reach = AcquireReach(a);
  if (at_bound && reach < a.radius_px) {
    found = SearchAbovePlate(frame, a, plate_row, reach, min_separation_px, min_score,
                             coarse_candidates, &at_bound);
  }
  return found;
}

}  // namespace dimer::tracking
