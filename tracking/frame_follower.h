#pragma once
// Following the two spheres and the plate edge through a sequence, one frame at a time.
// A list of stages per frame:
//   1. predict each sphere from its last two positions (constant velocity);
//   2. refine the plate row in a band around the last one, using columns clear of the spheres;
//   3. measure each sphere in a window around its prediction with the film's locator
//      (sphere_locator.h: the silhouette or the learnt appearance), which masks the rod toward
//      the other sphere, the plate, and the other sphere's disc where the two touch (A_r ~2);
//   4. if a sphere is lost (missing) or nothing is locked yet, acquire on the whole frame
//      (detector.h) and give each detection the identity of the nearest last position; with no
//      history, `left` is the one with the smaller column (docs/FORMATS.md). Not where one
//      sphere is followed and the dimer's last vector puts the other out of view or cut by the
//      frame's edge (template method: OutOfViewByTheDimer);
//   5. a sphere cut by the frame's edge (template method): predicted from the other sphere,
//      found in this frame, and the dimer's vector of the last frames (the rod is rigid), or
//      alone in view from its own motion, then registered on its part in view (MeasureCuts).
// The tracker keeps only the last positions, so memory does not depend on sequence length.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "tracking/plate/clipped_edge.h"
#include "tracking/plate/plate_edge.h"
#include "tracking/sphere/measure_sphere.h"
#include "tracking/sphere/sphere_locator.h"
#include "tracking/sphere/template_locator.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {

struct Detection;  // sphere/detector.h

// FollowerOptions::lone_search_every's default: a whole-frame search costs a few times a
// following's ~0.4 ms (kCoarseCandidates; bench_cut_spheres), so every 16th frame adds a
// fraction of a following's time a frame and a sphere missed twice in a row waits at most 15
// frames.
inline constexpr int kLoneSearchEveryFrames = 16;

struct FollowerOptions {
  Method method = Method::kCentroid;  // sub-pixel method
  int polarity = 0;                   // +1 bright spheres, -1 dark (backlit), 0 automatic
  double radius_px = std::numeric_limits<double>::quiet_NaN();  // sphere radius, px; NaN: measured
  // The camera's blur, a Gaussian sigma in px: only a clipped plate edge's row depends on it
  // (ClippedEdgeRowInProfile); measure it on an unclipped edge of the same camera and lens.
  double psf_sigma_px = kPlatePsfSigmaPx;
  // Fit the blur with an over-exposed plate's level over the sequence (clipped_edge.h), with
  // psf_sigma_px only for each frame's first fit; false when the user gave the blur.
  bool fit_psf_sigma = true;
  // Method::kTemplate: ECC's stopping rule for every frame's registration. Stopping when the
  // correlation gains under 1e-5 (rather than 1e-7, which the learning keeps) costs 30 % less
  // CPU per frame and moves the answers by under 0.01 px (bench/bench_tracking.cc and
  // bench/bench_tracking_footage.cc --ecc).
  EccStop ecc{50, 1e-5};
  // Method::kTemplate: the quick step that follows from a prediction before ECC is asked
  // (sphere/fast_follow.h); max_iterations 0: ECC for every frame.
  FollowStop follow;
  // Method::kTemplate: the learnt appearances (left, right), shared by every chunk's tracker.
  std::shared_ptr<const std::array<Appearance, 2>> appearance;
  // The plate edge's slope in the image, rows per column (a camera not quite level, or a tilted
  // plate; plate_edge.h, PlateEdgeSlope), measured once for the sequence; 0: level.
  double plate_slope = 0;

