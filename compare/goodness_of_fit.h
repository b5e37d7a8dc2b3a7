#pragma once
// Goodness of fit of a chi2 (compare/fit.h): the probability that a chi2 with `dof` degrees of
// freedom reaches at least the value found, Q(dof / 2, chi2 / 2), the regularised upper
// incomplete gamma function. A fit whose p-value is below kMinFitPValue does not describe the
// track: it gives no constrained coefficient (docs/MODEL.md, "The fit").

namespace dimer::compare {

inline constexpr double kMinFitPValue = 1e-3;

// P(chi2_dof >= chi2); 1 for chi2 <= 0. `dof` >= 1.
double ChiSquarePValue(double chi2, int dof);

}  // namespace dimer::compare
