#pragma once
// The plate's top surface, as a sub-pixel row. The plate spans the whole width, so a row profile
// (mean over columns clear of the spheres) shows its top edge as the strongest step.
//
// Sub-pixel position by the coverage sum: with levels L_a above and L_b just below a straight
// edge at row y (pixel r spans [r - 1/2, r + 1/2]), a box-sampled pixel holds the fraction
// f_r = (p_r - L_a) / (L_b - L_a) of the lower side, and summing f over rows j0..j1 that bracket
// the edge gives j1 + 1/2 - y exactly: unlike interpolating a half-level crossing, it has no
// pixel locking. L_b is read three rows below the strongest step, so a lit edge band must be at
// least 4 px thick (the renderer's kPlateEdgeBandPx), or the edge a plain step.
#include <opencv2/core.hpp>

#include "tracking/plate/clipped_edge.h"
#include "tracking/plate/plate_step.h"
#include "tracking/tolerances.h"

#include <utility>
#include <vector>

namespace dimer::tracking {

// The row at column `col` of a plate edge that is at row `row` at column `ref_col` and slopes by
// `slope` rows per column (`row` itself when level). Frames and learning samples carry the three.
inline double SlopedRowAt(double row, double ref_col, double slope, double col) {
  return slope == 0 ? row : row + slope * (col - ref_col);
}

// Sub-pixel row of the strongest step of `profile` (profile[i] is the mean of row
// first_row + i), or NaN when there is no step of at least `min_step` or it is too close to the
// ends of the profile to bracket.
double EdgeRowInProfile(const std::vector<double>& profile, int first_row, double min_step);

// Acquisition: the strongest step of the per-row median over sampled columns (the median
// ignores the spheres, which cover less than half the width). Whole-pixel accuracy; NaN if no
// plate edge (no step of kPlateMinStepFraction of the frame's range).
// With `slope` (rows per column, PlateEdgeSlope) each column is read down the slope from the
// frame's centre column, and the row is the edge's there.
double FindPlateRowCoarse(const cv::Mat& frame, double slope = 0);

// The frame's horizontal edges that could be the plate's, each at its whole-pixel row (+ 1/2:
// between the two rows of the step) at the frame's centre column, read along `slope`: steps of
// the per-row median (as FindPlateRowCoarse) of at least kPlateMinStepFraction of the frame's
// range, each at least kPlateCandidateSeparationRows from a stronger one; top to bottom. The
// strongest is marked, and the one FindPlateRowCoarse takes from the image alone.
struct PlateCandidate {
  double row = 0;
  double step = 0;          // |step|, grey levels
  bool strongest = false;
  bool from_image = false;  // FindPlateRowCoarse's choice
};
std::vector<PlateCandidate> PlateCandidates(const cv::Mat& frame, double slope = 0);
inline constexpr int kPlateCandidateSeparationRows = 2 * kPlateBracketRows;

// Sub-pixel plate row near `row_guess` from the columns outside `excluded` (column intervals
// covered by the spheres, and so by their mirror images below a polished plate). Robust to the
// lighting: the columns are cut into blocks (tolerances.h, kPlateBlockColumns), each block's
// profile gives its own edge (EdgeRowInProfile) if its strongest step stands kPlateStepSigmas
// noise sigmas out (the noise measured in the band, so a dim frame still has its edge); the
// blocks whose step has the majority's sign and whose row is within kPlateInlierPx of the
// median row are averaged into one profile, whose edge is the result. A horizontal gain ramp
// only scales each block's step (not its row); a reflection, a highlight or a clipped block
// is an outlier. Where one side of the edge clips (over-exposure) its true level is unknown,
// and the row comes from ClippedEdgeRowInProfile with the camera's blur `psf_sigma_px`; its
// profile is then copied to `clipped` (when given; cleared otherwise), for the sequence to fit
// again once the clipped level is known (clipped_edge.h, SharedClippedLevel).
// NaN if fewer than kPlateMinBlocks blocks agree.
// A camera that is not level (or a tilted plate) shows the edge sloping by `slope` rows per
// column (PlateEdgeSlope): each block's profile is then read `slope` (block column - ref_col)
// rows down, to the nearest row, which lines the blocks' edges up; the row returned is the
// edge's at column `ref_col` (the fractions of a row left over are subtracted, exactly: the
// coverage sum is linear). With slope 0 (the default) nothing moves and ref_col is not used.
double RefinePlateRow(const cv::Mat& frame, double row_guess,
                      const std::vector<std::pair<double, double>>& excluded,
                      double psf_sigma_px = kPlatePsfSigmaPx,
                      ClippedEdgeProfile* clipped = nullptr, double slope = 0,
                      double ref_col = 0);

// The plate edge's slope, rows per column (> 0: descending to the right), from its column
// blocks (columns in `excluded` left out): a first robust line (Theil-Sen: the median of the
// pairwise slopes) through each block's strongest step over the whole height, then each block's
// sub-pixel row (as RefinePlateRow) in a band along that line, and a straight line through
// those, the blocks more than kPlateInlierPx off a robust line through them left out. `err`:
// the slope's standard error. NaN when fewer than kPlateMinSlopeBlocks blocks agree, or the
// edge is steeper than kPlateMaxSlope.
double PlateEdgeSlope(const cv::Mat& frame, const std::vector<std::pair<double, double>>& excluded,
                      double* err);
inline constexpr int kPlateMinSlopeBlocks = 6;
// Steeper than this (11 degrees) the plate is not the scene's horizontal edge.
inline constexpr double kPlateMaxSlope = 0.2;

}  // namespace dimer::tracking
