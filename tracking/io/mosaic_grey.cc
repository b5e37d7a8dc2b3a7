#include "tracking/io/mosaic_grey.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "common/median.h"

namespace dimer::tracking {
namespace {

// Cells whose mean is below this fraction of the frame's bright level (its 99.9th percentile)
// say little about the colours (noise, the dark offset) and are left out.
constexpr double kBalanceMinFraction = 0.25;
// Fewer usable cells than this: no balance.
constexpr size_t kBalanceMinCells = 100;

void CheckType(const cv::Mat& raw) {
  if (raw.type() != CV_8UC1 && raw.type() != CV_16UC1) {
    throw std::invalid_argument("mosaic: expected an 8- or 16-bit single-channel mosaic");
  }
}

double At(const cv::Mat& m, int r, int c) {
  return m.depth() == CV_8U ? double(m.at<uint8_t>(r, c)) : double(m.at<uint16_t>(r, c));
}

// The raw levels as float, each divided by its phase's ratio (float: the sums below must not
// round twice).
cv::Mat Balanced(const cv::Mat& raw, const std::array<double, 4>& ratio) {
  cv::Mat bal;
  raw.convertTo(bal, CV_32F);
  for (int r = 0; r < bal.rows; ++r) {
    float* row = bal.ptr<float>(r);
    const float even = float(1.0 / ratio[size_t(2 * (r % 2))]);
    const float odd = float(1.0 / ratio[size_t(2 * (r % 2) + 1)]);
    for (int c = 0; c < bal.cols; ++c) row[c] *= (c % 2 == 0) ? even : odd;
  }
  return bal;
}

// The pixels' noise, blind to colour: the robust spread of differences between same-colour
// neighbours two columns apart, on every other row (the sigma of a cell's checkerboard
// component is the pixels' sigma).
double MosaicNoise(const cv::Mat& bal) {
  std::vector<double> steps;
  for (int r = 0; r < bal.rows; r += 2) {
    const float* row = bal.ptr<float>(r);
    for (int c = 0; c + 2 < bal.cols; ++c) steps.push_back(std::abs(double(row[c + 2] - row[c])));
  }
  return steps.empty() ? 0.0 : 1.4826 * MedianOf(steps) / std::sqrt(2.0);
}

}  // namespace

MosaicBalance EstimateMosaicBalance(const cv::Mat& raw, double saturation) {
  CheckType(raw);
  MosaicBalance b;
  if (raw.rows < 2 || raw.cols < 2) return b;
  std::vector<double> levels;
  levels.reserve(raw.total());
  for (int r = 0; r < raw.rows; ++r) {
    for (int c = 0; c < raw.cols; ++c) levels.push_back(At(raw, r, c));
  }
  const size_t k = size_t(0.999 * double(levels.size() - 1));
  std::nth_element(levels.begin(), levels.begin() + std::ptrdiff_t(k), levels.end());
  const double floor = kBalanceMinFraction * levels[k];
  std::array<std::vector<double>, 4> ratios;
  for (int r = 0; r + 1 < raw.rows; r += 2) {
    for (int c = 0; c + 1 < raw.cols; c += 2) {
      const double v[4] = {At(raw, r, c), At(raw, r, c + 1), At(raw, r + 1, c),
                           At(raw, r + 1, c + 1)};
      const double hi = *std::max_element(v, v + 4);
      const double mean = 0.25 * (v[0] + v[1] + v[2] + v[3]);
      if (!(mean > floor) || hi >= saturation) continue;
      for (int p = 0; p < 4; ++p) ratios[size_t(p)].push_back(v[p] / mean);
    }
  }
  if (ratios[0].size() >= kBalanceMinCells) {
    for (int p = 0; p < 4; ++p) b.ratio[size_t(p)] = MedianOf(ratios[size_t(p)]);
    b.cells = ratios[0].size();
  }
  b.noise = MosaicNoise(Balanced(raw, b.ratio));
  return b;
}

cv::Mat MosaicFilterToGrey(const cv::Mat& raw) {
  CheckType(raw);
  const cv::Mat k = (cv::Mat_<float>(1, 3) << 0.25f, 0.5f, 0.25f);
  cv::Mat sum;
  cv::sepFilter2D(raw, sum, CV_32F, k, k, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::Mat grey;
  sum.convertTo(grey, raw.type());  // rounded to the nearest level, saturated
  return grey;
}

cv::Mat MosaicToGrey(const cv::Mat& raw, const MosaicBalance& balance) {
  CheckType(raw);
  const cv::Mat bal = Balanced(raw, balance.ratio);
  // Colour beyond the noise (half a level at least: less is lost in the output's rounding).
  const double limit = std::max(kMosaicColourSigmas * balance.noise, 0.5);
  // The checkerboard component at every 2x2 origin, signed by the origin's parity: colour gives
  // the same value at every origin (a one-pixel shift swaps the colours and the sign), a grey
  // scene's mixed second derivative alternates with the parity and is taken out by the 3x3
  // filter (zero response at the checkerboard's frequency). What is left is the colour.
  cv::Mat chroma(raw.size(), CV_32F, cv::Scalar(0));
  for (int r = 0; r + 1 < raw.rows; ++r) {
    const float* a = bal.ptr<float>(r);
    const float* b = bal.ptr<float>(r + 1);
    float* q = chroma.ptr<float>(r);
    for (int c = 0; c + 1 < raw.cols; ++c) {
      const float v = 0.5f * (a[c] + b[c + 1] - a[c + 1] - b[c]);
      q[c] = (r + c) % 2 == 0 ? v : -v;
    }
  }
  // The last row and column have no 2x2 origin: they take their neighbours'.
  if (raw.rows > 1) chroma.row(raw.rows - 2).copyTo(chroma.row(raw.rows - 1));
  if (raw.cols > 1) chroma.col(raw.cols - 2).copyTo(chroma.col(raw.cols - 1));
  const cv::Mat k = (cv::Mat_<float>(1, 3) << 0.25f, 0.5f, 0.25f);
  cv::Mat colour, filtered;
  cv::sepFilter2D(chroma, colour, CV_32F, k, k, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::sepFilter2D(bal, filtered, CV_32F, k, k, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::Mat out = bal.clone();
  for (int r = 0; r < raw.rows; ++r) {
    const float* col = colour.ptr<float>(r);
    const float* f = filtered.ptr<float>(r);
    float* o = out.ptr<float>(r);
    for (int c = 0; c < raw.cols; ++c) {
      if (std::abs(double(col[c])) > limit) o[c] = f[c];
    }
  }
  cv::Mat grey;
  out.convertTo(grey, raw.type());
  return grey;
}

}  // namespace dimer::tracking
