#include "tracking/plate_edge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Rows read on each side of the strongest step (see the header for why three).
constexpr int kBracketRows = 3;
// Column stride for the coarse median profile: 1/4 of the columns is plenty for a median.
constexpr int kCoarseColumnStride = 4;

double PixelAt(const cv::Mat& img, int row, int col) {
  return img.depth() == CV_8U ? img.at<uint8_t>(row, col) : img.at<uint16_t>(row, col);
}

// Sum of a row's pixels in columns first..last (integer: exact, no conversion per pixel).
template <typename T>
int64_t RangeSum(const cv::Mat& frame, int row, int first, int last) {
  const T* p = frame.ptr<T>(row);
  int64_t sum = 0;
  for (int col = first; col <= last; ++col) sum += p[col];
  return sum;
}

double FullScale(const cv::Mat& img) { return img.depth() == CV_8U ? 255.0 : 65535.0; }

// Pixel noise sigma in rows r0..r1: the median absolute difference of horizontal neighbours
// (clear columns; a sample of every kNoiseColumnStride-th column, every second row), which the
// plate's horizontal edge does not raise; at least the quantisation's 1/sqrt(12) level.
constexpr int kNoiseColumnStride = 4;
double BandNoise(const cv::Mat& frame, int r0, int r1, const std::vector<uint8_t>& use) {
  thread_local std::vector<double> d;
  d.clear();
  for (int row = r0; row <= r1; row += 2) {
    for (int col = 0; col + 1 < frame.cols; col += kNoiseColumnStride) {
      if (use[col] && use[col + 1]) d.push_back(std::abs(PixelAt(frame, row, col + 1) - PixelAt(frame, row, col)));
    }
  }
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return std::max(1.4826 * d[d.size() / 2] / std::sqrt(2.0), 1.0 / std::sqrt(12.0));
}

// Smallest step of a profile averaged over n columns that counts as an edge: kPlateStepSigmas
// noise sigmas of the difference of two rows, and at least kPlateMinStepGreyLevels (8-bit
// scale), so that a dim frame still shows its edge and noise never does.
double MinStep(double sigma, int n, const cv::Mat& frame) {
  return std::max(kPlateStepSigmas * sigma * std::sqrt(2.0 / n),
                  kPlateMinStepGreyLevels * FullScale(frame) / 255.0);
}

// The camera's blur across rows: a Gaussian of `sigma` px sampled on the pixel grid to 3 sigma
// (as cv::GaussianBlur applies it; sigma 0: none), normalised.
std::vector<double> PsfTaps(double sigma) {
  if (!(sigma > 0)) return {1.0};
  const int half = int(std::ceil(3 * sigma));
  std::vector<double> taps(2 * half + 1);
  double sum = 0;
  for (int t = -half; t <= half; ++t) sum += taps[t + half] = std::exp(-0.5 * t * t / (sigma * sigma));
  for (double& w : taps) w /= sum;
  return taps;
}

// Share of row `row` that the side below an edge at `y` gives after the blur: each row's box
// coverage (pixel r spans [r - 1/2, r + 1/2]) spread over its neighbours by `taps`.
double BlurredCover(int row, double y, const std::vector<double>& taps) {
  const int half = int(taps.size() / 2);
  double cover = 0;
  for (int t = -half; t <= half; ++t) {
    cover += taps[t + half] * std::clamp(row - t + 0.5 - y, 0.0, 1.0);
  }
  return cover;
}

}  // namespace

