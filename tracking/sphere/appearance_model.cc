#include "tracking/sphere/appearance_model.h"

#include "tracking/sphere/appearance_mismatch.h"
#include "tracking/sphere/fast_follow.h"
#include "tracking/sphere/impact_vertex.h"
#include "tracking/sphere/limb_fit.h"
#include "common/median.h"
#include "common/parallel_for.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace dimer::tracking {
namespace {

// Template half-size beyond the radius, px: the silhouette edge and a little background.
constexpr double kTemplateMarginPx = 4.0;
// A template pixel is known when at least this fraction of the samples showed it (others were
// rod or plate there), and at least kMinSamplesPerPixel.
constexpr double kMinSeenFraction = 0.3;
constexpr int kMinSamplesPerPixel = 2;
// Fewer usable samples than this and no appearance is learnt.
constexpr size_t kMinSamples = 3;
// Registration of the samples to the mean: whole-pixel search, px (rough centres of the
// existing methods scatter by up to ~2 px on footage they do not suit, at R = 23.75 px), the
// larger of this and kLearnSearchR times the radius (Reach, tolerances.h).
constexpr int kLearnSearchPx = 4;
constexpr double kLearnSearchR = 0.16;
// Symmetry: levels above this quantile of the appearance are clipped to it (highlights).
constexpr double kSymmetryClipQuantile = 0.9;
// Symmetry from the rim: the ring [R - kRimInsidePx, R + kRimOutsidePx] holds the outline and
// the grazing reflections of the surroundings, not the lamps' highlights (which face the camera).
constexpr double kRimInsidePx = 5.0, kRimOutsidePx = 3.0;
// The plate reflection's horizon (ReflectionHorizon) is looked for in this part of the sphere.
constexpr double kHorizonHalfWidthR = 0.5, kHorizonTopR = 0.3, kHorizonBottomR = 0.7;
constexpr double kHorizonMinRatio = 4.0;
// HorizonMoves: rows about the mean horizon searched per sample; the slope (px of horizon per
// px of height) above which it moves; the least span of heights that can show it.
constexpr int kHorizonWindowPx = 4;
constexpr double kHorizonMovesPerPx = 0.005;
constexpr double kMinHeightSpanPx = 3.0;
// Re-centring's row shift (LearnAppearances): a sphere's lowest (plate - R - row) counts when
// this many of its learning samples, and this fraction of them, lie within kRestShiftSupportPx
// above it (a resting sphere's rows scatter by a few tenths of a pixel).
constexpr size_t kRestShiftMinSupport = 3;
constexpr double kRestShiftSupportFraction = 0.1;
constexpr double kRestShiftSupportPx = 1.0;
// Floor of the symmetry offset's uncertainty, px (ECC's own repeatability on a template).
constexpr double kSymmetryErrFloorPx = 0.01;

// The patch of `image` (CV_32F) with `pos` at its centre pixel, bicubic; false if it leaves the
// frame.
bool Patch(const cv::Mat& image, const Eigen::Vector2d& pos, int half, cv::Mat* out) {
  const double x0 = pos.x() - half, y0 = pos.y() - half;
  if (x0 < 1 || y0 < 1 || x0 + 2 * half + 2 > image.cols || y0 + 2 * half + 2 > image.rows) {
    return false;
  }
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, x0, 0, 1, y0);
  cv::warpAffine(image, *out, m, cv::Size(2 * half + 1, 2 * half + 1),
                 cv::INTER_CUBIC | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  return true;
}

// Leaves out of `a` every row from `row` down, the cut sloping by `slope` rows per column about
// the centre column (a plate's reflection tilts with the plate).
void CutBelow(int row, double slope, Appearance* a) {
  if (slope == 0) {
    a->mask.rowRange(std::min(row, a->mask.rows), a->mask.rows).setTo(0);
    return;
  }
  for (int x = 0; x < a->mask.cols; ++x) {
    const int first = std::clamp(row + int(std::lround(slope * (x - a->half))), 0, a->mask.rows);
    for (int y = first; y < a->mask.rows; ++y) a->mask.at<uint8_t>(y, x) = 0;
  }
}

}  // namespace

MaskContext LearningContext(const LearningSample& s, int k) {
  MaskContext ctx;
  ctx.plate_row = s.PlateRowAt(s.centre[k].x());
  ctx.plate_slope = s.plate_slope;
  const Eigen::Vector2d d = s.centre[1 - k] - s.centre[k];
  if (d.norm() > 0) {
    ctx.rod_dir = d.normalized();
    ctx.other = d;
  }
  return ctx;
}

