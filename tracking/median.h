#pragma once
// The median of a sample (the upper middle element for an even count), NaN for an empty one.
// One definition for the robust statistics of the template method (appearance_model.cc,
// limb_fit.cc).
#include <algorithm>
#include <limits>
#include <vector>

namespace dimer::tracking {

inline double MedianOf(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace dimer::tracking
