#include "compare/goodness_of_fit.h"

#include <cmath>

namespace dimer::compare {
namespace {

constexpr int kMaxTerms = 500;       // series / continued fraction: converge in < 100 for dof < 1e4
constexpr double kRelTol = 1e-15;    // relative size of the last term kept
constexpr double kTiny = 1e-300;     // Lentz's guard against a zero denominator

// Lower regularised gamma P(a, x) by its series, for x < a + 1.
double LowerSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < kMaxTerms; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kRelTol) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Upper regularised gamma Q(a, x) by its continued fraction (modified Lentz), for x >= a + 1.
double UpperFraction(double a, double x) {
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int n = 1; n < kMaxTerms; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < kRelTol) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double ChiSquarePValue(double chi2, int dof) {
  if (!(chi2 > 0)) return 1.0;
  const double a = 0.5 * dof, x = 0.5 * chi2;
  return x < a + 1.0 ? 1.0 - LowerSeries(a, x) : UpperFraction(a, x);
}

}  // namespace dimer::compare