int ReflectionHorizon(const cv::Mat& image, const cv::Mat& mask, int half, double radius_px,
                      double slope) {
  cv::Mat gy;
  cv::Sobel(image, gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  const int x0 = std::max(1, half - int(kHorizonHalfWidthR * radius_px));
  const int x1 = std::min(image.cols - 2, half + int(kHorizonHalfWidthR * radius_px));
  const int y0 = std::max(1, half - int(kHorizonTopR * radius_px));
  const int y1 = std::min(image.rows - 2, half + int(kHorizonBottomR * radius_px));
  std::vector<double> step;
  int best = -1;
  double best_step = 0;
  std::vector<double> column_steps;
  for (int y = y0; y <= y1; ++y) {
    column_steps.clear();
    for (int x = x0; x <= x1; ++x) {
      // (Along a horizon that slopes with the plate: whole rows per column.)
      const int yy = slope == 0 ? y : y + int(std::lround(slope * (x - half)));
      if (yy < 1 || yy > image.rows - 2) continue;
      if (!mask.at<uint8_t>(yy - 1, x) || !mask.at<uint8_t>(yy, x) ||
          !mask.at<uint8_t>(yy + 1, x)) {
        continue;
      }
      column_steps.push_back(gy.at<float>(yy, x));
    }
    if (int(column_steps.size()) < (x1 - x0 + 1) / 2) continue;
    step.push_back(std::abs(MedianOf(column_steps)));
    if (step.back() > best_step) {
      best_step = step.back();
      best = y;
    }
  }
  if (step.size() < 3) return -1;
  return best_step > kHorizonMinRatio * MedianOf(step) ? best : -1;
}

namespace {

// The horizon's sub-pixel row in one sample's patch at `p` (HorizonMoves); NaN where the patch
// leaves the frame or shows no step.
double HorizonRowIn(const cv::Mat& image, const Eigen::Vector2d& p, int half, int horizon,
                    double radius_px, double plate_slope) {
  const int x0 = std::max(1, half - int(kHorizonHalfWidthR * radius_px));
  const int x1 = std::min(2 * half - 1, half + int(kHorizonHalfWidthR * radius_px));
  cv::Mat patch, gy;
  if (!Patch(image, p, half, &patch)) return std::nan("");
  cv::Sobel(patch, gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  double sw = 0, swy = 0, peak = 0;
  std::vector<double> step, column_steps;
  for (int y = horizon - kHorizonWindowPx; y <= horizon + kHorizonWindowPx; ++y) {
    double across = 0;
    if (y >= 1 && y < patch.rows - 1) {
      column_steps.clear();
      for (int x = x0; x <= x1; ++x) {
        const int yy = plate_slope == 0 ? y : y + int(std::lround(plate_slope * (x - half)));
        if (yy >= 1 && yy < patch.rows - 1) column_steps.push_back(gy.at<float>(yy, x));
      }
      if (!column_steps.empty()) across = std::abs(MedianOf(column_steps));
    }
    step.push_back(across);
    peak = std::max(peak, across);
  }
  for (size_t j = 0; j < step.size(); ++j) {
    const double w = std::max(0.0, step[j] - 0.5 * peak);
    sw += w;
    swy += w * (horizon - kHorizonWindowPx + int(j));
  }
  return sw > 0 ? swy / sw : std::nan("");
}

// Whether the horizon at template row `horizon` moves within the sphere with its height above
// the plate: per sample, the horizon's sub-pixel row (centroid of the vertical step across the
// central columns, their median as in ReflectionHorizon, within kHorizonWindowPx rows) against
// the height (plate - row), fitted by a straight line; it moves when the slope exceeds
// kHorizonMovesPerPx and three standard errors over heights spanning kMinHeightSpanPx. A resting
// sphere (no span) or a renderer whose reflection is painted on the sphere (no slope) keeps its
// whole appearance.
bool HorizonMoves(const std::vector<cv::Mat>& images, const std::vector<LearningSample>& samples,
                  const std::vector<size_t>& used, const std::vector<Eigen::Vector2d>& pos,
                  int half, int horizon, double radius_px, double plate_slope, int threads) {
  // Each sample on its own (any thread count gives the same rows), gathered in order.
  std::vector<double> row(used.size(), std::nan(""));
  ParallelFor(used.size(), threads, [&](size_t i) {
    if (std::isfinite(samples[used[i]].PlateRowAt(pos[i].x()))) {
      row[i] = HorizonRowIn(images[used[i]], pos[i], half, horizon, radius_px, plate_slope);
    }
  });
  std::vector<double> h, z;
  for (size_t i = 0; i < used.size(); ++i) {
    if (!std::isfinite(row[i])) continue;
    h.push_back(row[i]);
    z.push_back(samples[used[i]].PlateRowAt(pos[i].x()) - pos[i].y());
  }
  if (h.size() < 3) return false;
  const double n = double(h.size());
  double mz = 0, mh = 0;
  for (size_t i = 0; i < h.size(); ++i) mz += z[i] / n, mh += h[i] / n;
  double szz = 0, szh = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    szz += (z[i] - mz) * (z[i] - mz);
    szh += (z[i] - mz) * (h[i] - mh);
  }
  const auto [zmin, zmax] = std::minmax_element(z.begin(), z.end());
  if (*zmax - *zmin < kMinHeightSpanPx || !(szz > 0)) return false;
  const double slope = szh / szz;
  double rss = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    const double r = h[i] - mh - slope * (z[i] - mz);
    rss += r * r;
  }
  const double se = std::sqrt(rss / std::max(1.0, n - 2) / szz);
  return std::abs(slope) > kHorizonMovesPerPx && std::abs(slope) > 3 * se;
}

// Sums of the samples' patches (times their masks) and of their masks, and how many samples;
// `sumsq` (of the patches squared) only where still background is cut (CutStillBackground).
struct PatchSums {
  cv::Mat sum, count;
  int n = 0;
  cv::Mat sumsq;
};

// Sample i's patch and its mask (CV_32F) at pos[i]; false where the patch leaves the frame.
bool MaskedPatch(const std::vector<cv::Mat>& images, const std::vector<LearningSample>& samples,
                 const std::vector<size_t>& used, const std::vector<Eigen::Vector2d>& pos,
                 size_t i, int k, const Appearance& frame, cv::Mat* patch, cv::Mat* mask_f) {
  if (!Patch(images[used[i]], pos[i], frame.half, patch)) return false;
  FrameMask(frame, pos[i], LearningContext(samples[used[i]], k)).convertTo(*mask_f, CV_32F);
  *patch = patch->mul(*mask_f);
  return true;
}

// An appearance framed by `half`, with nothing yet cut: the frame FrameMask cuts from.
Appearance Framing(int half, double radius_px, double slope) {
  Appearance all;
  all.half = half;
  all.radius_px = radius_px;
  all.horizon_slope = slope;
  all.mask = cv::Mat::ones(2 * half + 1, 2 * half + 1, CV_8U);
  return all;
}

// Leaves out of `a` the known pixels whose values spread over the samples (sd, from the sums)
// by more than `times` the median spread of its known pixels (LearnOptions::
// still_background_spread), and those within kStillBackgroundMarginPx of them.
void CutStillBackground(const PatchSums& p, double times, Appearance* a) {
  cv::Mat var;
  cv::divide(p.sumsq, cv::max(p.count, 1.0f), var);
  var -= a->image.mul(a->image);
  cv::Mat sd;
  cv::sqrt(cv::max(var, 0.0f), sd);
  std::vector<float> known;
  for (int y = 0; y < sd.rows; ++y) {
    for (int x = 0; x < sd.cols; ++x) {
      if (a->mask.at<uint8_t>(y, x)) known.push_back(sd.at<float>(y, x));
    }
  }
  if (known.empty()) return;
  std::nth_element(known.begin(), known.begin() + std::ptrdiff_t(known.size() / 2), known.end());
  const float limit = float(times) * known[known.size() / 2];
  cv::Mat cut = sd > limit;
  const int m = kStillBackgroundMarginPx;
  cv::dilate(cut, cut, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * m + 1, 2 * m + 1)));
  a->mask.setTo(0, cut);
}

// The mean appearance from its sums: pixels seen by too few samples unknown, and those of still
// background where `still_spread` > 0 (CutStillBackground); rows from `cut_row` down left out.
Appearance FromSums(const PatchSums& p, const Appearance& frame, int cut_row,
                    double still_spread = 0) {
  Appearance a = frame;
  const float min_count = float(std::max(double(kMinSamplesPerPixel), kMinSeenFraction * p.n));
  a.mask = p.count >= min_count;  // 255 / 0
  a.mask /= 255;
  if (p.n < int(kMinSamples) || cv::countNonZero(a.mask) == 0) return Appearance{};
  cv::divide(p.sum, cv::max(p.count, 1.0f), a.image);
  if (still_spread > 0) {
    CutStillBackground(p, still_spread, &a);
    if (cv::countNonZero(a.mask) == 0) return Appearance{};
  }
  const int size = 2 * frame.half + 1;
  if (cut_row >= 0 && cut_row < size) {
    CutBelow(cut_row, frame.horizon_slope, &a);
    if (cv::countNonZero(a.mask) == 0) return Appearance{};
  }
  // Unknown pixels hold the mean known level: masked everywhere, but finite and neutral.
  const cv::Scalar mean = cv::mean(a.image, a.mask);
  a.image.setTo(mean, a.mask == 0);
  return a;
}