double ClippedEdgeRowInProfile(const std::vector<double>& profile, int first_row, int k,
                               double clip, double pixel_sigma, double profile_sigma,
                               double psf_sigma_px) {
  const int n = int(profile.size());
  const std::vector<double> taps = PsfTaps(psf_sigma_px);
  if (k - kBracketRows < 0 || k + kBracketRows >= n) return kNaN;
  // The clipped side is the brighter one; +1 when it lies below the edge.
  const bool below = profile[k + kBracketRows] > profile[k - kBracketRows];
  const double dark = below ? profile[k - kBracketRows] : profile[k + kBracketRows];
  const double at_clip = clip - kPlateClipMarginSigmas * pixel_sigma;
  const double at_floor = kPlateClipMarginSigmas * pixel_sigma;
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, double>> fits;  // (cost, step) per grid row
  const double y0 = first_row + k - 1.5, y1 = first_row + k + 2.5;
  const int steps = int(std::lround((y1 - y0) / kPlateClipGridPx));
  fits.reserve(steps + 1);
  for (int i = 0; i <= steps; ++i) {
    const double y = y0 + i * kPlateClipGridPx;
    double lo = 0, hi = std::numeric_limits<double>::infinity(), num = 0, den = 0;
    for (int j = k - kBracketRows; j <= k + kBracketRows; ++j) {
      const double cover = BlurredCover(first_row + j, y, taps);
      const double b = below ? cover : 1.0 - cover;  // the clipped side's share of row j
      const double d = profile[j] - dark;
      if (profile[j] >= at_clip) {
        lo = b > 0 ? std::max(lo, (at_clip - dark) / b) : std::numeric_limits<double>::infinity();
      } else if (d < at_floor) {
        if (b > 0) hi = std::min(hi, at_floor / b);
      } else {
        num += d * b;
        den += b * b;
      }
    }
    if (lo > hi) {
      fits.emplace_back(std::numeric_limits<double>::infinity(), 0.0);
      continue;
    }
    const double step = std::clamp(den > 0 ? num / den : lo, lo, hi);
    double cost = 0;
    for (int j = k - kBracketRows; j <= k + kBracketRows; ++j) {
      const double d = profile[j] - dark;
      if (profile[j] >= at_clip || d < at_floor) continue;
      const double cover = BlurredCover(first_row + j, y, taps);
      const double r = (d - step * (below ? cover : 1.0 - cover)) / profile_sigma;
      cost += r * r;
    }
    fits.emplace_back(cost, step);
    best_cost = std::min(best_cost, cost);
  }
  if (!std::isfinite(best_cost)) return kNaN;
  // Among the rows that fit within one unit of chi-square, the one needing the least light on
  // the clipped side: with a single unclipped sample the fit is flat in the direction of a
  // brighter clipped side, and the least over-exposure that still explains the clip is the
  // only choice the data do not contradict at its boundary.
  int pick = -1;
  for (int i = 0; i <= steps; ++i) {
    if (fits[i].first <= best_cost + 1.0 && (pick < 0 || fits[i].second < fits[pick].second)) pick = i;
  }
  return y0 + pick * kPlateClipGridPx;
}

double EdgeRowInProfile(const std::vector<double>& profile, int first_row, double min_step) {
  const int n = int(profile.size());
  int k = -1;
  double best = 0;
  for (int i = 0; i + 1 < n; ++i) {
    const double step = std::abs(profile[i + 1] - profile[i]);
    if (step > best) {
      best = step;
      k = i;
    }
  }
  if (k < 0 || best < min_step || k - kBracketRows < 0 || k + kBracketRows >= n) return kNaN;
  const double above = profile[k - kBracketRows], below = profile[k + kBracketRows];
  if (std::abs(below - above) < min_step) return kNaN;
  double covered = 0;  // sum of lower-side fractions over rows k-2 .. k+2
  for (int j = k - kBracketRows + 1; j <= k + kBracketRows - 1; ++j) {
    covered += std::clamp((profile[j] - above) / (below - above), 0.0, 1.0);
  }
  return first_row + (k + kBracketRows - 1) + 0.5 - covered;
}

double FindPlateRowCoarse(const cv::Mat& frame) {
  std::vector<double> profile(frame.rows), column;
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (int row = 0; row < frame.rows; ++row) {
    column.clear();
    for (int col = 0; col < frame.cols; col += kCoarseColumnStride) {
      column.push_back(PixelAt(frame, row, col));
    }
    std::nth_element(column.begin(), column.begin() + column.size() / 2, column.end());
    profile[row] = column[column.size() / 2];
    lo = std::min(lo, profile[row]);
    hi = std::max(hi, profile[row]);
  }
  const double min_step = kPlateMinStepFraction * std::max(hi - lo, 0.05 * FullScale(frame));
  int k = -1;
  double best = 0;
  for (int i = 0; i + 1 < frame.rows; ++i) {
    const double step = std::abs(profile[i + 1] - profile[i]);
    if (step > best) {
      best = step;
      k = i;
    }
  }
  return (k < 0 || best < min_step) ? kNaN : k + 0.5;
}

