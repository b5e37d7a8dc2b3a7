#pragma once
// The plate's edge where its bright side clips (over-exposure): the clipped side's true level is
// unknown, so the coverage sum (plate_edge.h) cannot be used; what is still measured is the shape
// of the partly lit rows under a known blur.
//
// Model of a profile row's mean: the edge box-sampled (pixel r spans [r - 1/2, r + 1/2]), blurred
// across rows by a Gaussian of `psf_sigma_px` sampled on the pixel grid (the camera's blur; 0:
// none), read with Gaussian pixel noise `pixel_sigma` and clipped to [0, clip] (so a dark or
// clipped row's mean is bent by its cut noise: censored samples, modelled rather than left out).
// The dark level comes from the row three rows off on the dark side.
//
// One frame alone (ClippedEdgeRowInProfile): for each trial edge row the clipped side's level is
// fitted (least squares, `profile_sigma` the noise of a profile row), and the row minimising
// chi-square + 2 ln(level) is returned: the most probable row under a scale-invariant prior on
// the unknown level. When two rows are partly lit the chi-square fixes the row. With one (the
// blur's spill above an edge whose own pixel clips), any edge row in that pixel fits for some
// brighter clipped side, and the prior picks the least light that reaches the clip: the error is
// then towards the dark side, at most the pixel's covered part (POV-Ray over-exposed footage,
// 40 frames: 0.43 px, the edge held at the pixel's boundary while it crossed the pixel).
//
// A sequence (SharedClippedLevel, then ClippedEdgeRowAtLevel): the plate's brightness is the same
// in every frame (one lighting, one exposure), while its edge crosses the pixels as the plate
// moves. The frames where two rows are partly lit fix the level; with it known, the one lit row
// of every other frame fixes that frame's row (its level is a known fraction of the plate's).
// Each such frame brings its own row as a further unknown, so the level comes out a little low
// with noise (-0.6 % at 2 x the clip, -1.9 % at 1.2 x; rows within 0.035 px). The same frames,
// sampled at different sub-pixel phases, also fix the camera's blur, which the one-row frames
// depend on (a blur of 0.6 px read as 0.5: rows up to 0.64 px off; fitted: 0.014 px;
// bench/bench_plate_edge.cc --clipped-sequence).
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace dimer::tracking {

// A clipped edge's profile as RefinePlateRow measured it: profile[i] is the mean of row
// first_row + i over the plate's inlier columns.
struct ClippedEdgeProfile {
  std::vector<double> profile;
  int first_row = 0;
  double clip = 0;           // full scale (255 or 65535)
  double pixel_sigma = 0;    // noise of one pixel, grey levels
  int columns = 1;           // columns averaged into each profile row
  // pixel_sigma was measured on rows clear of the clip and of black; else it is the band's,
  // which the clip has cut, and the sequence's median noise is used instead.
  bool noise_measured = false;
  // A sloping edge's profile is straightened by whole rows per column block; this is what those
  // rows leave over (RefinePlateRow): subtracted from any row fitted on the profile, it gives the
  // row at the reference column.
  double row_shift = 0;
  bool valid() const { return !profile.empty(); }
};

// Sub-pixel row of the plate's step in `profile` when its bright side clips at `clip` (NaN if the
// step is within three rows of the profile's ends), the level unknown (see above).
double ClippedEdgeRowInProfile(const std::vector<double>& profile, int first_row, double clip,
                               double pixel_sigma, double profile_sigma, double psf_sigma_px);

// The row of `p`'s edge whose model, with the clipped side's true level `level` (above the dark
// side), fits best (least chi-square); NaN as above. `chi2` (if given): that fit's chi-square.
// `shared_sigma`: the pixel noise to use when `p` did not measure its own (NaN: p's).
double ClippedEdgeRowAtLevel(const ClippedEdgeProfile& p, double level, double psf_sigma_px,
                             double* chi2 = nullptr,
                             double shared_sigma = std::numeric_limits<double>::quiet_NaN());

// The clipped side's level shared by a sequence's frames.
struct ClippedLevel {
  double value = std::numeric_limits<double>::quiet_NaN();  // grey levels above the dark side
  double err = std::numeric_limits<double>::quiet_NaN();    // its standard uncertainty
  size_t informative = 0;  // frames with two partly lit rows, which fix it
  size_t used = 0;         // of those, the ones fitted (at most kClippedLevelMaxFrames)
  // The pixel noise for frames that could not measure theirs: the median of those that did.
  double pixel_sigma = std::numeric_limits<double>::quiet_NaN();
  // The camera's blur the level was fitted with (Gaussian sigma, px): fitted with it when
  // psf_fitted, else the one assumed.
  double psf_sigma = std::numeric_limits<double>::quiet_NaN();
  bool psf_fitted = false;
  bool found() const { return !std::isnan(value); }
};

// The blur is fitted only from at least this many frames with two partly lit rows (with fewer,
// a wrong blur and level can fit them: bench/bench_plate_edge.cc --clipped-sequence, 4 frames).
inline constexpr size_t kBlurFitMinFrames = 8;
// Frames with two partly lit rows used at most (evenly spread over the sequence), and at least.
inline constexpr size_t kClippedLevelMaxFrames = 64;
inline constexpr size_t kClippedLevelMinFrames = 3;
// A row is partly lit when its mean is this many profile sigmas, and this fraction of the clip,
// clear of both the dark level and the clip.
inline constexpr double kPartlyLitSigmas = 10.0;
inline constexpr double kPartlyLitClipFraction = 0.02;
// A frame keeps its own row when the shared level fits it worse than its own level by more than
// this much chi-square (its plate was brighter or dimmer: a flicker, a changed exposure).
inline constexpr double kSharedLevelMaxExtraChi2 = 25.0;

// The level maximising the likelihood of the informative frames, each at its own best row
// (profile likelihood: the sum over frames of min_y chi-square(y, level), minimised over the
// level). Not found when fewer than kClippedLevelMinFrames frames are informative. At most
// `max_frames` of them are fitted (bench/bench_plate_edge.cc --clipped-sequence measures what
// that trades).
// With `fit_blur` the camera's blur is fitted too (the same profile likelihood, over the blur as
// well), `psf_sigma_px` then only choosing the informative frames' models.
ClippedLevel SharedClippedLevel(const std::vector<const ClippedEdgeProfile*>& frames,
                                double psf_sigma_px, size_t max_frames = kClippedLevelMaxFrames,
                                bool fit_blur = false);

// Every frame's clipped edge fitted again at the shared level (and its blur): rows[i] is
// replaced by the row of *frames[i] at `level` (frames[i] null or invalid: left as it is),
// unless the frame has two partly lit rows and the shared level fits it worse than its own by
// kSharedLevelMaxExtraChi2. Returns how many rows were replaced.
size_t RefitClippedRows(const std::vector<const ClippedEdgeProfile*>& frames,
                        const ClippedLevel& level, std::vector<double>* rows);

}  // namespace dimer::tracking