// Every sample's MaskedPatch (empty where it has none), each on its own: taken on `threads`
// workers and summed in the samples' order afterwards, the sums are the same for any count.
struct SamplePatches {
  std::vector<cv::Mat> patch, mask_f;
};
SamplePatches MaskedPatches(const std::vector<cv::Mat>& images,
                            const std::vector<LearningSample>& samples,
                            const std::vector<size_t>& used,
                            const std::vector<Eigen::Vector2d>& pos, int k,
                            const Appearance& frame, int threads) {
  SamplePatches p{std::vector<cv::Mat>(used.size()), std::vector<cv::Mat>(used.size())};
  ParallelFor(used.size(), threads, [&](size_t i) {
    if (!MaskedPatch(images, samples, used, pos, i, k, frame, &p.patch[i], &p.mask_f[i])) {
      p.patch[i].release();
    }
  });
  return p;
}

// Mean of the samples' patches over the pixels that show the sphere; rows from `cut_row` down
// left out (the plate's reflection, appearance_model.h; -1: none), the cut sloping with the
// plate by `slope` rows per column.
Appearance Average(const std::vector<cv::Mat>& images, const std::vector<LearningSample>& samples,
                   const std::vector<size_t>& used, const std::vector<Eigen::Vector2d>& pos,
                   int k, int half, double radius_px, int cut_row, double slope,
                   double still_spread, int threads) {
  const Appearance frame = Framing(half, radius_px, slope);
  const int size = 2 * half + 1;
  PatchSums p{cv::Mat::zeros(size, size, CV_32F), cv::Mat::zeros(size, size, CV_32F), 0, {}};
  if (still_spread > 0) p.sumsq = cv::Mat::zeros(size, size, CV_32F);
  const SamplePatches patches = MaskedPatches(images, samples, used, pos, k, frame, threads);
  for (size_t i = 0; i < used.size(); ++i) {
    if (patches.patch[i].empty()) continue;
    p.sum += patches.patch[i];
    p.count += patches.mask_f[i];
    if (still_spread > 0) p.sumsq += patches.patch[i].mul(patches.patch[i]);
    ++p.n;
  }
  return FromSums(p, frame, cut_row, still_spread);
}

// s->jackknife: the appearance averaged again without each group of samples (sample i in group
// i mod groups), at the positions and with the cut it was averaged at. Each is the whole sum
// less its group's, so the patches are taken once.
void LeaveGroupsOut(const std::vector<cv::Mat>& images, const std::vector<LearningSample>& samples,
                    const std::vector<size_t>& used, int k, int max_groups,
                    bool still_background, int threads, LearntSphere* s) {
  s->jackknife.clear();
  const Appearance& a = s->appearance;
  if (!a.valid() || s->averaged.size() != used.size() || max_groups < 3) return;
  const size_t groups = std::min(size_t(max_groups), used.size());
  const Appearance frame = Framing(a.half, a.radius_px, a.horizon_slope);
  const int size = 2 * a.half + 1;
  const auto zeros = [&] {
    return PatchSums{cv::Mat::zeros(size, size, CV_32F), cv::Mat::zeros(size, size, CV_32F), 0,
                     {}};
  };
  PatchSums whole = zeros();
  std::vector<PatchSums> group(groups);
  for (PatchSums& g : group) g = zeros();
  const SamplePatches patches =
      MaskedPatches(images, samples, used, s->averaged, k, frame, threads);
  for (size_t i = 0; i < used.size(); ++i) {
    if (patches.patch[i].empty()) continue;
    const cv::Mat& patch = patches.patch[i];
    const cv::Mat& mask_f = patches.mask_f[i];
    PatchSums& g = group[i % groups];
    g.sum += patch;
    g.count += mask_f;
    ++g.n;
    whole.sum += patch;
    whole.count += mask_f;
    ++whole.n;
  }
  for (const PatchSums& g : group) {
    const PatchSums rest{whole.sum - g.sum, whole.count - g.count, whole.n - g.n, {}};
    Appearance j = FromSums(rest, frame, s->cut_row);
    // The pixels the appearance left out as still background stay out of its jackknife's.
    if (j.valid() && still_background) {
      j.mask &= a.mask;
      j.image.setTo(cv::mean(j.image, j.mask), j.mask == 0);
    }
    s->jackknife.push_back(j);
  }
}

}  // namespace

