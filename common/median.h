#pragma once
// Robust order statistics of the tracker's libraries (the learnt appearance, the outline, colour
// mosaics, the plate's contact line, ...), one definition each.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dimer {

// The median of a sample (the upper middle element for an even count), NaN for an empty one.
inline double MedianOf(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The median of the finite values of a sample (the upper middle one for an even count), NaN
// when none is finite: MedianOf with NaN and infinities left out first.
inline double FiniteMedian(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }),
          v.end());
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The value of rank round(q (n - 1)) in a sample of n (0 <= q <= 1: q 0.5 is MedianOf for an odd
// count), NaN for an empty one.
inline double QuantileOf(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto at = v.begin() + std::ptrdiff_t(std::lround(q * double(v.size() - 1)));
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

// The lowest value of `v` that at least `min_count` values of `v` (itself included) lie within
// `support` above: the low end of the lowest cluster, a lone low outlier passed over. NaN
// (non-finite values ignored) when no value has that support.
inline double LowestSupported(std::vector<double> v, double support, size_t min_count) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }),
          v.end());
  std::sort(v.begin(), v.end());
  for (size_t i = 0, j = 0; i < v.size(); ++i) {
    while (j < v.size() && v[j] <= v[i] + support) ++j;
    if (j - i >= min_count) return v[i];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The median of non-negative values that are whole multiples of `step` (absolute differences of
// quantised levels), read as the continuous quantity they were rounded from: a value k step
// stands for [(k - 1/2) step, (k + 1/2) step] (k = 0: [0, step / 2]), evenly filled, and the
// median is interpolated where the count passes half. The plain median of such data jumps by
// whole steps: a noise of 1 level reads as 0.67 or 1.48 levels. NaN for an empty sample.
inline double QuantisedMedian(const std::vector<double>& v, double step) {
  if (v.empty() || !(step > 0)) return std::numeric_limits<double>::quiet_NaN();
  std::vector<long long> k(v.size());
  for (size_t i = 0; i < v.size(); ++i) k[i] = std::llround(std::abs(v[i]) / step);
  // The bin where the count passes half holds the element ranked ceil(n/2) - 1 (linear time: a
  // frame's 150,000 differences, every learning frame).
  const double half = 0.5 * double(k.size());
  const size_t rank = size_t(std::ceil(half)) - 1;
  std::nth_element(k.begin(), k.begin() + std::ptrdiff_t(rank), k.end());
  const long long m = k[rank];
  size_t below = 0, in = 0;
  for (long long x : k) {
    below += x < m;
    in += x == m;
  }
  const double lo = m == 0 ? 0.0 : (double(m) - 0.5) * step;
  const double width = m == 0 ? 0.5 * step : step;
  return lo + (half - double(below)) / double(in) * width;
}

}  // namespace dimer
