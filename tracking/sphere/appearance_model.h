#pragma once
// Each sphere's appearance, learnt from the footage itself, and the offset from that appearance
// to the sphere's true centre (`--method template`, template_locator.h locates it per frame).
//
// Learning. A fixed set of frames (chosen by frame index only, so it does not depend on the
// thread count or the chunking), with rough centres from the existing methods, gives one patch
// per sphere per frame. The patches are averaged over the pixels that show the sphere (the rod
// corridor toward the other sphere and the plate rows are left out per frame), then each patch
// is registered to the mean (template_locator.h) and the mean rebuilt from patches resampled at
// the registered sub-pixel positions (cv::warpAffine, bicubic); kLearnPasses times. The rough
// centres need only be within a few pixels and consistent: registration to the mean replaces
// them. The result is fixed for the whole sequence and shared by every chunk.
//
// Offset. The template's reference point is where the rough centres put it, not the sphere's
// centre (a front-lit steel sphere's rim fit is biased by pixels). It is estimated once per
// sequence, with its uncertainty, from what the footage shows:
//   - silhouette: when the spheres are clean uniform silhouettes (backlit, bright background,
//     matte discs), the existing centroid is unbiased; offset = median over the learning frames
//     of (silhouette centre - registered position);
//   - plate contact (rows): a sphere resting on the plate has its centre R above the plate's top
//     surface; over the whole track, the frames whose reference row is lowest relative to the
//     plate (the cluster within a band of the lowest, kContactBandPx or 3 noise sigmas) are
//     taken as resting, offset = mean of (plate - R - reference row); a sphere that never rests
//     touches the plate where its impacts' approach and rebound meet (impact_vertex.h);
//   - limb (columns): the centre of the sphere's outline in the appearance (limb_fit.h), which
//     does not depend on where the lamps are;
//   - symmetry (columns, where the outline cannot be fitted; checked against the whole outline,
//     ColumnWithoutTheUpperOutline): with the camera and the lights in
//     a vertical plane through the sphere, the appearance is mirror symmetric about the vertical
//     through the centre; the template is registered to its own mirror image
//     (cv::findTransformECC) and the axis is half the shift. Highlights are clipped first
//     (kSymmetryClipQuantile) so that two lamps placed unevenly weigh less than the silhouette
//     and the plate's reflection, which are symmetric. Lamps to one side defeat it (pixels off).
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tracking/plate/plate_edge.h"
#include "tracking/sphere/learnt_sphere.h"
#include "tracking/sphere/template_locator.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {

// Learning frames: every k-th of the first kLearnSpanFrames, k chosen for kLearnFrames frames.
inline constexpr size_t kLearnFrames = 48;
inline constexpr size_t kLearnSpanFrames = 4000;
// Registration passes after the first (patches to the mean, mean rebuilt). The first pass
// takes the patches from the rough centres (pixels apart) to the registration's noise; every
// pass after it moves them by that noise again (POV-Ray front_point: rms 0.13 px, then
// 0.023-0.030 px on each of passes 1, 2 and 3, with no downward trend), so one is kept: each
// pass cost ~16 ms of CPU per frame of a 40-frame film (90 ms with three, 57 with one) and the
// answers move within their stated uncertainty (bench/bench_tracking_footage --learn-passes).
inline constexpr int kLearnPasses = 1;

// Groups of learning samples for the delete-a-group jackknife (LearntSphere::jackknife): as
// many as there are samples up to this. More groups give the variance more degrees of freedom
// (groups - 1); each costs a mean and a limb fit per sphere and sequence.
// `bench_tracking_footage --jackknife` measures the trade.
inline constexpr int kJackknifeGroups = 16;