namespace {

// How the last pass of LearnOne registers the samples to the final mean.
enum class LastPass {
  kEcc,    // ECC alone: these positions become the offsets and decide the horizon cut
  kQuick,  // the quick step, as the earlier passes (RegisterWithEcc can redo it with ECC)
};

// Registers every sample to appearance `a` from `pos`: the whole-pixel search about it, then the
// quick step from its peak (fast_follow.h; ECC where it fails), or with `ecc_only` ECC alone.
// Each sample on its own, so any thread count gives the same positions.
void RegisterSamples(const std::vector<LearningSample>& samples, const std::vector<size_t>& used,
                     int k, const Appearance& a, double radius_px, bool ecc_only,
                     const LearnOptions& learn, std::vector<Eigen::Vector2d>* pos) {
  const int search_px = LearnSearchPx(radius_px);
  const FollowModel quick = ecc_only ? FollowModel{} : PrepareFollow(a);
  ParallelFor(used.size(), learn.threads, [&](size_t i) {
    const Located l =
        FollowAppearance(samples[used[i]].image, a, quick, (*pos)[i],
                         LearningContext(samples[used[i]], k), FollowStop{}, EccStop{}, search_px);
    if (l.ok) (*pos)[i] = l.position;
  });
}

// The rows of the samples flagged in `on_plate` (indexed as `samples`; empty: none) set by the
// plate under them (LearnOptions::rows_on_plate): the plate's row less the flagged samples'
// median gap between plate and row.
void PlaceRowsOnPlate(const std::vector<LearningSample>& samples, const std::vector<size_t>& used,
                      const std::vector<uint8_t>& on_plate, std::vector<Eigen::Vector2d>* pos) {
  if (on_plate.size() != samples.size()) return;
  std::vector<double> gaps;
  for (size_t i = 0; i < used.size(); ++i) {
    if (!on_plate[used[i]]) continue;
    const double plate = samples[used[i]].PlateRowAt((*pos)[i].x());
    if (std::isfinite(plate)) gaps.push_back(plate - (*pos)[i].y());
  }
  if (gaps.empty()) return;
  const double gap = MedianOf(gaps);
  for (size_t i = 0; i < used.size(); ++i) {
    if (!on_plate[used[i]]) continue;
    const double plate = samples[used[i]].PlateRowAt((*pos)[i].x());
    if (std::isfinite(plate)) (*pos)[i].y() = plate - gap;
  }
}

// Learns sphere k's appearance from `start` positions (one per used sample): kLearnPasses of
// averaging and registration to the mean (RegisterSamples). Invalid appearance if too few
// samples. The last pass's registration changes no appearance, only s->registered: with
// LastPass::kEcc, ECC alone there: with the quick step there the quarter-light POV-Ray film's
// centres scattered 0.27-0.39 px about the truth, with ECC 0.07-0.11 (povray.precision):
// HorizonMoves, which reads these positions, then cut that film's reflection out of its
// appearances.
void LearnOne(const std::vector<cv::Mat>& images, const std::vector<LearningSample>& samples,
              const std::vector<size_t>& used, int k, int half, double radius_px,
              int cut_row, std::vector<Eigen::Vector2d> pos, const LearnOptions& learn,
              LastPass last, LearntSphere* s) {
  Appearance a;
  for (int pass = 0; pass <= learn.passes; ++pass) {
    a = Average(images, samples, used, pos, k, half, radius_px, cut_row, learn.plate_slope,
                learn.still_background_spread, learn.threads);
    if (!a.valid()) return;
    s->averaged = pos;
    RegisterSamples(samples, used, k, a, radius_px,
                    pass == learn.passes && last == LastPass::kEcc, learn, &pos);
    PlaceRowsOnPlate(samples, used, learn.rows_on_plate[size_t(k)], &pos);
  }
  s->appearance = a;
  s->registered = pos;
  s->cut_row = cut_row;
  s->jackknife.clear();
}

// The last pass of a LearnOne made with LastPass::kQuick, made again with ECC: s->registered
// as LastPass::kEcc gives.
void RegisterWithEcc(const std::vector<LearningSample>& samples, const std::vector<size_t>& used,
                     int k, const LearnOptions& learn, LearntSphere* s) {
  std::vector<Eigen::Vector2d> pos = s->averaged;
  RegisterSamples(samples, used, k, s->appearance, s->appearance.radius_px, true, learn, &pos);
  s->registered = pos;
}

}  // namespace

int LearnSearchPx(double radius_px) {
  return int(std::lround(Reach(kLearnSearchPx, kLearnSearchR, radius_px)));
}

namespace {

// The learning frames where both spheres were found, as float images (indices into samples).
struct LearningSet {
  const std::vector<LearningSample>& samples;
  const LearnOptions& learn;
  std::vector<cv::Mat> images;
  std::vector<size_t> used;
};

// Each sphere's column shift from the wide template's outline (limb_fit.h) and, when asked and
// the two spheres agree, the radius from the outline.
std::array<double, 2> OutlineColumnShifts(const std::array<LearntSphere, 2>& out, bool fit_radius,
                                          double search, double* radius_px,
                                          bool* radius_from_outline) {
  std::array<double, 2> col_shift{0, 0};
  std::vector<double> radii;
  for (int k = 0; k < 2; ++k) {
    LimbFitOptions lo;
    lo.radius_px = *radius_px;
    lo.fit_radius = fit_radius;
    lo.max_shift_px = search;
    const LimbFit limb = FitLimb(out[k].appearance, lo);
    if (!limb.ok) continue;
    col_shift[k] = limb.centre.x();
    radii.push_back(limb.radius_px);
  }
  if (fit_radius && radii.size() == 2 &&
      std::abs(radii[0] - radii[1]) <= kOutlineRadiusAgreement * 0.5 * (radii[0] + radii[1])) {
    *radius_px = 0.5 * (radii[0] + radii[1]);
    if (radius_from_outline) *radius_from_outline = true;
  }
  return col_shift;
}

// Each sphere's lowest (plate - R - row) that enough of its samples support (kRestShift*): a
// registration that failed in one learning frame (17 px below the resting cluster on a 200-frame
// under-exposed film, and the template then framed 17 px off) is no sphere sinking into the
// plate. Such a cluster is a rest only where few samples lie clearly below it: in the jump mode
// the flights' samples bunch at some height above the landings (5.5 px on the A_r 3.9 mirror-lit
// jump of bench/auto_choice.sh, whose template then lost its top:
// TemplateLearning.CentresTheReferenceOnAJumpFilm), and the shift is then the second lowest
// sample (a landing, one failed registration passed over). The smallest over the spheres that
// rest; over the others where none does; 0 without any sample.
double RestingRowShift(const LearningSet& set, const std::array<LearntSphere, 2>& out,
                       double radius_px) {
  double rest = std::numeric_limits<double>::infinity();
  double landing = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    std::vector<double> g;
    for (size_t i = 0; i < set.used.size(); ++i) {
      const LearningSample& sample = set.samples[set.used[i]];
      const double v = sample.PlateRowAt(out[k].registered[i].x()) -
                       radius_px * std::hypot(1.0, sample.plate_slope) - out[k].registered[i].y();
      if (std::isfinite(v)) g.push_back(v);
    }
    if (g.empty()) continue;
    std::sort(g.begin(), g.end());
    const size_t support = std::max(kRestShiftMinSupport,
                                    size_t(std::ceil(kRestShiftSupportFraction * double(g.size()))));
    const double cluster = LowestSupported(g, kRestShiftSupportPx, support);
    // Samples clearly below the cluster, counted only where there is one (g is sorted).
    const bool rests =
        std::isfinite(cluster) &&
        std::lower_bound(g.begin(), g.end(), cluster - kRestShiftSupportPx) - g.begin() <
            std::ptrdiff_t(kRestShiftMinSupport);
    if (rests) {
      rest = std::min(rest, cluster);
    } else {
      landing = std::min(landing, g[std::min<size_t>(1, g.size() - 1)]);
    }
  }
  if (std::isfinite(rest)) return rest;
  return std::isfinite(landing) ? landing : 0.0;
}

// The whole outline's column offset of each final appearance (an offset source).
void MeasureWholeOutlines(double radius_px, std::array<LearntSphere, 2>* out) {
  for (int k = 0; k < 2; ++k) {
    LimbFitOptions lo;
    lo.radius_px = radius_px;
    lo.max_shift_px = Reach(kLimbOffsetMaxPx, kLimbOffsetMaxR, radius_px);
    const LimbFit whole = FitLimb((*out)[k].appearance, lo);
    if (whole.ok) {
      (*out)[k].whole_outline_col = OffsetEstimate{whole.centre.x(), whole.centre_err.x(),
                                                   size_t(whole.rays), "whole_outline"};
    }
  }
}

