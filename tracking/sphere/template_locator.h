#pragma once
// Locating a sphere's learnt appearance (appearance_model.h) in a frame to a fraction of a pixel,
// with OpenCV's own registration tools, nothing hand-rolled:
//   1. cv::matchTemplate (normalised correlation coefficient, with the template's mask) over a
//      small search window around the guess: the whole-pixel peak;
//   2. a quadratic through the peak's 3x3 neighbourhood (one parabola per axis): a sub-pixel
//      start within ~0.2 px;
//   3. cv::findTransformECC (translation only, the template's mask warped with it): the final
//      shift, which maximises the enhanced correlation coefficient between the frame and the
//      template over the masked pixels (Evangelidis & Psarakis 2008).
// Nothing is assumed about how the sphere looks: a silhouette, a few highlights, a reflection,
// all are a pattern fixed to the sphere (a mirror sphere looks the same whatever its spin). The
// rod (a corridor toward the other sphere) and the plate (the rows at and below its top edge,
// with the sphere's reflection in it) are not part of the sphere: they are cut from the mask
// for each frame, where they are in that frame.
//
// The result is the position of the template's reference point in the frame, not the sphere's
// centre: the offset between the two is estimated once per sequence (appearance_model.h).
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <vector>

#include "tracking/sphere/still_background.h"

