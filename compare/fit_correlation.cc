#include "compare/fit_correlation.h"

#include <algorithm>
#include <cmath>

namespace dimer::compare {
namespace {

// d theta_j / d theta_k along k's profile, between its range's two ends; NaN without both.
double Slope(const FitParameter& k_param, size_t k, size_t j) {
  const std::vector<double>&lo = k_param.at_range_lo, &hi = k_param.at_range_hi;
  if (lo.size() <= std::max(j, k) || hi.size() <= std::max(j, k)) return kNaN;
  const double dk = hi[k] - lo[k];
  return dk != 0 ? (hi[j] - lo[j]) / dk : kNaN;
}

}  // namespace

std::vector<double> ProfileCorrelations(const std::vector<FitParameter>& params) {
  const size_t n = params.size();
  std::vector<double> rho(n * n, kNaN);
  auto constrained = [&](size_t k) { return params[k].status == "constrained"; };
  for (size_t k = 0; k < n; ++k) {
    if (!constrained(k)) continue;
    rho[k * n + k] = 1;
    for (size_t j = k + 1; j < n; ++j) {
      if (!constrained(j)) continue;
      const double s_jk = Slope(params[k], k, j), s_kj = Slope(params[j], j, k);
      const double product = s_jk * s_kj;
      if (!std::isfinite(product)) continue;
      double r = kNaN;
      if (product > 0) r = std::copysign(std::min(1.0, std::sqrt(product)), s_jk);
      rho[k * n + j] = rho[j * n + k] = r;
    }
  }
  return rho;
}

}  // namespace dimer::compare