// The plate's reflection is left out of both appearances when the horizon of either moves
// with its height (HorizonMoves): the same scene and lights make both spheres' reflections
// alike, and the one that rests shows no motion to measure. Returns the appearances to keep
// (`out`, or both cut above the horizon); empty ones when a cut appearance cannot be learnt.
std::array<LearntSphere, 2> CutAtMovingHorizon(const LearningSet& set,
                                               const std::array<LearntSphere, 2>& out,
                                               const std::array<std::vector<Eigen::Vector2d>, 2>& start,
                                               int half, double radius_px) {
  const auto& [samples, learn, images, used] = set;
  std::array<int, 2> horizon{-1, -1};
  bool moves = false;
  for (int k = 0; k < 2; ++k) {
    const Appearance& a = out[k].appearance;
    horizon[k] = ReflectionHorizon(a.image, a.mask, a.half, radius_px, learn.plate_slope);
    moves = moves || (horizon[k] >= 0 && HorizonMoves(images, samples, used, out[k].registered,
                                                      a.half, horizon[k], radius_px,
                                                      learn.plate_slope, learn.threads));
  }
  std::array<LearntSphere, 2> cut = out;
  for (int k = 0; k < 2; ++k) {
    if (horizon[k] < 0) continue;
    // The quick step's positions for HorizonMoves below; ECC's only if the cut is kept.
    LearnOne(images, samples, used, k, half, radius_px,
             std::max(0, horizon[k] - HorizonGuard(radius_px)), start[k], learn, LastPass::kQuick,
             &cut[k]);
    if (!cut[k].appearance.valid()) return {};
  }
  // Registered with the whole appearance, a sphere follows its own reflection as much as its
  // outline and highlights where the reflection is most of what it shows (a lens blurring by
  // 2 px: the outline and the highlights are faint), and the horizon barely moves against such
  // positions. Measured against the positions the cut appearance registers, which nothing of
  // the reflection pulls, it does (POV-Ray defocus_2px).
  for (int k = 0; k < 2 && !moves; ++k) {
    moves = horizon[k] >= 0 && HorizonMoves(images, samples, used, cut[k].registered,
                                            cut[k].appearance.half, horizon[k], radius_px,
                                            learn.plate_slope, learn.threads);
  }
  if (!moves) return out;
  for (int k = 0; k < 2; ++k) {
    if (horizon[k] >= 0) RegisterWithEcc(samples, used, k, learn, &cut[k]);
  }
  return cut;
}

// The least height of s's registered reference points above the plate under them over its
// samples, px (Appearance::lowest_gap_px); NaN where no sample has a plate row.
double LowestGap(const std::vector<LearningSample>& samples, const LearntSphere& s) {
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (size_t j = 0; j < s.samples.size() && j < s.registered.size(); ++j) {
    const double gap = samples[s.samples[j]].PlateRowAt(s.registered[j].x()) - s.registered[j].y();
    if (std::isfinite(gap) && !(gap >= lowest)) lowest = gap;
  }
  return lowest;
}

}  // namespace

std::array<LearntSphere, 2> LearnAppearances(const std::vector<LearningSample>& samples,
                                             double radius_px, bool recentre, bool fit_radius,
                                             bool* radius_from_outline,
                                             const LearnOptions& learn) {
  if (radius_from_outline) *radius_from_outline = false;
  std::array<LearntSphere, 2> out;
  LearningSet set{samples, learn, std::vector<cv::Mat>(samples.size()), {}};
  for (size_t j = 0; j < samples.size(); ++j) {
    if (!samples[j].found[0] || !samples[j].found[1]) continue;
    samples[j].image.convertTo(set.images[j], CV_32F);
    set.used.push_back(j);
  }
  const std::vector<cv::Mat>& images = set.images;
  const std::vector<size_t>& used = set.used;
  if (used.size() < kMinSamples || !(radius_px > 0)) return out;
  // Footage of silhouettes: the rough centres are right, the template is framed around them.
  // Otherwise they can be pixels off (the visible part of a front-lit steel sphere is its lower
  // half; highlight seeds sit where the lamps are reflected), and so can the radius, and a
  // template framed around them would cut the sphere and misplace the rod and plate cuts: a
  // first, wider template is learnt, its outline (limb_fit.h) gives each sphere's column shift
  // and, if asked, the radius; the plate contact of the sphere that rests in the learning frames
  // gives the row shift (no sphere sinks below plate - R, so the smallest (plate - R - row) over
  // both spheres); both appearances are then learnt again around the rough centres so shifted.
  // The final offsets are estimated on the whole track (appearance_model.h). The final
  // appearances leave out the plate's reflection where its horizon moves (HorizonGuard).
  const double wide_radius = fit_radius ? kRecentreRadiusHigh * radius_px : radius_px;
  const double recentre_search = Reach(kRecentreSearchPx, kRecentreSearchR, radius_px);
  const int half = int(std::ceil((recentre ? wide_radius + recentre_search : radius_px) +
                                 kTemplateMarginPx));
  for (int k = 0; k < 2; ++k) {
    out[k].samples = used;
    for (size_t j : used) out[k].rough.push_back(samples[j].centre[k]);
    // Recentred, these positions are only the final LearnOne's start (after its own search
    // and passes) and RestingRowShift's, which clusters them to a pixel: the quick step's
    // positions do for them (ECC there costs 1/3 of the learning's CPU, bench_track_e2e;
    // povray.precision holds either way, and fine_scale and pincushion_lens sit at the 0.1 px
    // target whichever registers here: tests/tracking/CMakeLists.txt).
    LearnOne(images, samples, used, k, half, radius_px, -1, out[k].rough, learn,
             recentre ? LastPass::kQuick : LastPass::kEcc, &out[k]);
    if (!out[k].appearance.valid()) return {};
  }
  if (!recentre) return out;
  const std::array<double, 2> col_shift = OutlineColumnShifts(
      out, fit_radius, recentre_search, &radius_px, radius_from_outline);
  const double shift = RestingRowShift(set, out, radius_px);
  const int final_half = int(std::ceil(radius_px + kTemplateMarginPx));
  std::array<std::vector<Eigen::Vector2d>, 2> start;
  for (int k = 0; k < 2; ++k) {
    start[k] = out[k].registered;
    for (Eigen::Vector2d& p : start[k]) p += Eigen::Vector2d(col_shift[k], shift);
    LearnOne(images, samples, used, k, final_half, radius_px, -1, start[k], learn, LastPass::kEcc,
             &out[k]);
    if (!out[k].appearance.valid()) return {};
  }
  MeasureWholeOutlines(radius_px, &out);
  std::array<LearntSphere, 2> learnt = CutAtMovingHorizon(set, out, start, final_half, radius_px);
  if (!learnt[0].appearance.valid()) return {};
  for (int k = 0; k < 2; ++k) {
    LeaveGroupsOut(images, samples, used, k, learn.jackknife_groups,
                   learn.still_background_spread > 0, learn.threads, &learnt[k]);
    learnt[k].appearance.lowest_gap_px = LowestGap(samples, learnt[k]);
  }
  return learnt;
}