// How the learning runs: `passes` as kLearnPasses (0: the rough positions' mean is the
// appearance; each pass more averages and registers every sample once again), `threads` for
// the samples' registrations (common/parallel_for.h: the result does not depend on it).
// bench/bench_tracking_footage --learn-passes measures what the passes buy.
struct LearnOptions {
  int passes = kLearnPasses;
  int threads = 1;
  // The plate edge's slope, rows per column (plate_slope.h): the plate's reflection in a sphere
  // tilts with it, and is looked for and cut along it.
  double plate_slope = 0;
  // Jackknife groups (kJackknifeGroups); 0 (or fewer than 3): none, the column's uncertainty
  // from the outline's pairs alone.
  int jackknife_groups = kJackknifeGroups;
  // Seeds from the highlights (highlight_seed.h, SeedFilm): a learning frame is kept when its
  // two seeds stand within this of the film's median separation, px; 0: twice LearnSearchPx
  // (each seed then possibly within the learning's search). PrepareSequenceMethod uses it.
  double seed_agreement_px = 0;
  // Pixels whose values, in the patches aligned on the sphere, spread over the learning samples
  // by more than this many times the appearance's median spread are left out of it: they stand
  // still behind the sphere instead of moving with it (a ruler's or a backdrop's edges). 0:
  // none. PrepareSequenceMethod sets kStillBackgroundSpread where it learns a sphere again that
  // the referee (detection_agreement.h) found held by something behind it.
  double still_background_spread = 0;
  // Per sphere, one flag per learning sample (empty: none): the samples where the sphere rests
  // on the plate. Their rows are set by the plate after every registration, at the plate's row
  // under the sphere less the flagged samples' median gap, instead of registered: a resting
  // sphere moves with the plate, while something standing still behind it (a ruler's edge) can
  // hold its registrations. PrepareSequenceMethod sets them where it learns a resting sphere
  // again whose rows did not move with the plate (learn_method.cc, RelearnHeldByThePlate).
  std::array<std::vector<uint8_t>, 2> rows_on_plate{};
  // Per sphere: learnt again from its highlights without what stands still behind it whatever
  // its detections' referee says (learn_method.cc, RelearnHeldSpheres), and kept where that
  // referee then passes it. Set where the dimer's length, followed over the film's first
  // frames, departs (length_relearn.h).
  std::array<bool, 2> relearn_held{false, false};
};
// The median spread is the noise's; a sphere's own edges spread by their gradient times the
// registration's error, the edges of what stands still behind it by their gradient times the
// sphere's motion. On POV-Ray ruler_above_plate the hopping sphere learnt again is followed
// (rows and columns within 0.06 px of the truth, scatter <= 0.031 px) with 5 to 20 (with the
// margin below); it scatters by 0.12-0.16 px with 4, by 1.2-1.4 px with 2 or 3
// (povray.detection_agreement).
inline constexpr double kStillBackgroundSpread = 6.0;
// The pixels within this of still background are left out with it: the edge's blur spreads it
// over them, and the template's gradient and its sub-pixel shift reach them. A still edge's
// flat side kept beside the cut held the rows: on the ruler's 100-frame film the resting left
// sphere, learnt again, scattered 0.084 px in rows about the truth with no margin, 0.048 with
// 1 px and 0.023 with 2 or 3 (povray.long_ruler).
inline constexpr int kStillBackgroundMarginPx = 2;
// Frames whose reference row is within this of the lowest (relative to the plate) rest, px;
// where the gap's noise (impact_vertex.h, GapNoise) is larger than a third of it, within
// kContactBandNoise times the noise.
inline constexpr double kContactBandPx = 0.3;
inline constexpr double kContactBandNoise = 3.0;
// The resting cluster's window is moved to its mean at most this many times, until it moves by
// less than kContactWindowSettledPx, and never reaches above kContactCeilingBands bands over
// the lowest value (ContactRowOffset).
inline constexpr int kContactWindowSteps = 20;
inline constexpr double kContactWindowSettledPx = 1e-4;
inline constexpr double kContactCeilingBands = 3.0;

