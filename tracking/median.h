#pragma once
// Robust order statistics of the template method (appearance_model.cc, limb_fit.cc), one
// definition each.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dimer::tracking {

// The median of a sample (the upper middle element for an even count), NaN for an empty one.
inline double MedianOf(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
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

}  // namespace dimer::tracking