  // Each found sphere's stated uncertainty in FrameTrack::sigma_px (sphere_locator.h): off by
  // default, as nothing downstream of the follower reads it and it costs ~25 % of a uniform
  // sphere's centroid.
  bool state_uncertainty = false;
  // Method::kTemplate: the distance between the two appearances' reference points on the
  // learning frames (their median), px: where a frame shows one sphere and no earlier frame of
  // the chunk gave the dimer's vector, the other is looked for, cut by the frame's edge, on the
  // circle of this radius about it (FrameFollower::SearchCutOnCircle). NaN: not looked for.
  double dimer_length_px = std::numeric_limits<double>::quiet_NaN();
  // The silhouette methods (where `auto` chose one over the learnt template): the learnt
  // appearances that place a sphere cut by the frame's edge, each one's offset from its
  // reference point to the centre the method measures, and that offset's uncertainty (col,
  // row; SilhouetteOffset over the learning frames). Null: a cut sphere is not measured.
  std::shared_ptr<const std::array<Appearance, 2>> cut_appearance;
  std::array<Eigen::Vector2d, 2> cut_offset{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  std::array<Eigen::Vector2d, 2> cut_offset_err{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  // Two frames in a row whose whole-frame search finds one sphere, the dimer's length known and
  // able to put the other out of view: the other is out of view or cut on the far side of the
  // dimer (it cannot cross to the near side between frames, half a turn away), so the one is
  // followed and the whole frame searched again only every this many frames, in case the other
  // was missed (1: every frame). Likewise two in a row that find nothing, not even a candidate
  // (the dimer has left the view): only the plate is measured until the next search.
  // bench/bench_cut_spheres measures the trade.
  int lone_search_every = kLoneSearchEveryFrames;
  // Method::kTemplate: a whole-frame search (acquisition) correlates the frame at half
  // resolution and then at full resolution about this many of its best peaks (FindAppearance,
  // kCoarseCandidates); 0: at full resolution everywhere. bench/bench_cut_spheres measures it.
  int coarse_candidates = kCoarseCandidates;

  void Check() const;  // InputError listing every invalid field
};

// One frame's result. Sphere 0 is `left`, 1 is `right`.
struct FrameTrack {
  size_t index = 0;                                // position in the frame list
  std::array<bool, 2> found{false, false};
  // Found though cut by the frame's edge: placed by the rigid dimer's prediction and its part in
  // view (FrameFollower::MeasureCut), with its own stated uncertainty in sigma_px.
  std::array<bool, 2> cut{false, false};
  std::array<Eigen::Vector2d, 2> centre{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};  // px
  std::array<double, 2> radius_px{0, 0};           // measured radius (for calibration), px
  // Each found sphere's stated standard deviation (col, row), px, from its locator
  // (SphereMeasurement::sigma_px; NaN where the locator states none or
  // FollowerOptions::state_uncertainty is off).
  std::array<Eigen::Vector2d, 2> sigma_px{
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()),
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN())};
  // Template method: each found sphere's correlation with its learnt appearance, refined by ECC
  // (NaN where ECC did not converge, and for the other methods).
  std::array<double, 2> score{std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN()};
  // The plate's top surface: its row at column plate_col (under the dimer: midway between the
  // spheres as they were predicted or found), sloping by plate_slope rows per column, px.
  double plate_row = std::numeric_limits<double>::quiet_NaN();
  double plate_col = 0;
  double plate_slope = 0;
  // The plate's row at column `col` (plate_row itself when the plate is level).
  double PlateRowAt(double col) const {
    return SlopedRowAt(plate_row, plate_col, plate_slope, col);
  }
  // Where the plate's bright side clips: its profile, fitted again once the sequence knows the
  // clipped level (clipped_edge.h); null otherwise, and after that fit.
  std::shared_ptr<const ClippedEdgeProfile> clipped_plate;
  bool acquired = false;                           // whole-frame detection was needed
  // Acquired: the image's strongest edge's row where the plate is another edge (the one the
  // dimer stands on, sphere/detector.h); NaN where the strongest edge is the plate.
  double strongest_edge_row = std::numeric_limits<double>::quiet_NaN();
  // Template method: the learnt appearance each sphere was measured with (the chunk's name for
  // it); the film's names (dimer_identity.h) may differ, and the appearance's offsets follow it.
  std::array<int, 2> appearance{0, 1};

  // Found and whole: not cut by the frame's edge (film-level measures rest on these).
  bool whole(int k) const { return found[k] && !cut[k]; }
  // Every per-sphere field exchanged between the two names.
  void SwapSpheres();
  // Sphere k taken for no match: not found, its centre cleared, no score.
  void Drop(int k);
};

