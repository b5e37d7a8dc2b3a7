#pragma once
// The last stage of a fit (fit.h), apart from the simulations it is usually run on: from the
// best point the searches found, a polish, the goodness test, the chi2 profiles and, for a fit
// that fails the test, the move to a lower point those profiles found (at most kProfileMoves
// times). Its own function so that the move can be tested on a chi2 whose minima are known
// (FitSearch.* in tests/compare/fit_search_test.cc); FitCoefficients runs it on the simulations.
#include <vector>

#include "compare/fit.h"

namespace dimer::compare {

// The chi2 a fit minimises over the five coefficients (eps, mu_hat, mu_hat_s, mu, mu_s; fit.h),
// as the fit's searches see it.
class Chi2Objective {
 public:
  virtual ~Chi2Objective() = default;
  // chi2 at `x`; `simulated`, if given: the model's value of each observable (NaN: none).
  virtual double Chi2(const std::vector<double>& x, std::vector<double>* simulated = nullptr) = 0;
  // Takes the observables' spread between samplings of the motion at `x` into their errors
  // from now on: the larger of it and the spread taken before, or, with `replace`, in its place
  // (where a spread is taken at all: fit.cc, AddScatter).
  virtual void AddScatter(const std::vector<double>& x, bool replace) = 0;
  // Scales every observable's analysis floor (fit.h) by the factor in [min_scale, 1] at which
  // chi2 at `x` is `target` (1 where it is `target` or more already, min_scale where it stays
  // below), uses it from now on and returns it.
  virtual double ScaleFloors(const std::vector<double>& x, double target, double min_scale) = 0;
  // Observables with a value: the fit's degrees of freedom are these less the five.
  virtual int usable() const = 0;
};

struct FitSearchResult {
  // chi2, dof, p-value, acceptable, threshold, simulated and the parameters' profiles, ranges
  // and statuses ("no_acceptable_fit" with no range when the fit fails), their correlations.
  FitResult result;
  std::vector<double> x;  // the coefficients at the optimum
  int moves = 0;          // times the fit moved to a lower point of its profiles
};

// From `best` (the searches' best point): judged, profiled, and moved where a failing fit's
// profiles reach lower by more than the threshold (fit.h, goodness of fit).
FitSearchResult JudgeAndMove(Chi2Objective* obj, const std::vector<double>& best,
                             const FitOptions& options);

}  // namespace dimer::compare