OffsetEstimate SilhouetteOffset(const LearntSphere& s, int axis) {
  OffsetEstimate e;
  e.source = "silhouette";
  std::vector<double> d;
  for (size_t i = 0; i < s.rough.size(); ++i) d.push_back(s.rough[i](axis) - s.registered[i](axis));
  if (d.empty()) return OffsetEstimate{};
  e.value = MedianOf(d);
  std::vector<double> dev;
  for (double v : d) dev.push_back(std::abs(v - e.value));
  // Standard error of a median: 1.2533 sigma / sqrt(n), sigma = 1.4826 MAD; and the silhouette
  // centroid's own bias, which no number of frames averages away.
  e.err = std::hypot(1.2533 * 1.4826 * MedianOf(dev) / std::sqrt(double(d.size())),
                     kSilhouetteBiasPx);
  e.n = d.size();
  return e;
}

namespace {

// The contact from the impacts' vertices (impact_vertex.h): those within kContactBandPx of the
// lowest cluster of vertices (a sphere that comes close to a plate falling away faster than g,
// Gamma > 1, draws a V-like curve above the contact), weighed by their inverse variances, the
// uncertainty scaled up by sqrt(chi^2 / (n - 1)) where the vertices scatter more than they
// state. n counts the frames of their arms.
OffsetEstimate ImpactContact(const std::vector<ImpactVertex>& impacts) {
  std::vector<double> values;
  for (const ImpactVertex& v : impacts) values.push_back(v.value);
  std::sort(values.begin(), values.end());
  std::vector<double> low;
  for (double x : values) {
    if (x > values.front() + kContactBandPx) break;
    low.push_back(x);
  }
  const double centre = low[low.size() / 2];
  double sw = 0, swx = 0;
  std::vector<const ImpactVertex*> used;
  for (const ImpactVertex& v : impacts) {
    if (std::abs(v.value - centre) > kContactBandPx) continue;
    const double w = 1.0 / (v.err * v.err);
    sw += w;
    swx += w * v.value;
    used.push_back(&v);
  }
  OffsetEstimate e;
  e.source = "plate_contact_impacts";
  e.value = swx / sw;
  e.err = std::sqrt(1.0 / sw);
  if (used.size() > 1) {
    double chi2 = 0;
    for (const ImpactVertex* v : used) chi2 += std::pow((v->value - e.value) / v->err, 2);
    e.err *= std::max(1.0, std::sqrt(chi2 / double(used.size() - 1)));
  }
  e.n = used.size() * 2 * kImpactArmFrames;
  return e;
}

// The V's of `gap` (ImpactVertices) with an arm that leaves the resting cluster's band over its
// frames. One whose arms both stay within it is no impact at the band's resolution: a resting
// sphere's gap wiggles by the tracker's own error, and where that error is smooth and the noise
// lower still, the slope test alone takes 0.02 px V's (the quick step on a resting sphere:
// RunTrack.AutoStatesItsChoiceOnStderrAndInTheFileWithTheTemplatesOffsets).
std::vector<ImpactVertex> ImpactsLeavingTheBand(const std::vector<double>& gap, double noise,
                                                const std::vector<double>& bend, double band) {
  std::vector<ImpactVertex> impacts = ImpactVertices(gap, noise, bend);
  std::erase_if(impacts, [band](const ImpactVertex& v) {
    return std::max(-v.approach, v.rebound) * kImpactArmFrames <= band;
  });
  return impacts;
}

}  // namespace

OffsetEstimate ContactRowOffset(const std::vector<double>& reference_rows,
                                const std::vector<double>& plate_rows, double radius_px,
                                double gravity_px, double noise_cap) {
  OffsetEstimate e;
  e.source = "plate_contact";
  std::vector<double> series(reference_rows.size());  // the same in frame order, NaN kept
  std::vector<double> gap;  // plate - R - reference row: the offset if the sphere rests
  for (size_t i = 0; i < reference_rows.size(); ++i) {
    series[i] = plate_rows[i] - radius_px - reference_rows[i];
    if (std::isfinite(series[i])) gap.push_back(series[i]);
  }
  if (gap.empty() || !(radius_px > 0)) return OffsetEstimate{0, NAN, 0, "none"};
  // gap = plate - R - (row + offset) >= 0 in every frame, = 0 while resting: the offset is the
  // lower edge of (plate - R - row), where the resting frames cluster. The cluster is the frames
  // within a band of its centre: kContactBandPx, or kContactBandNoise times the gap's noise
  // where that is wider. Its centre is found in steps: the median of the values within the band
  // of the lowest, then the mean over a window of +-band about it, moved to that mean until it
  // settles (symmetric about the cluster, so the noise of the plate row and of the position does
  // not bias it; a single low outlier only moves the first window). A resting sphere's gap
  // scattering by 0.24 px (POV-Ray's one-sided light at 0.4 mm/px) put the lowest values 0.8 px
  // below its level, and one fixed window of 0.3 px about them found there a cluster of seven.
  // The window never rises past kContactCeilingBands bands above the lowest value: there a
  // sphere that never rests spends its flights, slowest at their tops.
  double noise = GapNoise(series);
  if (noise_cap > 0 && noise > noise_cap) noise = noise_cap;
  const double band =
      std::isfinite(noise) ? std::max(kContactBandPx, kContactBandNoise * noise) : kContactBandPx;
  std::sort(gap.begin(), gap.end());
  const double ceiling = gap.front() + kContactCeilingBands * band;
  std::vector<double> low;
  for (double g : gap) {
    if (g > gap.front() + band) break;
    low.push_back(g);
  }
  double centre = low[low.size() / 2];
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (int step = 0; step < kContactWindowSteps; ++step) {
    sum = 0, sum2 = 0, n = 0;
    for (double g : gap) {
      if (std::abs(g - centre) > band || g > ceiling) continue;
      sum += g;
      sum2 += g * g;
      ++n;
    }
    const double mean = sum / double(n);
    if (std::abs(mean - centre) <= kContactWindowSettledPx) break;
    centre = mean;
  }
  // The impacts: a V's bottom passes through the cluster too, for as many frames as it takes to
  // cross the band (5 at 0.12 px a frame), and is no rest.
  const std::vector<ImpactVertex> impacts =
      ImpactsLeavingTheBand(series, noise, GapBend(plate_rows, gravity_px), band);
  std::vector<bool> impact_frame(series.size(), false);
  for (const ImpactVertex& v : impacts) impact_frame[v.frame] = true;
  // The longest run of consecutive frames in the cluster without an impact in it: a resting
  // sphere stays there.
  size_t run = 0, longest_run = 0;
  bool run_has_impact = false;
  for (size_t i = 0; i <= series.size(); ++i) {
    if (i < series.size() && std::abs(series[i] - centre) <= band) {  // NaN: ends it
      ++run;
      run_has_impact = run_has_impact || impact_frame[i];
      continue;
    }
    if (!run_has_impact) longest_run = std::max(longest_run, run);
    run = 0;
    run_has_impact = false;
  }
  if (longest_run < kMinRestingFrames && !impacts.empty()) return ImpactContact(impacts);
  e.n = n;
  e.value = sum / double(n);
  const double var = n > 1 ? std::max(0.0, (sum2 - sum * sum / double(n)) / double(n - 1)) : 0.0;
  // Standard error of the mean, floored at a tenth of the window (a few frames near the edge of
  // the window can move the mean by that much).
  e.err = std::max(std::sqrt(var / double(n)), kContactBandPx / 10.0);
  if (longest_run < kMinRestingFrames) {
    e.source = "plate_contact_bounces";
    e.err = std::max(e.err, std::sqrt(var));
  }
  return e;
}

