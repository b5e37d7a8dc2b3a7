#pragma once
// Every tolerance, margin and iteration cap of the tracking library, named once with its unit.
// They derive from two base facts: pixels are the unit of image geometry, and the spheres are
// tens of pixels across, so a few pixels of margin separate a sphere from its surroundings.
#include <algorithm>

namespace dimer::tracking {

// A reach that scales with the sphere: the larger of a floor in pixels (blur, noise, a pixel's
// own extent) and a fraction of the radius in pixels (errors that grow with the sphere's image:
// a rough centre's offset, how differently two appearances are framed). Each fraction is set so
// that at the scale the floors were tuned on (0.2 mm/px, R = 23.75 px) the floor holds.
inline double Reach(double floor_px, double per_radius, double radius_px) {
  return std::max(floor_px, per_radius * radius_px);
}

// Half-size added to the sphere radius for a measurement window, px. Must exceed the largest
// frame-to-frame prediction error (a sphere moves < 1 px per frame at 2000 frames/s), else the
// first centroid iteration sees a cut disc.
inline constexpr double kWindowMarginPx = 4.0;
// Iterative centroid: stop when the centre moves less than this between iterations, px.
// Two orders below the accuracy target (0.02 px) so convergence never shows in the error.
inline constexpr double kCentroidConvergedPx = 1e-4;
inline constexpr int kCentroidMaxIter = 12;
// Disc fit (Gauss-Newton): stop when the centre update is below this, px. From the centroid's
// start the steps fall ~100-fold per pass (0.02, 2e-4, 1e-6 px), so what is left is ~1e-6 px.
// Looser is not free: 1e-3 doubled the noise-free pixel locking of a resting sphere (0.0009 to
// 0.0022 px p-p; the plate cut makes the convergence slower there) and 3e-4 raised it to 0.0014.
inline constexpr double kFitConvergedPx = 1e-4;
inline constexpr int kFitMaxIter = 8;
// Disc fit uses pixels whose centre is within this distance of the current edge, px: the edge
// pixels carry the position information, and a band of whole pixels on both sides pins the
// two levels locally (so a non-uniform interior, e.g. a mirror sphere, matters less).
inline constexpr double kFitBandPx = 3.0;
// Pixels whose centre lies this close above the plate surface are left out, px: their extent
// (half a pixel) plus motion blur and edge-estimate error must not reach the plate.
inline constexpr double kPlateGuardPx = 1.0;
// The rod leaves a sphere along its axis: pixels in a corridor of this half-width (in units of
// the sphere radius) beyond kRodCutInsetPx inside the edge are left out, on both sides so the
// mask stays point-symmetric (a symmetric mask does not bias a centroid).
inline constexpr double kRodCorridorHalfWidthR = 0.3;
inline constexpr double kRodCutInsetPx = 2.0;
// A sphere is "found" when its weighted area is within this factor of pi R^2 (the masks remove
// at most ~25 %; a missing sphere gives ~0, a merged blob far more).
inline constexpr double kMinAreaFraction = 0.45;
inline constexpr double kMaxAreaFraction = 1.6;
// Touching spheres (A_r < ~2.2): the other sphere enters this one's window. Its disc, widened
// by this margin, is left out, px: the other's estimate (a prediction, < 1 px off, or a coarse
// detection, +-1 px) plus the motion blur of a bouncing sphere's edge.
inline constexpr double kOtherSphereMarginPx = 2.0;
// Plate edge: search band half-height around the previous row, px (plate motion is < 1 px per
// frame at 2000 frames/s; a wider band costs time only).
inline constexpr int kPlateBandHalfPx = 8;
// Columns within this distance of a sphere's edge are not used for the plate profile, px.
inline constexpr double kPlateSphereClearPx = 4.0;
// A step smaller than this fraction of the frame's dynamic range is not a plate edge
// (acquisition, FindPlateRowCoarse).
inline constexpr double kPlateMinStepFraction = 0.15;
// Sub-pixel plate edge (RefinePlateRow): the clear columns are cut into blocks of this many
// columns, each finds its own edge; the blocks whose edge has the majority's sign and lies
// within kPlateInlierPx of the median row make the profile (a gain ramp only scales a block's
// step; a reflection or a highlight makes an outlier block). At least kPlateMinBlocks blocks.
inline constexpr int kPlateBlockColumns = 16;
inline constexpr double kPlateInlierPx = 1.0;
inline constexpr int kPlateMinBlocks = 3;
// A step is an edge above kPlateStepSigmas noise sigmas (of the difference of two rows of a
// profile) and at least kPlateMinStepGreyLevels grey levels of the 8-bit scale.
inline constexpr double kPlateStepSigmas = 8.0;
inline constexpr double kPlateMinStepGreyLevels = 2.0;
// Clipped plate edge (ClippedEdgeRowInProfile). The camera's blur assumed by the tracker: a
// Gaussian of kPlatePsfSigmaPx sampled on the pixel grid (the POV-Ray footage's PSF, a focused
// lens's order of magnitude; only a clipped edge depends on it, the coverage sum does not).
// The edge row is searched every kPlateClipCoarsePx, then by golden section about the choice to
// kPlateClipTolerancePx; the clipped side's level by at most kPlateClipFitIterations
// Gauss-Newton steps.
inline constexpr double kPlatePsfSigmaPx = 0.5;
inline constexpr double kPlateClipCoarsePx = 0.05;
inline constexpr double kPlateClipTolerancePx = 1e-4;
inline constexpr int kPlateClipFitIterations = 8;
// A profile row whose mean lies within this fraction of the clip from 0 or from the clip is
// left out of the pixel noise measured for the clipped fit (its noise is cut by the clip).
inline constexpr double kPlateClipNoiseRowMargin = 0.1;
// A learnt appearance is located only where at least this fraction of its template remains
// after the frame's cuts (rod, plate, other sphere, the frame's edge).
inline constexpr double kTemplateMinMaskedFraction = 0.25;
// Following a learnt appearance quickly (sphere/fast_follow.h). Its answer must stay within
// kFollowMaxMovePx of the prediction, as ECC's from a prediction must (a prediction is < 1 px
// off at 2000 frames/s; further means a neighbouring optimum). Iterations that wander beyond
// kFollowReachPx end the quick step; the frame's patch reaches kFollowPatchMarginPx beyond the
// template: that reach and the smoothing's pixel. A solve has converged when its remainder is
// within kFollowCellFraction of a grid step of the shift it was solved at: its own cell (0.5),
// or the border it shares with the next one, where the estimate would swing between the two.
// Both images are smoothed by a Gaussian of kFollowGaussSize, ECC's residual run's
// (template_locator.cc: the appearance is nearly noise-free, the frame is not; 3 keeps the
// highlights' detail).
inline constexpr double kFollowMaxMovePx = 1.0;
inline constexpr double kFollowReachPx = 2.0;
inline constexpr int kFollowPatchMarginPx = 3;
inline constexpr double kFollowCellFraction = 0.75;
inline constexpr int kFollowGaussSize = 3;
// Acquisition: a second distance-transform peak is a sphere if at least this fraction of the
// first one (a rod or a clipped sliver gives much less).
inline constexpr double kSecondPeakFraction = 0.6;

}  // namespace dimer::tracking
