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

#include "tracking/tolerances.h"

#include <utility>
#include <vector>

namespace dimer::tracking {

// Sub-pixel row of the strongest step of `profile` (profile[i] is the mean of row
// first_row + i), or NaN when there is no step of at least `min_step` or it is too close to the
// ends of the profile to bracket.
double EdgeRowInProfile(const std::vector<double>& profile, int first_row, double min_step);

// Sub-pixel row of the strongest step of `profile` when its bright side clips at `clip` (NaN if
// the step is within three rows of the profile's ends). The clipped level is unknown, so the
// coverage sum cannot be used; what is still measured is the shape of the partly lit rows under
// a known blur. Model of a row's mean: the edge box-sampled (pixel r spans [r - 1/2, r + 1/2]),
// blurred across rows by a Gaussian of `psf_sigma_px` sampled on the pixel grid (the camera's
// blur; 0: none), read with Gaussian pixel noise `pixel_sigma` and clipped to [0, clip] (so a
// dark or clipped row's mean is bent by its cut noise: censored samples, modelled rather than
// left out). The dark level comes from the row three rows off on the dark side. For each trial
// edge row the clipped side's true level is fitted (least squares, `profile_sigma` the noise of
// a profile row), and the row minimising chi-square + 2 ln(level) is returned: the most
// probable row under a scale-invariant prior on the unknown level. When two rows are partly lit
// the chi-square fixes the row. With one (the blur's spill above an edge whose own pixel
// clips), any edge row in that pixel fits for some brighter clipped side, and the prior picks
// the least light that reaches the clip: the error is then towards the dark side, at most the
// pixel's covered part, and grows with the over-exposure (docs/BENCHMARKS.md).
double ClippedEdgeRowInProfile(const std::vector<double>& profile, int first_row, double clip,
                               double pixel_sigma, double profile_sigma, double psf_sigma_px);

// Acquisition: the strongest step of the per-row median over sampled columns (the median
// ignores the spheres, which cover less than half the width). Whole-pixel accuracy; NaN if no
// plate edge (no step of kPlateMinStepFraction of the frame's range).
double FindPlateRowCoarse(const cv::Mat& frame);

// Sub-pixel plate row near `row_guess` from the columns outside `excluded` (column intervals
// covered by the spheres, and so by their mirror images below a polished plate). Robust to the
// lighting: the columns are cut into blocks (tolerances.h, kPlateBlockColumns), each block's
// profile gives its own edge (EdgeRowInProfile) if its strongest step stands kPlateStepSigmas
// noise sigmas out (the noise measured in the band, so a dim frame still has its edge); the
// blocks whose step has the majority's sign and whose row is within kPlateInlierPx of the
// median row are averaged into one profile, whose edge is the result. A horizontal gain ramp
// only scales each block's step (not its row); a reflection, a highlight or a clipped block
// is an outlier. Where one side of the edge clips (over-exposure) its true level is unknown,
// and the row comes from ClippedEdgeRowInProfile with the camera's blur `psf_sigma_px`.
// NaN if fewer than kPlateMinBlocks blocks agree.
double RefinePlateRow(const cv::Mat& frame, double row_guess,
                      const std::vector<std::pair<double, double>>& excluded,
                      double psf_sigma_px = kPlatePsfSigmaPx);

}  // namespace dimer::tracking