// The distance between the two centres in each frame, in frame order, px; NaN where a sphere is
// not found whole (FrameTrack::whole). A rigid body keeps it: its second differences are the
// tracker's noise whatever the motion (GapNoise).
std::vector<double> DimerLengthSeries(const std::vector<FrameTrack>& frames);

class FrameFollower {
 public:
  explicit FrameFollower(const FollowerOptions& options);
  FrameTrack Process(const cv::Mat& frame, size_t index);
  int polarity() const { return polarity_; }
  // A chunk's first frames have no history to place a cut sphere by, nor its last frames a
  // future: the chunk goes back over them from the first frame that placed it, and the film
  // over its chunks' seams both ways (cut_spheres.h). Places each sphere of `adjacent` (the
  // frame next to *t, before or after it) that *t misses, in `frame`: where *t shows the other
  // and `adjacent` both, by the dimer's vector (changing as from `beyond`, the frame next to
  // `adjacent`; null: none); else by its own motion from `adjacent` and `beyond`. True: *t has
  // every sphere `adjacent` has.
  bool PlaceCutBeside(const cv::Mat& frame, const FrameTrack& adjacent, const FrameTrack* beyond,
                      FrameTrack* t) const;
  double radius_px() const { return radius_px_; }

 private:
  bool Follow(const cv::Mat& frame, FrameTrack* out);
  // Template method: where the dimer's last vector puts the sphere other than j, followed at
  // its last position, its disc is out of `frame` or within kCutWholeMarginPx of its edge (no
  // whole-frame search could find it there).
  bool OutOfViewByTheDimer(const cv::Mat& frame, int j) const;
  // One sphere found in `t`: whether the other, on the circle of the dimer's length about it
  // (either side, tilted up to kCutMaxTiltRad), can lie out of view or cut by the frame's edge.
  // Where it cannot, a search that found one sphere missed the other in view. False without
  // the dimer's length.
  bool OtherCanBeOutOfView(const cv::Mat& frame, const FrameTrack& t) const;
  // After frame `t` of `frame`: how many frames follow a lone sphere before the whole frame is
  // searched again (FollowerOptions::lone_search_every).
  void PlanSearches(const cv::Mat& frame, const FrameTrack& t);
  void Acquire(const cv::Mat& frame, FrameTrack* out);
  // Acquire's search with the plate at the detection's `det.plate_row`.
  void AcquireAbove(const cv::Mat& frame, const Detection& detection, FrameTrack* out);
  // The lowest row, at column `col` along the plate's slope, above which t's found spheres'
  // reference points stand by their reach (AcquireReach); NaN where none was found.
  double LowestReach(const FrameTrack& t, double col) const;
  // A frame between whole-frame searches while nothing is in view: the plate's row near its
  // last, no sphere. False where the plate is not found there (the frame is then acquired).
  bool MeasurePlateOnly(const cv::Mat& frame, FrameTrack* out);
  bool uses_template() const;
  // A sphere cut by the frame's edge is placed by a learnt appearance: the method's own, or
  // options_.cut_appearance with the silhouette methods (step 5).
  bool places_cuts() const;
  const Appearance& CutAppearance(int k) const;
  // From appearance k's reference point to the centre the method measures (0 for the template,
  // whose offsets come after the film: ApplyOffsets).
  Eigen::Vector2d CutOffset(int k) const;
  // What a locator is told of sphere at `at`: the other sphere (null: none), the plate under it
  // in `frame`'s track, and whether `at` is a follower's prediction or a coarse detection.
  SpherePrediction Prediction(const Eigen::Vector2d& at, const Eigen::Vector2d* other,
                              const FrameTrack& frame, bool precise) const;
  // The plate's row under the spheres at `centres` (the first n), and the column it is at;
  // `guess` is a row of the edge at column `guess_col`.
  double PlateRow(const cv::Mat& frame, double guess, double guess_col,
                  const std::array<Eigen::Vector2d, 2>& centres, int n,
                  std::shared_ptr<const ClippedEdgeProfile>* clipped, double* col) const;
  void Commit(const FrameTrack& t);
  // Sphere k, not found in *out, placed from `guess` if at least kCutMinInView of its disc is
  // in view and its appearance registers there; where the other is found, only if its distance
  // from it is within kCutLengthTolerancePx of `length`. True: *out has it, marked cut.
  bool PlaceCut(const cv::Mat& frame, int k, const Eigen::Vector2d& guess, double length,
                FrameTrack* out) const;
  // A cut sphere k's stated uncertainty (col, row), px: its registration's on the pixels in
  // view, with what cutting a sphere alike does: the whole sphere beside it in `t`, cut as k
  // is by the frame's edge (the same part of it in view), moves by `shift`, which is added in
  // quadrature (PlaceCut adds how far the pair's distance misses the dimer's length). NaN where
  // the other is not found whole: the film states the sphere's mean (StateCutUncertainty,
  // cut_spheres.h).
  Eigen::Vector2d CutSigma(const cv::Mat& frame, int k, const Located& l,
                           const FrameTrack& t) const;
  // Step 5 for sphere k, not found in *out while the other is: PlaceCut where `dimer` (right -
  // left centre) puts it.
  bool MeasureCut(const cv::Mat& frame, int k, const Eigen::Vector2d& dimer, double length,
                  FrameTrack* out) const;
  // Step 5 for both spheres with the dimer's vector of the last frames, or without it, on the
  // circle of options_.dimer_length_px about the one found (SearchCutOnCircle); a sphere alone
  // in view, followed into the last frame, from its own motion (no length to referee it).
  void MeasureCuts(const cv::Mat& frame, FrameTrack* out) const;
  // One sphere found in *out and no dimer's vector known: the other is looked for cut by the
  // frame's edge on either side, its centre on the circle of the dimer's length about the one
  // found and above the plate; the best match by its part in view, if it registers there and
  // scores kMinTemplateScore, is the other sphere, and the pair's names follow from their
  // places on the dimer (left: the smaller column).
  void SearchCutOnCircle(const cv::Mat& frame, FrameTrack* out) const;