namespace {

// Axis of mirror symmetry of `image` about its centre column (relative to it), by registering
// the image to its own mirror image: A_f(x) = A(2 h - x); A_f(x + t) = A(x) gives axis -t/2.
bool SymmetryAxis(const cv::Mat& image, const cv::Mat& mask, double* axis) {
  cv::Mat flipped, flipped_mask;
  cv::flip(image, flipped, 1);
  cv::flip(mask, flipped_mask, 1);
  Eigen::Vector2d t(0, 0);
  if (!RegisterTranslation(image, flipped, flipped_mask & mask, &t)) return false;
  *axis = -0.5 * t.x();
  return std::isfinite(*axis);
}

}  // namespace

OffsetEstimate SymmetryColumnOffset(const Appearance& a) {
  OffsetEstimate e;
  if (!a.valid()) return OffsetEstimate{0, NAN, 0, "none"};
  std::vector<float> levels;
  for (int y = 0; y < a.image.rows; ++y) {
    for (int x = 0; x < a.image.cols; ++x) {
      if (a.mask.at<uint8_t>(y, x)) levels.push_back(a.image.at<float>(y, x));
    }
  }
  auto q = levels.begin() + std::ptrdiff_t(kSymmetryClipQuantile * double(levels.size() - 1));
  std::nth_element(levels.begin(), q, levels.end());
  const cv::Mat clipped = cv::min(a.image, *q);
  cv::Mat rim = cv::Mat::zeros(a.mask.size(), CV_8U);
  cv::circle(rim, cv::Point(a.half, a.half), int(std::lround(a.radius_px + kRimOutsidePx)),
             cv::Scalar(1), cv::FILLED);
  cv::circle(rim, cv::Point(a.half, a.half), int(std::lround(a.radius_px - kRimInsidePx)),
             cv::Scalar(0), cv::FILLED);
  double at_rim = 0, whole = 0;
  if (!SymmetryAxis(clipped, a.mask & rim, &at_rim)) return OffsetEstimate{0, NAN, 0, "none"};
  if (!SymmetryAxis(clipped, a.mask, &whole)) whole = at_rim;
  e.value = at_rim;
  // Where the rim and the whole (clipped) appearance disagree, the lighting is not symmetric:
  // half the difference is the uncertainty.
  e.err = std::max(kSymmetryErrFloorPx, 0.5 * std::abs(whole - at_rim));
  e.n = 1;
  e.source = "symmetry";
  return e;
}

// The appearance above its plate reflection's horizon (less HorizonGuard), where the outline
// is the sphere's own and not a reflection's boundary; itself when it shows no horizon (a cut
// template, a matte or backlit sphere).
Appearance UpperPart(const Appearance& a) {
  const int horizon = ReflectionHorizon(a.image, a.mask, a.half, a.radius_px, a.horizon_slope);
  if (horizon < 0) return a;
  Appearance u = a;
  u.mask = a.mask.clone();
  CutBelow(std::max(0, horizon - HorizonGuard(a.radius_px)), a.horizon_slope, &u);
  return u;
}

namespace {

// The outline fit LimbColumnOffset makes, on the part of `a_whole` above its reflection.
LimbFit UpperLimb(const Appearance& a_whole, double row_offset) {
  const Appearance a = UpperPart(a_whole);
  LimbFitOptions lo;
  lo.radius_px = a.radius_px;
  lo.max_shift_px = Reach(kLimbOffsetMaxPx, kLimbOffsetMaxR, a.radius_px);
  lo.row = row_offset;
  return FitLimb(a, lo);
}

// The pairs' model uncertainty (LimbFit::col_model_err: half their difference from the circle
// fit) where the symmetry axis, resting on a third assumption (the lights in the camera's
// vertical plane), stands nearer the pairs: half the pairs' difference from it, with its own
// uncertainty. Two of three estimates that agree show the third's assumption failed, not the
// pairs': on POV-Ray cluttered_backdrop the backdrop's edges drew the circle fit 1.0-1.5 px
// aside while the pairs and the axis agreed within 0.02 px and the truth within 0.05, and the
// stated column uncertainty was 0.48-0.70 px (povray.coverage.cluttered_backdrop holds it
// under 0.3 px and over the bias). Where the axis stands further (lamps to one side:
// front_softbox's lies 0.7-1.1 px the other way), the circle's difference stays.
double PairsModelError(const LimbFit& limb, const OffsetEstimate& symmetry) {
  if (limb.pairs < kLimbMinPairs || symmetry.source != "symmetry" || !std::isfinite(symmetry.err)) {
    return limb.col_model_err;
  }
  const double by_axis = std::hypot(0.5 * std::abs(limb.centre.x() - symmetry.value), symmetry.err);
  return std::min(limb.col_model_err, by_axis);
}

OffsetEstimate LimbEstimate(const LimbFit& limb) {
  if (!limb.ok) return OffsetEstimate{0, NAN, 0, "none"};
  OffsetEstimate e;
  e.value = limb.centre.x();
  e.err = limb.centre_err.x();
  e.n = size_t(limb.rays);
  e.source = "limb";
  return e;
}

}  // namespace

double JackknifeError(const std::vector<double>& values) {
  double sum = 0;
  size_t g = 0;
  for (double v : values) {
    if (std::isfinite(v)) sum += v, ++g;
  }
  if (g < 3) return NAN;
  const double mean = sum / double(g);
  double ss = 0;
  for (double v : values) {
    if (std::isfinite(v)) ss += (v - mean) * (v - mean);
  }
  return std::sqrt(double(g - 1) / double(g) * ss);
}

OffsetEstimate LimbColumnOffset(const Appearance& a_whole, double row_offset) {
  return LimbEstimate(UpperLimb(a_whole, row_offset));
}