namespace dimer::tracking {

// A learnt appearance: (2 half + 1) pixels square, the reference point at (half, half).
struct Appearance {
  cv::Mat image;         // CV_32F, the mean appearance (masked pixels hold the mean level)
  cv::Mat mask;          // CV_8U, 1 where the appearance is known (seen, not rod nor plate)
  int half = 0;          // half-size, px
  double radius_px = 0;  // sphere radius the masks are sized for, px
  // The slope (rows per column) of the plate whose reflection the appearance shows: its horizon
  // is looked for and cut along it (appearance_model.h); 0: level.
  double horizon_slope = 0;
  // The reference point's least height above the plate over the learning frames (the plate's
  // row less the reference row), px; NaN: not measured. The reference point is where the
  // rough centres put the sphere, which on mirror-lit spheres can be pixels below its centre;
  // a sphere touching the plate is searched for down to there (FindAppearance).
  double lowest_gap_px = std::numeric_limits<double>::quiet_NaN();
  // What stands still behind the sphere in the film (still_background.h), set where the sphere
  // was learnt without it; FrameMask cuts it about and beyond the rim. Null: nothing cut.
  std::shared_ptr<const StillBackground> still;
  bool valid() const { return !image.empty(); }
};

// Where the rod, the plate and the other sphere are in one frame, relative to a sphere.
struct MaskContext {
  Eigen::Vector2d rod_dir{0, 0};  // unit vector toward the other sphere; zero: no rod cut
  double plate_row = std::numeric_limits<double>::quiet_NaN();  // plate top surface, px
  double plate_slope = 0;  // its slope, rows per column (plate_row is at the sphere's column)
  // The other sphere's position minus this one's (px; NaN: unknown): spheres in contact
  // (A_r 2.0) reach into each other's templates, and the other's disc widened by
  // kOtherSphereMarginPx is cut, its look changing with the tilt.
  Eigen::Vector2d other{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
};

// The appearance's mask with the rod corridor and the plate rows of the frame cut, for the
// reference point at `position` (frame coordinates, px).
cv::Mat FrameMask(const Appearance& a, const Eigen::Vector2d& position, const MaskContext& ctx);

// How near the plate `a`'s reference point can come, px: the radius, or less where it came
// nearer the plate in the learning frames (Appearance::lowest_gap_px), less a margin. The
// whole-frame search (FindAppearance) reaches down to there where a sphere is found pressed
// against its bound a radius above the plate.
double AcquireReach(const Appearance& a);

struct Located {
  bool ok = false;              // false: window outside the frame, too few pixels, flat peak
  bool clipped = false;         // too little of the sphere is in the frame to match
  bool at_edge = false;         // matched on the part in the frame (the rest left out)
  Eigen::Vector2d position{0, 0};  // reference point in the frame (col, row), px
  double score = 0;             // correlation coefficient at the peak (-1..1)
  // The correlation coefficient at the refined position, where ECC or the quick step
  // (fast_follow.h) converged (NaN else):
  // after a whole-pixel search `score` is the search's, lower by the fraction of a pixel the
  // peak is off (POV-Ray under-exposed: 0.52 against 0.86 refined), so that only `refined`
  // compares one frame's match with another's (match_scores.h).
  double refined = std::numeric_limits<double>::quiet_NaN();
  // Standard deviation of the refined position (col, row), px (RegistrationSigma); NaN where
  // neither ECC nor the quick step refined it, or it was not asked for.
  Eigen::Vector2d sigma{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
};

// ECC's stopping rule (cv::findTransformECC's criteria, for each of its two runs): Gauss-Newton
// iterations at most, and the increase of the correlation coefficient that ends them. It trades
// time for accuracy: bench/bench_tracking_footage.cc --ecc measures by how much.
struct EccStop {
  int max_iterations = 50;
  double epsilon = 1e-7;
};

// Translation t with moving(x + t) ~ fixed(x) over `mask` (moving's pixels, CV_8U), starting
// from *t: cv::findTransformECC, then once more on `moving` pre-shifted by Lanczos
// interpolation, that run smoothing with a Gaussian of `residual_gauss` (ECC's gaussFiltSize;
// the first run always 5). False when ECC does not converge. Both images CV_32F, same size.
bool RegisterTranslation(const cv::Mat& fixed, const cv::Mat& moving, const cv::Mat& mask,
                         Eigen::Vector2d* t, double* rho = nullptr, int residual_gauss = 5,
                         const EccStop& stop = {});

// Standard deviation (col, row) of a translation t registered by RegisterTranslation (same
// images and mask, its last run smoothing with a Gaussian of `gauss_size`): `moving` warped by
// t and fitted to `fixed` by a gain and a level over the mask gives the residual variance,
// which holds the noise and any mismatch of the appearance (a poorer match states a larger
// uncertainty); propagated through the smoothed least squares that ECC solves.
Eigen::Vector2d RegistrationSigma(const cv::Mat& fixed, const cv::Mat& moving, const cv::Mat& mask,
                                  const Eigen::Vector2d& t, int gauss_size);

// Searches +-search_px (whole pixels) around `guess`, then refines. search_px = 0: no search,
// ECC from the guess (a tracker's prediction), ok only if it converges within a pixel of it,
// score = ECC's correlation coefficient. `frame` is CV_8U or CV_16U
// (or CV_32F), single channel.
// `state_sigma`: also compute Located::sigma (RegistrationSigma, ~3 % of the call's time).
Located LocateAppearance(const cv::Mat& frame, const Appearance& a, const Eigen::Vector2d& guess,
                         int search_px, const MaskContext& ctx, const EccStop& stop = {},
                         bool state_sigma = false);

// LocateAppearance's whole-pixel search alone (search_px > 0): the correlation peak refined by
// the parabola only (`refined` NaN); ok as LocateAppearance's would be before its ECC.
Located SearchAppearance(const cv::Mat& frame, const Appearance& a, const Eigen::Vector2d& guess,
                         int search_px, const MaskContext& ctx);

// A sphere cut by the frame's edge, placed from `guess` (the rigid dimer's prediction, within
// a pixel) by ECC on its pixels in view alone, with no whole-pixel search: the peak of a search
// beside a cut sphere lay 3-7 px off (the DimerIdentity walks). Not ok where under
// `min_in_view` of the appearance's pixels are in view, or ECC does not converge within a pixel
// of the guess; `sigma` always stated (RegistrationSigma on the pixels in view). `view`: the
// part of the frame taken for in view (null: all of it), to cut a whole sphere alike.
Located LocateCutAppearance(const cv::Mat& frame, const Appearance& a,
                            const Eigen::Vector2d& guess, const MaskContext& ctx,
                            double min_in_view, const EccStop& stop = {},
                            const cv::Rect* view = nullptr);

// The correlation of a sphere cut by the frame's edge with its appearance, over its pixels in
// view, at the whole pixels next to `guess` (the best, by the parabola; `refined` NaN); not ok
// where under `min_in_view` of them are in view. A candidate's score, for LocateCutAppearance.
Located SearchCutAppearance(const cv::Mat& frame, const Appearance& a,
                            const Eigen::Vector2d& guess, const MaskContext& ctx,
                            double min_in_view);

// FindAppearance's default `coarse_candidates`: the whole frame searched at half resolution,
// then at full resolution about this many of the best coarse peaks, finding what the full map
// finds (FindAppearance.TheCoarseSearchFindsWhatTheFullOneFinds) at a third of its ~6 ms a
// frame at 512x256 and R 23.75 px (bench_cut_spheres).
inline constexpr int kCoarseCandidates = 6;

// Whole-frame search (acquisition): the best match above `plate_row` (NaN: anywhere), and the
// best one at least `min_separation_px` from it (if any scores above `min_score`).
// Sub-pixel refined. Returns 0, 1 or 2 positions, best first. `coarse_candidates` 0: the
// correlation at every whole pixel of the frame (also for spheres under 8 px in radius);
// otherwise only about that many peaks of it at half resolution.
std::vector<Located> FindAppearance(const cv::Mat& frame, const Appearance& a, double plate_row,
                                    double min_separation_px, double min_score,
                                    int coarse_candidates = kCoarseCandidates);

}  // namespace dimer::tracking
