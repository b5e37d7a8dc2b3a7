#include "compare/noise.h"

#include <algorithm>
#include <cmath>

namespace dimer::compare {

double NoiseSigma(const std::vector<double>& v) {
  std::vector<double> d3;
  d3.reserve(v.size());
  for (size_t i = 3; i < v.size(); ++i) {
    const double d = v[i] - 3 * v[i - 1] + 3 * v[i - 2] - v[i - 3];
    if (std::isfinite(d)) d3.push_back(std::abs(d));
  }
  if (d3.size() < 8) return 0.0;
  std::nth_element(d3.begin(), d3.begin() + d3.size() / 2, d3.end());
  // 1.4826: MAD of a Gaussian to its sigma; sqrt(20): the third difference's noise gain.
  return 1.4826 * d3[d3.size() / 2] / std::sqrt(20.0);
}

}  // namespace dimer::compare
