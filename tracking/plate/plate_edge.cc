#include "tracking/plate/plate_edge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "tracking/io/full_scale.h"
#include "tracking/plate/plate_step.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kBracketRows = kPlateBracketRows;
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

// A plate's bright side at a level within this fraction of the full scale is taken as clipped
// there when most of its pixels sit at that level (RefinePlateRow).
constexpr double kClipBelowFullScale = 0.01;

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

// Pixel noise sigma for a clipped edge's fit (RefinePlateRow): as BandNoise, over the `use`
// columns of the rows near the step k whose mean is clear of 0 and of the `clip` level
// (elsewhere the clip cuts the noise), each column's rows moved down by `shift` (a sloping
// edge); NaN if there is none.
double LitRowNoise(const cv::Mat& frame, int first_row, const std::vector<double>& profile, int k,
                   const std::vector<uint8_t>& use, const std::vector<int>& shift, double clip) {
  thread_local std::vector<double> d;
  d.clear();
  for (int i = k - kBracketRows; i <= k + kBracketRows; ++i) {
    if (std::min(profile[i], clip - profile[i]) < kPlateClipNoiseRowMargin * clip) continue;
    for (int col = 0; col + 1 < frame.cols; ++col) {
      // (Neighbours in one block: read along the same shifted row.)
      if (use[col] && use[col + 1] && shift[col] == shift[col + 1]) {
        d.push_back(std::abs(PixelAt(frame, first_row + i + shift[col], col + 1) -
                             PixelAt(frame, first_row + i + shift[col], col)));
      }
    }
  }
  if (d.empty()) return kNaN;
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

}  // namespace

// Rows kBracketRows off the step a sharp edge has levelled off, a defocused one not: through a
// lens blurring by 2 px (Gaussian sigma), 4 % of the step is still to come there, the coverage
// sum counts it on the wrong side, and the row came out 0.2 px high on average, 0.37 px at worst
// (POV-Ray defocus_2px, see povray.plate.defocus_2px). So the bracket
// widens, one row on each side at a time up to kMaxBracketRows, while a row at either end still
// differs from the next one in by more than kBracketTailFraction of the step (and half the
// smallest step that counts as an edge, above the noise), and that difference is the tail of
// this edge, decaying outward, not the start of another one.
constexpr int kMaxBracketRows = kPlateBandHalfPx - 1;
constexpr double kBracketTailFraction = 0.01;

int BracketRows(const std::vector<double>& p, int k, double min_step) {
  const int n = int(p.size());
  int b = kBracketRows;
  const double sign = p[k + 1] > p[k] ? 1 : -1;
  while (b < kMaxBracketRows && k - b - 1 >= 0 && k + b + 1 < n) {
    const double t = std::max(kBracketTailFraction * std::abs(p[k + b] - p[k - b]), 0.5 * min_step);
    const double top = sign * (p[k - b + 1] - p[k - b]), top_out = sign * (p[k - b] - p[k - b - 1]);
    const double bot = sign * (p[k + b] - p[k + b - 1]), bot_out = sign * (p[k + b + 1] - p[k + b]);
    const bool top_tail = top > t && top_out < top;
    const bool bot_tail = bot > t && bot_out < bot;
    if (!top_tail && !bot_tail) break;
    ++b;
  }
  return b;
}

double EdgeRowInProfile(const std::vector<double>& profile, int first_row, double min_step) {
  const int n = int(profile.size());
  double best = 0;
  const int k = PlateStepIndex(profile, &best);
  if (k < 0 || best < min_step || k - kBracketRows < 0 || k + kBracketRows >= n) return kNaN;
  const int b = BracketRows(profile, k, min_step);
  const double above = profile[k - b], below = profile[k + b];
  if (std::abs(below - above) < min_step) return kNaN;
  double covered = 0;  // sum of lower-side fractions over rows k-b+1 .. k+b-1
  for (int j = k - b + 1; j <= k + b - 1; ++j) {
    covered += std::clamp((profile[j] - above) / (below - above), 0.0, 1.0);
  }
  return first_row + (k + b - 1) + 0.5 - covered;
}

