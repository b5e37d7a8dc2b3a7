#pragma once
// Correlations between fitted parameters, read off their chi2 profiles (fit.h).
//
// Near the optimum chi2 is quadratic with covariance C. Along the profile of parameter k (the
// others re-optimised at each value of k) every other parameter j follows the line
//   theta_j = theta_j* + (C_jk / C_kk) (theta_k - theta_k*),
// so the slopes s_jk = C_jk / C_kk and s_kj = C_jk / C_jj, measured between the two ends of
// each profile's range, give rho_jk = sign(s_jk) sqrt(s_jk s_kj) = C_jk / sqrt(C_jj C_kk)
// without another simulation. A pair is given a correlation only when both parameters are
// constrained (both profiles close); slopes of opposite signs, or a slope of exactly 0 (the
// re-optimisation did not move the other parameter at all), give NaN rather than a guess. The
// numbers are as fine as the re-optimisation at the ranges' ends (fit.cc, RefineRangeEnds: 30
// simulations, steps of a tenth of each other parameter's range): on a noise-free scene whose
// ranges are 5e-4 of the bounds it resolves some pairs only (Fit.StartedAtTheTruthStaysThere:
// eps with none). Held by FitCorrelation.* (fit_test.cc).
#include <vector>

#include "compare/fit.h"

namespace dimer::compare {

// params.size() squared, row-major: 1 on the diagonal of a constrained parameter, NaN for
// every pair not both constrained; |rho| <= 1.
std::vector<double> ProfileCorrelations(const std::vector<FitParameter>& params);

}  // namespace dimer::compare
