#pragma once
// Following a learnt appearance (template_locator.h) from a tracker's prediction at about the
// cost of a centroid: a Gauss-Newton fit of shift, gain and offset with the appearance's
// gradients computed once (inverse compositional Lucas-Kanade, Baker & Matthews 2004), and
// cv::findTransformECC (LocateAppearance) only where this quick step fails its checks.
//
// Why: the two ECC runs of LocateAppearance cost ~1.3 ms a sphere (OpenCV smooths, takes
// gradients and warps both images afresh in every iteration); at 2,000 frames/s a 10 s film
// took over a minute. The quick step does per frame one smoothing of the frame's patch and, per
// iteration, a handful of masked sums and a 4x4 solve.
//
// The model. A is the appearance smoothed like ECC's residual run (a 3x3 Gaussian), c its
// reference point (half, half), F the frame smoothed alike. Where the reference point is at p,
// F(y) = a A(y - p + c) + b over the appearance's mask (a, b: the frame's gain and offset, to
// which ECC's correlation is invariant; the footage's brightness drifts). With d = p - c split
// into whole pixels D, a step of the shift grid k / K and a remainder delta:
//     F(x + D) = a A_k(x - delta) + b ~ a A_k(x) + b + grad A_k(x) . u,   u = -a delta,
// where A_k is A shifted by k / K px (Lanczos, a = 4: OpenCV's INTER_LANCZOS4, as ECC's
// residual run shifts it) with its gradients, prepared once for the K x K shifts of the grid.
// Linear in theta = (a, b, u_x, u_y): least squares over the frame's mask M gives
// H theta = sum_M phi J, J(x) = F(x + D), phi = (A_k, 1, dA_k/dx, dA_k/dy), H = sum_M phi phi^T.
// H depends on the frame's mask (the rod corridor, the plate rows and the other sphere are cut
// per frame: FrameMask), so it is summed per frame, never precomputed. The frame is read at
// whole pixels only, as ECC reads it: nothing of a cut region leaks into the sums beyond the
// smoothing's pixel (the mask's guards cover it), as interpolating the frame would (Lanczos
// reaches 4 px: a bright plate 3 px below moved the answer 0.03 px).
// The iteration: from the prediction, solve at the nearest grid shift, move there; done when the
// remainder is within 0.75 / K px (the grid point's own cell, or the border two cells share).
// The linearisation's error is second order in the remainder, ~delta^2 / 3 px for detail ~1.5 px
// wide: under 0.003 px at K = 8 (bench_tracking measures K).
//
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {

// The quick step's knobs, which trade time for accuracy and for how often ECC is called
// (bench/bench_tracking.cc and bench/bench_tracking_footage.cc measure them).
// max_iterations = 0: no quick step, ECC for every frame.
struct FollowStop {
  int max_iterations = 4;        // solves (each at the grid shift nearest the last estimate)
  int shifts_per_px = 8;         // K: the grid of prepared shifts, 1 / K px apart
  double min_correlation = 0.8;  // the correlation coefficient below which ECC decides
};

// An appearance prepared for the quick step: smoothed and shifted to each point of the grid.
struct FollowModel {
  int half = 0;
  int shifts_per_px = 0;
  // shifted[(ky + K/2) * K + kx + K/2]: A shifted by (kx, ky) / K px, kx, ky in [-K/2, K/2),
  // with a pixel of border (its gradients are central differences). CV_32F, size + 2 square.
  std::vector<cv::Mat> shifted;
  bool valid() const { return !shifted.empty(); }
};
FollowModel PrepareFollow(const Appearance& a, int shifts_per_px = FollowStop{}.shifts_per_px);

struct QuickFollow {
  bool ok = false;                 // converged and passed every check
  Eigen::Vector2d position{0, 0};  // reference point in the frame, px (the last estimate)
  double correlation = 0;          // of the sampled frame with the appearance over the mask
  double gain = 0;                 // the frame's gain against the appearance
  int iterations = 0;
};

// The quick step from `guess` over `mask` (the appearance's grid, CV_8U: FrameMask). Not ok
// also when the patch it needs is not wholly in the frame (the caller falls back to ECC, which
// handles a sphere at the frame's edge). `frame`: CV_8U, CV_16U or CV_32F, one channel.
QuickFollow FollowQuickly(const cv::Mat& frame, const FollowModel& m, const cv::Mat& mask,
                          const Eigen::Vector2d& guess, const FollowStop& stop);

// The quick step alone, from `guess` or (search_px > 0) from SearchAppearance's peak about it:
// nothing where it fails its checks, the search finds no sphere, the sphere is at the frame's
// edge or too little of its mask is left. Answers as FollowAppearance's below.
std::optional<Located> FollowOnlyQuickly(const cv::Mat& frame, const Appearance& a,
                                         const FollowModel& m, const Eigen::Vector2d& guess,
                                         const MaskContext& ctx, const FollowStop& stop,
                                         int search_px = 0, bool state_sigma = false);

// Following from a prediction: the quick step, from `guess` (search_px 0, the tracker's) or
// from LocateAppearance's whole-pixel search's peak about it (SearchAppearance: acquisition, the
// learning's registrations). Where it fails (or `m` is not valid, or stop.max_iterations is 0,
// or the sphere is at the frame's edge), LocateAppearance(frame, a, guess, search_px, ctx, ecc),
// ECC after the search if any. The quick step's answer is reported like ECC's: ok, refined =
// its correlation coefficient, score = the search's peak (with a search) or that coefficient,
// and with `state_sigma` its standard deviation (RegistrationSigma at the answer: the quick step
// solves the same smoothed least squares, and reaches that bound, sphere_locator_test.cc).
Located FollowAppearance(const cv::Mat& frame, const Appearance& a, const FollowModel& m,
                         const Eigen::Vector2d& guess, const MaskContext& ctx,
                         const FollowStop& stop, const EccStop& ecc, int search_px = 0,
                         bool state_sigma = false);

}  // namespace dimer::tracking