namespace {

// Other edges across the frame (a ruler, a shelf or the far wall's edge behind the dimer; the
// shaker under the plate) can be as strong as the plate's, or stronger, and the strongest step
// alone then lands on one of them: the spheres were searched above a ruler and found in no
// frame. The plate is the edge the dimer stands on: of the candidate edges, the one with the
// most of the dimer between it and the next candidate above. The dimer shows as runs of
// sampled pixels standing out from their row's median, at least kStandOutRun samples wide
// (a sphere, the rod; not a ruler's ticks or text, which are thin).
constexpr int kCandidateSeparationRows = 2 * kPlateBandHalfPx;  // closer: the same edge
constexpr double kStandOutSigmas = 8;                           // a pixel off its row's median
constexpr double kStandOutMinFraction = 0.02;                   // ... and off by this of the range
constexpr int kStandOutRun = 3;                                 // samples, 4 px apart
constexpr int kMinStandOutPixels = 12;                          // (sampled) evidence of a dimer

// Per row, the sampled pixels in runs of kStandOutRun or more that stand out from the row's
// median; the noise is the median absolute deviation from the row medians (most pixels are
// backdrop or plate). Row r's samples are samples[start[r] .. start[r + 1]).
std::vector<int> StandOutPerRow(const std::vector<double>& samples,
                                const std::vector<size_t>& start,
                                const std::vector<double>& profile, double range) {
  const size_t rows = profile.size();
  std::vector<double> dev;
  dev.reserve(samples.size());
  for (size_t r = 0; r < rows; ++r) {
    for (size_t i = start[r]; i < start[r + 1]; ++i) {
      dev.push_back(std::abs(samples[i] - profile[r]));
    }
  }
  std::vector<int> out(rows, 0);
  if (dev.empty()) return out;
  std::nth_element(dev.begin(), dev.begin() + dev.size() / 2, dev.end());
  const double sigma = std::max(1.4826 * dev[dev.size() / 2], 1.0 / std::sqrt(12.0));
  const double limit = std::max(kStandOutSigmas * sigma, kStandOutMinFraction * range);
  for (size_t r = 0; r < rows; ++r) {
    int run = 0;
    for (size_t i = start[r]; i <= start[r + 1]; ++i) {
      if (i < start[r + 1] && std::abs(samples[i] - profile[r]) > limit) {
        ++run;
        continue;
      }
      if (run >= kStandOutRun) out[r] += run;
      run = 0;
    }
  }
  return out;
}

// The frame's brightness down its rows: each row's median over every kCoarseColumnStride-th
// column, read along the plate's slope; the samples are kept for StandOutPerRow.
struct RowProfile {
  std::vector<double> profile, samples;
  std::vector<size_t> start;  // row r's samples: [start[r], start[r + 1])
  double lo = std::numeric_limits<double>::max(), hi = -std::numeric_limits<double>::max();
};

RowProfile RowProfileOf(const cv::Mat& frame, double slope) {
  RowProfile p;
  p.profile.resize(frame.rows);
  p.start.assign(frame.rows + 1, 0);
  std::vector<double> column;
  p.samples.reserve(size_t(frame.rows) * (frame.cols / kCoarseColumnStride + 1));
  const double centre = 0.5 * (frame.cols - 1);
  for (int row = 0; row < frame.rows; ++row) {
    for (int col = 0; col < frame.cols; col += kCoarseColumnStride) {
      const int r = slope == 0 ? row : row + int(std::lround(slope * (col - centre)));
      if (r >= 0 && r < frame.rows) p.samples.push_back(PixelAt(frame, r, col));
    }
    if (p.samples.size() == p.start[row]) p.samples.push_back(PixelAt(frame, row, int(centre)));
    p.start[row + 1] = p.samples.size();
    column.assign(p.samples.begin() + std::ptrdiff_t(p.start[row]), p.samples.end());
    std::nth_element(column.begin(), column.begin() + column.size() / 2, column.end());
    p.profile[row] = column[column.size() / 2];
    p.lo = std::min(p.lo, p.profile[row]);
    p.hi = std::max(p.hi, p.profile[row]);
  }
  return p;
}

// The candidates: the strongest step `k` and every other local peak step of either sign (a
// front-lit plate is brighter than the backdrop, a backlit one darker), at least min_step,
// kCandidateSeparationRows from a stronger one (each read as PlateStepIndex reads its own
// neighbourhood: the upper of a top face's two edges).
std::vector<int> CandidateSteps(const std::vector<double>& profile, int k, double min_step) {
  std::vector<std::pair<double, int>> peaks;  // (size, index)
  const int n = int(profile.size());
  for (int i = 0; i + 1 < n; ++i) {
    const double d = profile[i + 1] - profile[i], step = std::abs(d);
    const bool peak = (i == 0 || d * (profile[i] - profile[i - 1]) <= 0 ||
                       step >= std::abs(profile[i] - profile[i - 1])) &&
                      (i + 2 >= n || d * (profile[i + 2] - profile[i + 1]) <= 0 ||
                       step >= std::abs(profile[i + 2] - profile[i + 1]));
    if (step >= min_step && peak) peaks.emplace_back(step, i);
  }
  std::sort(peaks.begin(), peaks.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<int> candidates{k};
  for (const auto& [size, i] : peaks) {
    bool apart = true;
    for (int c : candidates) apart = apart && std::abs(i - c) >= kCandidateSeparationRows;
    if (!apart) continue;
    double unused = 0;
    candidates.push_back(UpperComparableStep(profile, i, profile[i + 1] - profile[i], &unused));
  }
  return candidates;
}

// The candidate with the most of the dimer's evidence between it and the next one above it (or
// the frame's top); the strongest step `k` where no candidate has enough.
int CandidateUnderTheDimer(const RowProfile& p, std::vector<int> candidates, int k) {
  const std::vector<int> stand_out = StandOutPerRow(p.samples, p.start, p.profile, p.hi - p.lo);
  std::sort(candidates.begin(), candidates.end());
  int chosen = k, most = 0;
  for (size_t j = 0; j < candidates.size(); ++j) {
    const int top = j == 0 ? 0 : candidates[j - 1] + kPlateBandHalfPx;
    int evidence = 0;
    for (int r = top; r <= candidates[j] - kPlateBandHalfPx / 2; ++r) evidence += stand_out[r];
    // Ties go to the strongest step; a frame without a dimer in view keeps it too.
    if (evidence > most || (evidence == most && candidates[j] == k)) {
      most = evidence;
      chosen = candidates[j];
    }
  }
  return most >= kMinStandOutPixels ? chosen : k;
}

// The row FindPlateRowCoarse takes from the profile `p` (its step's index), -1 if none; the
// strongest step's index in *strongest and the smallest step that counts in *min_step.
int CoarseStepOf(const RowProfile& p, const cv::Mat& frame, int* strongest, double* min_step) {
  *min_step = kPlateMinStepFraction * std::max(p.hi - p.lo, 0.05 * FullScale(frame));
  double best = 0;
  const int k = PlateStepIndex(p.profile, &best);
  *strongest = k;
  if (k < 0 || best < *min_step) return -1;
  const std::vector<int> candidates = CandidateSteps(p.profile, k, *min_step);
  if (candidates.size() == 1) return k;
  return CandidateUnderTheDimer(p, candidates, k);
}

}  // namespace

double FindPlateRowCoarse(const cv::Mat& frame, double slope) {
  const RowProfile p = RowProfileOf(frame, slope);
  int strongest = -1;
  double min_step = 0;
  const int k = CoarseStepOf(p, frame, &strongest, &min_step);
  return k < 0 ? kNaN : k + 0.5;
}

std::vector<PlateCandidate> PlateCandidates(const cv::Mat& frame, double slope) {
  const RowProfile p = RowProfileOf(frame, slope);
  int strongest = -1;
  double min_step = 0;
  const int chosen = CoarseStepOf(p, frame, &strongest, &min_step);
  if (chosen < 0) return {};
  // Every local peak step that counts, strongest first, each kept where no stronger one is
  // within kPlateCandidateSeparationRows (the same blurred edge); the two of PlateStepIndex's
  // choices always.
  std::vector<std::pair<double, int>> peaks;
  const std::vector<double>& q = p.profile;
  for (int i = 0; i + 1 < int(q.size()); ++i) {
    const double step = std::abs(q[i + 1] - q[i]);
    const bool peak = (i == 0 || step >= std::abs(q[i] - q[i - 1])) &&
                      (i + 2 >= int(q.size()) || step >= std::abs(q[i + 2] - q[i + 1]));
    if (step >= min_step && peak) peaks.emplace_back(step, i);
  }
  std::sort(peaks.begin(), peaks.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<int> kept{chosen};
  if (strongest != chosen) kept.push_back(strongest);
  for (const auto& [size, i] : peaks) {
    bool apart = true;
    for (int c : kept) apart = apart && std::abs(i - c) >= kPlateCandidateSeparationRows;
    if (apart) kept.push_back(i);
  }
  std::sort(kept.begin(), kept.end());
  std::vector<PlateCandidate> out;
  for (int i : kept) {
    out.push_back({i + 0.5, std::abs(q[i + 1] - q[i]), i == strongest, i == chosen});
  }
  return out;
}

namespace {

// The band's column blocks and each one's own edge (RefinePlateRow, PlateEdgeSlope).
struct BlockEdge {
  size_t block;
  double row;  // its edge's row moved to ref_col along the slope
  int sign;    // +1: brighter below
};
struct PlateBlocks {
  int r0 = 0, rows = 0;                     // band rows r0 .. r0 + rows - 1 (at ref_col)
  std::vector<std::pair<int, int>> blocks;  // [first, last] column
  std::vector<int> shift;                   // whole rows each block is read down by
  std::vector<double> rest;                 // slope (centre - ref_col) - shift: the fraction left
  std::vector<double> sums;                 // block b's profile: sums[b * rows + i]
  std::vector<uint8_t> use;                 // columns clear of the spheres
  std::vector<BlockEdge> edges;             // blocks with an edge, row at ref_col
  double sigma = 1;                         // pixel noise in the band
  bool ok = false;
};

// Fills `out` (its vectors keep their capacity: this runs for every frame, and the callers keep
// one per thread).
void MeasureBlocks(const cv::Mat& frame, double row_guess,
                   const std::vector<std::pair<double, double>>& excluded, double slope,
                   double ref_col, PlateBlocks* out) {
  PlateBlocks& pb = *out;
  pb.ok = false;
  pb.r0 = pb.rows = 0;
  pb.blocks.clear();
  pb.shift.clear();
  pb.rest.clear();
  pb.edges.clear();
  pb.sigma = 1;
  if (!std::isfinite(row_guess)) return;
  pb.r0 = std::max(0, int(std::lround(row_guess)) - kPlateBandHalfPx);
  const int r1 = std::min(frame.rows - 1, int(std::lround(row_guess)) + kPlateBandHalfPx);
  pb.rows = r1 - pb.r0 + 1;
  if (pb.rows < 2 * kBracketRows + 2) return;
  pb.use.assign(frame.cols, 1);
  for (const auto& [a, b] : excluded) {
    for (int c = std::max(0, int(std::floor(a))); c <= std::min(frame.cols - 1, int(std::ceil(b)));
         ++c) {
      pb.use[c] = 0;
    }
  }
  // Column blocks: runs of clear columns cut into blocks of kPlateBlockColumns; a run's
  // remainder of at least half a block is a block of its own, a shorter one is dropped. A block
  // whose band, moved along the slope, leaves the frame is dropped too.
  for (int c = 0; c < frame.cols;) {
    if (!pb.use[c]) {
      ++c;
      continue;
    }
    int end = c;
    while (end + 1 < frame.cols && pb.use[end + 1] && end + 1 - c < kPlateBlockColumns) ++end;
    if (end - c + 1 >= kPlateBlockColumns / 2) {
      const double along = slope == 0 ? 0.0 : slope * (0.5 * (c + end) - ref_col);
      const int shift = int(std::lround(along));
      if (pb.r0 + shift >= 0 && r1 + shift < frame.rows) {
        pb.blocks.emplace_back(c, end);
        pb.shift.push_back(shift);
        pb.rest.push_back(along - shift);
      }
    }
    c = end + 1;
  }
  if (pb.blocks.size() < size_t(kPlateMinBlocks)) return;
  pb.sigma = BandNoise(frame, pb.r0, r1, pb.use);
  // Block profiles (sums over the block's columns, per row).
  pb.sums.assign(pb.blocks.size() * size_t(pb.rows), 0.0);
  for (int i = 0; i < pb.rows; ++i) {
    for (size_t b = 0; b < pb.blocks.size(); ++b) {
      const int row = pb.r0 + i + pb.shift[b];
      pb.sums[b * pb.rows + i] =
          double(frame.depth() == CV_8U
                     ? RangeSum<uint8_t>(frame, row, pb.blocks[b].first, pb.blocks[b].second)
                     : RangeSum<uint16_t>(frame, row, pb.blocks[b].first, pb.blocks[b].second));
    }
  }
  thread_local std::vector<double> profile;
  profile.assign(pb.rows, 0.0);
  for (size_t b = 0; b < pb.blocks.size(); ++b) {
    const int n = pb.blocks[b].second - pb.blocks[b].first + 1;
    for (int i = 0; i < pb.rows; ++i) profile[i] = pb.sums[b * pb.rows + i] / n;
    const double row = EdgeRowInProfile(profile, pb.r0, MinStep(pb.sigma, n, frame));
    if (!std::isfinite(row)) continue;
    const int k =
        std::clamp(int(std::lround(row)) - pb.r0, kBracketRows, pb.rows - 1 - kBracketRows);
    pb.edges.push_back({b, row - pb.rest[b],
                        profile[k + kBracketRows] > profile[k - kBracketRows] ? 1 : -1});
  }
  pb.ok = true;
}

// The plate's edge has one sign across the width: the majority's.
int MajoritySign(const std::vector<BlockEdge>& edges) {
  const int positive = int(std::count_if(edges.begin(), edges.end(),
                                         [](const BlockEdge& e) { return e.sign > 0; }));
  return 2 * positive >= int(edges.size()) ? 1 : -1;
}

// The inlier blocks' mean profile: one edge at one row, whatever each block's gain. Each
// column's whole-row shift (`shift_of`) follows its block; what is left of the slope is
// averaged over the columns (`rest`).
struct InlierProfile {
  std::vector<double> profile;
  int n_cols = 0, inliers = 0;
  double rest = 0;
  std::vector<uint8_t> inlier_cols;
  std::vector<int> shift_of;
};

// Blocks of the other sign (a reflection's edge, a highlight) and blocks far from the median
// row are left out; false when too few are left.
bool InlierProfileOf(const PlateBlocks& pb, int cols, double slope, InlierProfile* ip) {
  const int rows = pb.rows;
  const auto& blocks = pb.blocks;
  const int sign = MajoritySign(pb.edges);
  std::vector<double> rows_found;
  for (const auto& e : pb.edges) {
    if (e.sign == sign) rows_found.push_back(e.row);
  }
  if (rows_found.size() < size_t(kPlateMinBlocks)) return false;
  std::nth_element(rows_found.begin(), rows_found.begin() + rows_found.size() / 2,
                   rows_found.end());
  const double median = rows_found[rows_found.size() / 2];
  ip->profile.assign(rows, 0.0);
  ip->inlier_cols.assign(cols, 0);
  ip->shift_of.assign(cols, 0);
  for (const auto& e : pb.edges) {
    if (e.sign != sign || std::abs(e.row - median) > kPlateInlierPx) continue;
    const int n = blocks[e.block].second - blocks[e.block].first + 1;
    for (int i = 0; i < rows; ++i) ip->profile[i] += pb.sums[e.block * rows + i];
    ip->n_cols += n;
    ip->rest += n * pb.rest[e.block];
    std::fill(ip->inlier_cols.begin() + blocks[e.block].first,
              ip->inlier_cols.begin() + blocks[e.block].second + 1, 1);
    std::fill(ip->shift_of.begin() + blocks[e.block].first,
              ip->shift_of.begin() + blocks[e.block].second + 1, pb.shift[e.block]);
    ++ip->inliers;
  }
  if (ip->inliers < kPlateMinBlocks) return false;
  for (double& p : ip->profile) p /= ip->n_cols;
  ip->rest = slope == 0 ? 0.0 : ip->rest / ip->n_cols;
  return true;
}

// Where the camera saturates: the container's top, or the bright row's brightest level when
// that is within kClipBelowFullScale of it. A camera of fewer bits saturates below the top
// (its levels shifted up: 4095 x 16 = 65520; or scaled, level_scale.h: 8-bit data x 64 taken
// as 14-bit, 65283), and a plate clipped there was taken for an edge's true level (POV-Ray
// over-exposed: the plate row 0.41 px off). Sets *at_clip to the inlier columns there.
double ClipLevel(const cv::Mat& frame, const InlierProfile& ip, int bright_row, int* at_clip) {
  double clip = FullScale(frame), brightest = 0;
  for (int col = 0; col < frame.cols; ++col) {
    if (ip.inlier_cols[col]) {
      brightest = std::max(brightest, PixelAt(frame, bright_row + ip.shift_of[col], col));
    }
  }
  if (brightest >= (1 - kClipBelowFullScale) * clip) clip = brightest;
  *at_clip = 0;
  for (int col = 0; col < frame.cols; ++col) {
    *at_clip += ip.inlier_cols[col] && PixelAt(frame, bright_row + ip.shift_of[col], col) >= clip;
  }
  return clip;
}

}  // namespace

double RefinePlateRow(const cv::Mat& frame, double row_guess,
                      const std::vector<std::pair<double, double>>& excluded, double psf_sigma_px,
                      ClippedEdgeProfile* clipped, double slope, double ref_col) {
  if (clipped) *clipped = ClippedEdgeProfile{};
  if (!(std::isfinite(slope) && std::isfinite(ref_col))) slope = 0;
  thread_local PlateBlocks pb;
  MeasureBlocks(frame, row_guess, excluded, slope, ref_col, &pb);
  if (!pb.ok) return kNaN;
  const int r0 = pb.r0;
  InlierProfile ip;
  if (!InlierProfileOf(pb, frame.cols, slope, &ip)) return kNaN;
  const std::vector<double>& profile = ip.profile;
  const int n_cols = ip.n_cols;
  const double rest = ip.rest;
  const double row = EdgeRowInProfile(profile, r0, MinStep(pb.sigma, n_cols, frame));
  if (!std::isfinite(row)) return row;
  // One side at the clip (most of its pixels at full scale): its level is unknown, and the
  // coverage sum (which reads it three rows off) would take the clip for it; the blurred edge
  // is fitted to the rows instead.
  double size = 0;
  const int k = PlateStepIndex(profile, &size);
  const bool below = profile[k + kBracketRows] > profile[k - kBracketRows];
  const int bright_row = r0 + k + (below ? kBracketRows : -kBracketRows);
  int at_clip = 0;
  const double clip = ClipLevel(frame, ip, bright_row, &at_clip);
  if (2 * at_clip < n_cols) return row - rest;
  // No row clear of the clip and of black: the band's noise, which the clip has cut (a frame's
  // own fit is then too sure of itself; the sequence uses the others' noise, clipped_edge.h).
  const double lit_sigma =
      LitRowNoise(frame, r0, profile, k, ip.inlier_cols, ip.shift_of, clip);
  const double pixel_sigma = std::isfinite(lit_sigma) ? lit_sigma : pb.sigma;
  const double fitted = ClippedEdgeRowInProfile(
      profile, r0, clip, pixel_sigma, pixel_sigma / std::sqrt(double(n_cols)), psf_sigma_px);
  if (!std::isfinite(fitted)) return row - rest;
  if (clipped) {
    *clipped = ClippedEdgeProfile{profile, r0, clip, pixel_sigma, n_cols,
                                  std::isfinite(lit_sigma), rest};
  }
  return fitted - rest;
}

namespace {

// A line through (x, y) robust to a few points off it: the Theil-Sen slope (the median of the
// pairwise slopes) and the median intercept.
std::pair<double, double> TheilSen(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> pair_slopes;
  for (size_t i = 0; i < x.size(); ++i) {
    for (size_t j = i + 1; j < x.size(); ++j) {
      if (x[j] != x[i]) pair_slopes.push_back((y[j] - y[i]) / (x[j] - x[i]));
    }
  }
  if (pair_slopes.empty()) return {kNaN, kNaN};
  std::nth_element(pair_slopes.begin(), pair_slopes.begin() + pair_slopes.size() / 2,
                   pair_slopes.end());
  const double b = pair_slopes[pair_slopes.size() / 2];
  std::vector<double> offsets;
  for (size_t i = 0; i < x.size(); ++i) offsets.push_back(y[i] - b * x[i]);
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  return {b, offsets[offsets.size() / 2]};
}

// Each column block's strongest step over the whole frame height (whole rows): where the edge
// is, however steeply it slopes; blocks of the majority's sign only.
void CoarseBlockSteps(const cv::Mat& frame, const std::vector<std::pair<double, double>>& excluded,
                      std::vector<double>* x, std::vector<double>* y) {
  std::vector<uint8_t> use(frame.cols, 1);
  for (const auto& [a, b] : excluded) {
    for (int c = std::max(0, int(std::floor(a))); c <= std::min(frame.cols - 1, int(std::ceil(b)));
         ++c) {
      use[c] = 0;
    }
  }
  std::vector<double> xs, ys;
  std::vector<int> signs;
  std::vector<double> profile(frame.rows);
  for (int c = 0; c + kPlateBlockColumns <= frame.cols; c += kPlateBlockColumns) {
    if (!std::all_of(use.begin() + c, use.begin() + c + kPlateBlockColumns,
                     [](uint8_t u) { return u != 0; })) {
      continue;
    }
    for (int row = 0; row < frame.rows; ++row) {
      profile[row] = double(frame.depth() == CV_8U
                                ? RangeSum<uint8_t>(frame, row, c, c + kPlateBlockColumns - 1)
                                : RangeSum<uint16_t>(frame, row, c, c + kPlateBlockColumns - 1));
    }
    double size = 0;
    const int k = PlateStepIndex(profile, &size);
    if (k < 0) continue;
    xs.push_back(c + 0.5 * (kPlateBlockColumns - 1));
    ys.push_back(k + 0.5);
    signs.push_back(profile[k + 1] > profile[k] ? 1 : -1);
  }
  const int positive = int(std::count(signs.begin(), signs.end(), 1));
  const int sign = 2 * positive >= int(signs.size()) ? 1 : -1;
  for (size_t i = 0; i < xs.size(); ++i) {
    if (signs[i] != sign) continue;
    x->push_back(xs[i]);
    y->push_back(ys[i]);
  }
}

}  // namespace

double PlateEdgeSlope(const cv::Mat& frame, const std::vector<std::pair<double, double>>& excluded,
                      double* err) {
  *err = kNaN;
  // A first line through each block's strongest step over the whole height (an edge that
  // slopes by degrees leaves any fixed band of rows).
  std::vector<double> cx, cy;
  CoarseBlockSteps(frame, excluded, &cx, &cy);
  if (cx.size() < size_t(kPlateMinSlopeBlocks)) return kNaN;
  const auto [coarse_slope, coarse_offset] = TheilSen(cx, cy);
  if (!std::isfinite(coarse_slope) || std::abs(coarse_slope) > kPlateMaxSlope) return kNaN;
  // Then each block's sub-pixel row in a band that follows that line, moved along it to the
  // centre column: what is left is the first line's error, fitted by least squares over the
  // blocks within kPlateInlierPx of a robust line through them.
  const double centre = 0.5 * (frame.cols - 1);
  thread_local PlateBlocks pb;
  MeasureBlocks(frame, coarse_offset + coarse_slope * centre, excluded, coarse_slope, centre, &pb);
  if (!pb.ok) return kNaN;
  const int sign = MajoritySign(pb.edges);
  std::vector<double> x, y;
  for (const auto& e : pb.edges) {
    if (e.sign != sign) continue;
    x.push_back(0.5 * (pb.blocks[e.block].first + pb.blocks[e.block].second));
    y.push_back(e.row);
  }
  const size_t n = x.size();
  if (n < size_t(kPlateMinSlopeBlocks)) return kNaN;
  const auto [robust, offset] = TheilSen(x, y);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  std::vector<size_t> in;
  for (size_t i = 0; i < n; ++i) {
    if (std::abs(y[i] - offset - robust * x[i]) > kPlateInlierPx) continue;
    in.push_back(i);
    sx += x[i];
    sy += y[i];
  }
  const size_t m = in.size();
  if (m < size_t(kPlateMinSlopeBlocks)) return kNaN;
  const double mx = sx / double(m), my = sy / double(m);
  for (size_t i : in) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0)) return kNaN;
  const double b = sxy / sxx;
  double ss = 0;
  for (size_t i : in) ss += std::pow(y[i] - my - b * (x[i] - mx), 2);
  *err = std::sqrt(ss / double(m - 2) / sxx);
  return coarse_slope + b;
}

}  // namespace dimer::tracking