// One learning frame with the rough centres of the existing methods (left, right).
struct LearningSample {
  cv::Mat image;
  // The plate's row at column plate_col, sloping by plate_slope rows per column (frame_follower.h,
  // FrameTrack).
  double plate_row = std::numeric_limits<double>::quiet_NaN();
  double plate_col = 0;
  double plate_slope = 0;
  double PlateRowAt(double col) const {
    return SlopedRowAt(plate_row, plate_col, plate_slope, col);
  }
  std::array<bool, 2> found{false, false};
  std::array<Eigen::Vector2d, 2> centre{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
};

// Where the rod, the plate and the other sphere are relative to sphere k (0 left, 1 right) in a
// learning sample, from its rough centres: the cuts its registrations make.
MaskContext LearningContext(const LearningSample& s, int k);

// The jackknife estimate of the standard error of `values` (one per left-out group, NaN where
// the quantity could not be measured without that group): sqrt((g - 1) / g * sum (v - mean)^2)
// over the g finite ones; NaN with fewer than 3.
double JackknifeError(const std::vector<double>& values);

// How far the learning reaches for a sphere (Reach, tolerances.h): the rough centres' errors
// are a fraction of the radius (a centroid on a front-lit steel sphere sits ~0.45 R low, on its
// reflection of the plate), so reaches fixed in pixels failed at a finer scale: at 0.1 mm/px
// (R = 47.5 px) the first template cut off the sphere's top and one column was 4.3 px off
// (see povray.targets.fine_scale).

// Re-centring (footage without clean silhouettes): the first template reaches this much beyond
// the radius to hold a sphere whose rough centre is off by up to that,
// Reach(kRecentreSearchPx, kRecentreSearchR, R); with the radius unknown, it is sized for
// kRecentreRadiusHigh times the guess.
inline constexpr double kRecentreSearchPx = 14.0;
inline constexpr double kRecentreSearchR = 0.58;
inline constexpr double kRecentreRadiusHigh = 1.3;
// The limb column offset of a re-centred template is within
// Reach(kLimbOffsetMaxPx, kLimbOffsetMaxR, R) of its reference point.
inline constexpr double kLimbOffsetMaxPx = 4.0;
inline constexpr double kLimbOffsetMaxR = 0.16;

// A steel sphere on a plate reflects the plate in its lower part, and on real optics that
// reflection is not fixed to the sphere: its horizon (the plate's far edge seen in the sphere, a
// strong horizontal step) moves as the sphere rises, and near the rim the reflection ends before
// the outline does, by different amounts on the two sides. Matched with it, a bouncing sphere's
// row drifted by 0.05 px per px of lift on the POV-Ray footage (reflection_cut_test.cc). So when the
// horizon of either sphere moves with its height above the plate in the learning frames (a
// straight-line fit, appearance_model.cc HorizonMoves), both final appearances leave out
// everything from HorizonGuard(R) above their horizon down (at R = 23.75 px, 2 px did better
// there than 4 or 6; the guard scales with the radius: at 0.1 mm/px 2 px left a bouncing
// sphere's row drifting 0.18 px over its lift);
// what remains is fixed to the sphere: the outline against the backdrop, the lamps' highlights.
// Where it does not move (our renderer paints the reflection on the sphere) the whole appearance
// is kept: cut, it located impacts 2x less precisely there. The outline fits (columns, the row
// carried through the outlines) use the part above the horizon in every case.
inline constexpr int kHorizonGuardPx = 2;
inline constexpr double kHorizonGuardR = 0.084;
inline int HorizonGuard(double radius_px) {
  return int(std::lround(Reach(kHorizonGuardPx, kHorizonGuardR, radius_px)));
}

// Row (template coordinates) of the horizon of the plate's reflection in a mirror sphere
// `image` (CV_32F, `mask` CV_8U): the strongest vertical step across the central columns
// (|x| <= 0.5 R) between 0.3 R above and 0.7 R below the centre, if it stands 4 times above the
// median step there; -1 if there is none (a matte sphere, a backlit one). The step of a row is
// the median over those columns: the horizon crosses them all, a lamp's reflection only some.
// Their mean took a soft box's bright reflection just above the horizon for it (POV-Ray
// front_softbox), and the cut below it then ran through the lamp, whose cut edge locked the
// rows to the pixel grid (a row scatter of 0.06-0.08 px; 0.014 px with the real horizon).
// `slope`: the plate's, rows per column: the horizon is looked for along lines of that slope.
int ReflectionHorizon(const cv::Mat& image, const cv::Mat& mask, int half, double radius_px,
                      double slope = 0);
// The appearance above its plate reflection's horizon, less HorizonGuard (the outline there is
// the sphere's own), cut along its horizon_slope; itself when it shows no horizon.
Appearance UpperPart(const Appearance& a);

// How far the learning registers a sample from where it was seeded, px (whole pixels): a rough
// centre farther off than this is averaged in where it is.
int LearnSearchPx(double radius_px);

// Both spheres' appearances (0 left, 1 right); invalid appearance if too few samples.
// `recentre` (footage without clean silhouettes): the templates are framed again around the
// rough centres shifted by provisional offsets, columns from the outline, rows from the plate
// contact (see the .cc), and leave out the plate's reflection (kHorizonGuardPx). `fit_radius`
// (with `recentre`; the scale is not given): `radius_px` is only a guess and the radius is taken
// from the outline; the appearances' radius_px holds it.
std::array<LearntSphere, 2> LearnAppearances(const std::vector<LearningSample>& samples,
                                             double radius_px, bool recentre,
                                             bool fit_radius = false,
                                             bool* radius_from_outline = nullptr,
                                             const LearnOptions& learn = {});
// Both spheres' outline radii must agree within this fraction to be taken (fit_radius): one
// that does not has caught a reflection's boundary instead of the outline.
inline constexpr double kOutlineRadiusAgreement = 0.03;

// The silhouette methods' own bias on footage they were not made on, px: the centroid on the
// POV-Ray backlit and bright-background films is 0.028-0.031 px off in each column, toward the
// rod (docs/BENCHMARKS.md, bench_tracking_footage). A silhouette offset inherits it, and
// stated only the scatter of its median (0.003 px there: 12 of its own sigmas off).
inline constexpr double kSilhouetteBiasPx = 0.03;

// Silhouette: median of rough - registered per axis (0 column, 1 row); error from the MAD and
// kSilhouetteBiasPx.
OffsetEstimate SilhouetteOffset(const LearntSphere& s, int axis);
// Plate contact from the whole track: reference rows and plate rows per frame, in frame order
// (NaN: not found). A sphere that never rests (no kMinRestingFrames consecutive frames in the
// cluster: the jump and flutter modes, a bouncing end) touches the plate only between two
// frames, and the cluster holds the frames next to its impacts, spread over the band above the
// contact: their mean leans off it by up to half the band (+0.09 to +0.12 px on POV-Ray films
// of the jump mode, stated +-0.03 before). Its impacts give the contact instead: the vertices
// where each impact's approach and rebound meet (impact_vertex.h; the arms bent by the plate's
// acceleration and by gravity, `gravity_px` = g in px per frame^2, NaN: left out), source
// "plate_contact_impacts". Where no impact draws a clear V, the source is
// "plate_contact_bounces" and the uncertainty at least the cluster's standard deviation.
// `noise_cap` (px, NaN: none): the tracker's own noise where the motion does not enter it (the
// dimer's length from frame to frame, which a rigid body keeps); the gap's noise is taken as at
// most that. On a film of separate poses the gap's second differences are the poses' changes,
// not noise: a band of three of them held every pose of a lifted sphere, and its row came out
// 3.4 px off (povray.still_plate_poses).
OffsetEstimate ContactRowOffset(const std::vector<double>& reference_rows,
                                const std::vector<double>& plate_rows, double radius_px,
                                double gravity_px = std::numeric_limits<double>::quiet_NaN(),
                                double noise_cap = std::numeric_limits<double>::quiet_NaN());
// Centre column of the appearance's outline (limb_fit.h), relative to its reference column;
// `row_offset` (reference -> centre, NaN: unknown) holds the circle's row where only one side of
// the outline shows. Its uncertainty: the outline model's (LimbFit::col_model_err) with the
// larger of the pairs' scatter and the column's jackknife error over the sphere's left-out
// groups (LearntSphere::jackknife). The pairs' scatter alone treats neighbouring rays as
// independent edges; they are not (at R = 23.75 px the 120 rays are 1.2 px apart, within the
// gradient's reach): on POV-Ray A_r 5.5 the left column spread over seven noise seeds by
// 0.058 px where the pairs stated 0.018-0.043 (see povray.noise_seeds).
OffsetEstimate LimbColumnOffset(const LearntSphere& s, double row_offset);
OffsetEstimate LimbColumnOffset(const Appearance& a, double row_offset);
// Symmetry axis of the appearance, relative to its reference column.
OffsetEstimate SymmetryColumnOffset(const Appearance& a);
// The column where the upper outline gives none: the symmetry axis and the whole outline (the
// plate reflection's boundary in it, which ends short of the rim by different amounts on the two
// sides) rest on different assumptions, each pixels wrong where its own fails; with both, their
// midpoint and half their difference in the uncertainty (source "symmetry_and_whole_outline"),
// else the symmetry alone.
OffsetEstimate ColumnWithoutTheUpperOutline(const LearntSphere& s);
// A plate-contact estimate rests on a resting sphere when at least this many frames are in its
// cluster; fewer (a sphere that only lands now and then, or never in the footage) and the
// lowest frames are flight, not contact.
inline constexpr size_t kMinRestingFrames = 5;
// A sphere with fewer than this fraction of the other's contact frames bounces while the other
// rests (drift): it takes the other's row offset (TransferOffset).
inline constexpr double kTransferBelowFraction = 0.5;
// The other sphere's offset carried over: two steel spheres under the same lights look alike,
// so the shift that registers appearance `to` onto appearance `from` (cv::findTransformECC)
// carries `from`'s offset (axis 0 column, 1 row) to `to`'s reference. Source
// "plate_contact_of_other". The uncertainty adds the registration's asymmetry (forward vs
// backward) to `from`'s.
OffsetEstimate TransferOffset(const Appearance& from, const Appearance& to,
                              const OffsetEstimate& from_offset, int axis);
// The same carried through the two outlines (limb_fit.h, row fitted): whatever bias the outline
// fit has (an edge seen a fraction of a pixel inside the rim) is common to two spheres under the
// same lights and cancels: to's offset = from's + (to's outline row - from's outline row).
// Source "plate_contact_of_other_outline". Each outline may show one side only (the far side
// dark under one-sided light): both are fitted over the same pixels, so their arcs are alike.
OffsetEstimate TransferRowByOutline(const Appearance& from, const Appearance& to,
                                    const OffsetEstimate& from_offset);
// The same with the outlines' noise measured: the uncertainty takes the larger of the two
// circle fits' and the jackknife's over the spheres' left-out groups (LearntSphere::jackknife),
// as the limb column does (LimbColumnOffset).
OffsetEstimate TransferRowByOutline(const LearntSphere& from, const LearntSphere& to,
                                    const OffsetEstimate& from_offset);
// The bouncing sphere's row from both transfers. They rest on different assumptions (the two
// appearances alike, or the two outlines alike) and each fails where its own does: light from
// one side or a soft box makes the appearances unlike (the registered row 0.11-0.17 px off on
// the POV-Ray footage), a template framed far above its centre or a faint outline defeats the
// outline fit (0.4-0.6 px off on ring_light at lower levels). `mismatch` says how unlike the
// two appearances are (AppearanceMismatch, appearance_mismatch.h). Each transfer's uncertainty
// takes its model error in quadrature: the registered one RegisteredTransferModelErr(mismatch),
// the outline one kOutlineTransferModelPx. With both, they are weighed by their inverse
// variances, the uncertainty scaled up by the ratio of their difference to its own uncertainty
// where that is above 1 (the Particle Data Group's scale factor for inconsistent measurements);
// source "plate_contact_of_other_both". With `mismatch` unknown (NaN: no jackknife), their
// midpoint and half their difference in the uncertainty. With one, that one.
OffsetEstimate CombineRowTransfers(const OffsetEstimate& registered,
                                   const OffsetEstimate& outline, double mismatch);
// The outline transfer's own error where its outlines are clear, px: measured against the truth
// on the POV-Ray films, 0.04-0.16 px (front_point 0.04, soft box 0.05, one-sided light 0.10, 0.1
// and 0.4 mm/px 0.10 and 0.15, a camera rolled 8 degrees 0.13), beyond the noise its jackknife
// states (see OutlineTransfer.TheJackknifeStatesItsNoise).
inline constexpr double kOutlineTransferModelPx = 0.1;
// Outline fits for the transfer reach Reach(kTransferOutlineMaxShiftPx, ...R, R) from the
// reference: the bouncing sphere's template is framed on its lowest frames and can sit more
// than the limb offset's reach above its centre (POV-Ray A_r 2.0, 40 frames: 4.4 px).
inline constexpr double kTransferOutlineMaxShiftPx = 6.0;
inline constexpr double kTransferOutlineMaxShiftR = 0.25;

}  // namespace dimer::tracking