OffsetEstimate LimbColumnOffset(const LearntSphere& s, double row_offset) {
  const LimbFit limb = UpperLimb(s.appearance, row_offset);
  OffsetEstimate e = LimbEstimate(limb);
  if (e.source == "none" || s.jackknife.empty()) return e;
  std::vector<double> columns;
  for (const Appearance& a : s.jackknife) {
    const LimbFit f = a.valid() ? UpperLimb(a, row_offset) : LimbFit{};
    columns.push_back(f.ok ? f.centre.x() : NAN);
  }
  const double noise = JackknifeError(columns);
  if (std::isfinite(noise)) {
    e.err = std::hypot(std::max(limb.col_scatter_err, noise),
                       PairsModelError(limb, SymmetryColumnOffset(s.appearance)));
  }
  return e;
}

namespace {

// Two estimates of one offset resting on different assumptions, each wrong where its own fails:
// their midpoint, with half their difference added to the larger uncertainty (the truth may be
// at either end). `a`'s frame count is kept.
OffsetEstimate Midway(const OffsetEstimate& a, const OffsetEstimate& b, const char* source) {
  OffsetEstimate e = a;
  const double half = 0.5 * (b.value - a.value);
  e.value += half;
  e.err = std::hypot(std::max(a.err, b.err), half);
  e.source = source;
  return e;
}

}  // namespace

OffsetEstimate ColumnWithoutTheUpperOutline(const LearntSphere& s) {
  const OffsetEstimate e = SymmetryColumnOffset(s.appearance);
  if (e.source == "none" || s.whole_outline_col.source == "none") return e;
  return Midway(e, s.whole_outline_col, "symmetry_and_whole_outline");
}

namespace {

// The two outline fits of TransferRowByOutline; false where either fails.
bool OutlineRows(const Appearance& from, const Appearance& to, LimbFit* a, LimbFit* b) {
  if (!from.valid() || !to.valid() || from.image.size() != to.image.size()) return false;
  // Both outlines over the same pixels (the rod's side of each and the lower cuts of both left
  // out of both): the arcs fitted are the same, and so is their bias.
  Appearance f = UpperPart(from), t = UpperPart(to);
  // A new matrix: assigned to f.mask, the expression would be written into the matrix f shares
  // with `from` wherever UpperPart returned it whole, and the learnt appearance lose pixels.
  const cv::Mat common = f.mask & t.mask;
  f.mask = common;
  t.mask = common;
  LimbFitOptions lo;
  lo.radius_px = from.radius_px;
  lo.max_shift_px =
      Reach(kTransferOutlineMaxShiftPx, kTransferOutlineMaxShiftR, from.radius_px);
  lo.one_side_ok = true;
  *a = FitLimb(f, lo);
  *b = FitLimb(t, lo);
  return a->ok && b->ok;
}

}  // namespace

OffsetEstimate TransferRowByOutline(const LearntSphere& from, const LearntSphere& to,
                                    const OffsetEstimate& from_offset) {
  OffsetEstimate e = TransferRowByOutline(from.appearance, to.appearance, from_offset);
  if (e.source == "none" || from.jackknife.size() != to.jackknife.size()) return e;
  // Group j leaves the same learning frames out of both spheres (both learn from the frames
  // that show both): the difference's spread over the groups is its noise, neighbouring edges'
  // correlation included.
  std::vector<double> differences;
  for (size_t j = 0; j < from.jackknife.size(); ++j) {
    LimbFit a, b;
    differences.push_back(OutlineRows(from.jackknife[j], to.jackknife[j], &a, &b)
                              ? b.centre.y() - a.centre.y()
                              : NAN);
  }
  const double noise = JackknifeError(differences);
  if (std::isfinite(noise)) {
    const double fits = std::sqrt(e.err * e.err - from_offset.err * from_offset.err);
    e.err = std::hypot(from_offset.err, std::max(fits, noise));
  }
  return e;
}

OffsetEstimate TransferRowByOutline(const Appearance& from, const Appearance& to,
                                    const OffsetEstimate& from_offset) {
  LimbFit a, b;
  if (!OutlineRows(from, to, &a, &b)) return OffsetEstimate{0, NAN, 0, "none"};
  OffsetEstimate e;
  e.value = from_offset.value + (b.centre.y() - a.centre.y());
  e.err = std::sqrt(from_offset.err * from_offset.err + a.centre_err.y() * a.centre_err.y() +
                    b.centre_err.y() * b.centre_err.y());
  e.n = from_offset.n;
  e.source = "plate_contact_of_other_outline";
  return e;
}

OffsetEstimate CombineRowTransfers(const OffsetEstimate& registered,
                                   const OffsetEstimate& outline, double mismatch) {
  if (!std::isfinite(mismatch)) {
    if (outline.source == "none") return registered;
    if (registered.source == "none") return outline;
    return Midway(registered, outline, "plate_contact_of_other_both");
  }
  // Each with its model error.
  OffsetEstimate reg = registered, out = outline;
  reg.err = std::hypot(reg.err, RegisteredTransferModelErr(mismatch));
  out.err = std::hypot(out.err, kOutlineTransferModelPx);
  if (outline.source == "none") return reg;
  if (registered.source == "none") return out;
  if (!(reg.err > 0) || !std::isfinite(reg.err) || !std::isfinite(out.err)) {
    return Midway(registered, outline, "plate_contact_of_other_both");
  }
  const double wr = 1.0 / (reg.err * reg.err), wo = 1.0 / (out.err * out.err);
  OffsetEstimate e = reg;
  e.value = (wr * reg.value + wo * out.value) / (wr + wo);
  e.err = 1.0 / std::sqrt(wr + wo);
  const double scale = std::abs(reg.value - out.value) / std::hypot(reg.err, out.err);
  if (scale > 1) e.err *= scale;
  e.source = "plate_contact_of_other_both";
  return e;
}

OffsetEstimate TransferOffset(const Appearance& from, const Appearance& to,
                              const OffsetEstimate& from_offset, int axis) {
  if (!from.valid() || !to.valid() || from.image.size() != to.image.size()) {
    return OffsetEstimate{0, NAN, 0, "none"};
  }
  // to(x + t) = from(x): the centre, at reference + offset in `from`, is at that + t in `to`.
  Eigen::Vector2d forward(0, 0), backward(0, 0);
  const cv::Mat both = from.mask & to.mask;
  if (!RegisterTranslation(from.image, to.image, both, &forward) ||
      !RegisterTranslation(to.image, from.image, both, &backward)) {
    return OffsetEstimate{0, NAN, 0, "none"};
  }
  OffsetEstimate e;
  e.value = from_offset.value + 0.5 * (forward(axis) - backward(axis));
  e.err = std::hypot(from_offset.err, 0.5 * std::abs(forward(axis) + backward(axis)));
  e.n = from_offset.n;
  e.source = "plate_contact_of_other";
  return e;
}

}  // namespace dimer::tracking