  FollowerOptions options_;
  // Sphere k's locator (sphere_locator.h): the learnt appearance k, or the silhouette for both.
  std::array<std::shared_ptr<const SphereLocator>, 2> locator_;
  int polarity_ = 0;
  double radius_px_;
  double plate_row_ = std::numeric_limits<double>::quiet_NaN();
  double plate_col_ = 0;  // the column plate_row_ is at
  // The footage's pixel noise (FrameNoiseSigma on the first frame), grey levels: the centroid's
  // stated uncertainty scales with it.
  double noise_sigma_ = std::numeric_limits<double>::quiet_NaN();
  bool noise_measured_ = false;
  std::array<bool, 2> known_{false, false};    // a last position exists (maybe stale)
  std::array<bool, 2> locked_{false, false};   // found in the previous frame
  std::array<Eigen::Vector2d, 2> last_{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  std::array<Eigen::Vector2d, 2> velocity_{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  // The dimer's vector (right - left centre) in the last frame both were found in, its change
  // per frame where the frame before had both too, and how many frames ago it was seen.
  Eigen::Vector2d dimer_{0, 0}, dimer_rate_{0, 0};
  bool dimer_known_ = false;
  bool dimer_seen_ = false;  // dimer_ was measured in this follower's frames (maybe long ago)
  int dimer_age_ = 0;
  // Frames left before a lone sphere's whole-frame search again (lone_search_every), and how
  // many whole-frame searches in a row found one sphere.
  int lone_frames_left_ = 0;
  int lone_searches_ = 0;
  // The same for frames with nothing in view: the last whole-frame search's candidates, how many
  // searches in a row found none, and frames left that measure the plate alone (MeasurePlateOnly).
  int acquired_candidates_ = 0;
  int empty_searches_ = 0;
  int empty_frames_left_ = 0;
};

}  // namespace dimer::tracking