double RefinePlateRow(const cv::Mat& frame, double row_guess,
                      const std::vector<std::pair<double, double>>& excluded, double psf_sigma_px) {
  if (!std::isfinite(row_guess)) return kNaN;
  const int r0 = std::max(0, int(std::lround(row_guess)) - kPlateBandHalfPx);
  const int r1 = std::min(frame.rows - 1, int(std::lround(row_guess)) + kPlateBandHalfPx);
  const int rows = r1 - r0 + 1;
  if (rows < 2 * kBracketRows + 2) return kNaN;
  std::vector<uint8_t> use(frame.cols, 1);
  for (const auto& [a, b] : excluded) {
    for (int c = std::max(0, int(std::floor(a))); c <= std::min(frame.cols - 1, int(std::ceil(b)));
         ++c) {
      use[c] = 0;
    }
  }
  // Column blocks: runs of clear columns cut into blocks of kPlateBlockColumns; a run's
  // remainder of at least half a block is a block of its own, a shorter one is dropped.
  std::vector<std::pair<int, int>> blocks;  // [first, last] column
  for (int c = 0; c < frame.cols;) {
    if (!use[c]) {
      ++c;
      continue;
    }
    int end = c;
    while (end + 1 < frame.cols && use[end + 1] && end + 1 - c < kPlateBlockColumns) ++end;
    if (end - c + 1 >= kPlateBlockColumns / 2) blocks.emplace_back(c, end);
    c = end + 1;
  }
  if (blocks.size() < size_t(kPlateMinBlocks)) return kNaN;
  const double sigma = BandNoise(frame, r0, r1, use);
  // Block profiles (sums over the block's columns, per row).
  thread_local std::vector<double> sums;
  sums.assign(blocks.size() * size_t(rows), 0.0);
  for (int row = r0; row <= r1; ++row) {
    for (size_t b = 0; b < blocks.size(); ++b) {
      sums[b * rows + (row - r0)] =
          double(frame.depth() == CV_8U
                     ? RangeSum<uint8_t>(frame, row, blocks[b].first, blocks[b].second)
                     : RangeSum<uint16_t>(frame, row, blocks[b].first, blocks[b].second));
    }
  }
  // Each block's own edge and its sign (+1: brighter below).
  struct BlockEdge {
    size_t block;
    double row;
    int sign;
  };
  std::vector<BlockEdge> edges;
  std::vector<double> profile(rows);
  for (size_t b = 0; b < blocks.size(); ++b) {
    const int n = blocks[b].second - blocks[b].first + 1;
    for (int i = 0; i < rows; ++i) profile[i] = sums[b * rows + i] / n;
    const double row = EdgeRowInProfile(profile, r0, MinStep(sigma, n, frame));
    if (!std::isfinite(row)) continue;
    const int k = std::clamp(int(std::lround(row)) - r0, kBracketRows, rows - 1 - kBracketRows);
    edges.push_back({b, row, profile[k + kBracketRows] > profile[k - kBracketRows] ? 1 : -1});
  }
  // The plate's edge has one sign across the width: the majority's. Blocks of the other sign
  // (a reflection's edge, a highlight) and blocks far from the median row are left out.
  const int positive = int(std::count_if(edges.begin(), edges.end(),
                                         [](const BlockEdge& e) { return e.sign > 0; }));
  const int sign = 2 * positive >= int(edges.size()) ? 1 : -1;
  std::vector<double> rows_found;
  for (const auto& e : edges) {
    if (e.sign == sign) rows_found.push_back(e.row);
  }
  if (rows_found.size() < size_t(kPlateMinBlocks)) return kNaN;
  std::nth_element(rows_found.begin(), rows_found.begin() + rows_found.size() / 2,
                   rows_found.end());
  const double median = rows_found[rows_found.size() / 2];
  // The inlier blocks' mean profile: one edge at one row, whatever each block's gain.
  std::fill(profile.begin(), profile.end(), 0.0);
  int n_cols = 0, inliers = 0;
  for (const auto& e : edges) {
    if (e.sign != sign || std::abs(e.row - median) > kPlateInlierPx) continue;
    for (int i = 0; i < rows; ++i) profile[i] += sums[e.block * rows + i];
    n_cols += blocks[e.block].second - blocks[e.block].first + 1;
    ++inliers;
  }
  if (inliers < kPlateMinBlocks) return kNaN;
  for (double& p : profile) p /= n_cols;
  const double row = EdgeRowInProfile(profile, r0, MinStep(sigma, n_cols, frame));
  if (!std::isfinite(row)) return row;
  // One side at the clip: its level is unknown, and the coverage sum (which reads it three rows
  // off) would take the clip for it; fit the blurred edge to the unclipped rows instead.
  const int k = std::clamp(int(std::floor(row - 0.5)) - r0, kBracketRows, rows - 1 - kBracketRows);
  const double clip = FullScale(frame);
  const double bright = std::max(profile[k - kBracketRows], profile[k + kBracketRows]);
  if (bright < clip - kPlateClipMarginSigmas * sigma) return row;
  const double fitted = ClippedEdgeRowInProfile(profile, r0, k, clip, sigma, sigma / std::sqrt(n_cols),
                                                psf_sigma_px);
  return std::isfinite(fitted) ? fitted : row;
}

}  // namespace dimer::tracking
