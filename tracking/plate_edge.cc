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

// Sum of a row's pixels where use[col] (integer: exact, and no conversion per pixel).
template <typename T>
int64_t MaskedRowSum(const cv::Mat& frame, int row, const std::vector<uint8_t>& use) {
  const T* p = frame.ptr<T>(row);
  int64_t sum = 0;
  for (int col = 0; col < frame.cols; ++col) sum += use[col] ? p[col] : 0;
  return sum;
}

double FullScale(const cv::Mat& img) { return img.depth() == CV_8U ? 255.0 : 65535.0; }

}  // namespace

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
                      const std::vector<std::pair<double, double>>& excluded) {
  if (!std::isfinite(row_guess)) return kNaN;
  const int r0 = std::max(0, int(std::lround(row_guess)) - kPlateBandHalfPx);
  const int r1 = std::min(frame.rows - 1, int(std::lround(row_guess)) + kPlateBandHalfPx);
  if (r1 - r0 < 2 * kBracketRows + 1) return kNaN;
  std::vector<uint8_t> use(frame.cols, 1);
  for (const auto& [a, b] : excluded) {
    for (int c = std::max(0, int(std::floor(a))); c <= std::min(frame.cols - 1, int(std::ceil(b)));
         ++c) {
      use[c] = 0;
    }
  }
  const int n_cols = int(std::count(use.begin(), use.end(), 1));
  if (n_cols < 8) return kNaN;  // too few clear columns for a trustworthy profile
  std::vector<double> profile;
  for (int row = r0; row <= r1; ++row) {
    profile.push_back(double(frame.depth() == CV_8U ? MaskedRowSum<uint8_t>(frame, row, use)
                                                     : MaskedRowSum<uint16_t>(frame, row, use)) /
                      n_cols);
  }
  return EdgeRowInProfile(profile, r0, kPlateMinStepFraction * 0.25 * FullScale(frame));
}

}  // namespace dimer::tracking
