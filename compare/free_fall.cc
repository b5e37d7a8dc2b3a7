#include "compare/free_fall.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dimer::compare {
namespace {

// One flight [a, b): g and its variance from a quadratic fit, the residual giving the noise.
bool FitFlight(const SampledRun& run, size_t a, size_t b, double* g, double* var) {
  const int n = static_cast<int>(b - a);
  Eigen::MatrixXd m(n, 3);
  Eigen::VectorXd z(n);
  const double tm = run.Time((a + b) / 2);
  for (int k = 0; k < n; ++k) {
    const double t = run.Time(a + k) - tm;
    m.row(k) << 1.0, t, t * t;
    z(k) = 0.5 * (run.z[0][a + k] + run.z[1][a + k]);
  }
  const Eigen::Matrix3d mtm = m.transpose() * m;
  const Eigen::Vector3d c = mtm.ldlt().solve(m.transpose() * z);
  const double rss = (z - m * c).squaredNorm();
  *g = -2.0 * c(2);
  *var = 4.0 * rss / std::max(1, n - 3) * mtm.inverse()(2, 2);
  return std::isfinite(*g);
}

}  // namespace

FreeFall FitFreeFall(const SampledRun& run, const Contacts& contacts) {
  FreeFall ff;
  auto airborne = [&](size_t i) {
    if (!run.Valid(i)) return false;
    for (int s = 0; s < 2; ++s) {
      const SphereContacts& c = contacts.sphere[s];
      const double clear = std::max(c.threshold_m, kFreeFlightMinGapRel * run.diameter_m);
      if (!(c.gap[i] - c.level_m > clear)) return false;
    }
    return true;
  };
  // Impacts split flights even when no frame falls within the contact threshold (a fast bounce
  // passes the plate between two frames): a parabola never spans one.
  std::vector<uint8_t> impact_after(run.n, 0);  // 1: an impact lies between frame i and i + 1
  for (const Impact& imp : contacts.AllImpacts()) {
    const long k = static_cast<long>(std::floor(imp.frame));
    if (k >= 0 && k < static_cast<long>(run.n)) impact_after[k] = 1;
    if (k >= 1 && static_cast<double>(k) == imp.frame) impact_after[k - 1] = 1;
  }
  double wsum = 0, gsum = 0;
  bool exact = false;  // a noise-free flight (simulation): its g is exact, use it alone
  size_t i = 0;
  while (i < run.n) {
    if (!airborne(i)) {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < run.n && airborne(j) && !impact_after[j - 1]) ++j;
    const size_t a = i + kFreeFlightTrimFrames, b = j - kFreeFlightTrimFrames;
    double g = 0, var = 0;
    if (b > a && b - a >= static_cast<size_t>(kMinFreeFlightFrames) && FitFlight(run, a, b, &g, &var)) {
      ++ff.flights;
      ff.frames += static_cast<int>(b - a);
      if (var <= 0) {
        exact = true, gsum = g, wsum = 1;
      } else if (!exact) {
        gsum += g / var, wsum += 1 / var;
      }
    }
    i = j;
  }
  if (ff.flights == 0) {
    ff.note = "no free flight: never both spheres " + std::to_string(kFreeFlightMinGapRel) .substr(0, 4) +
              " d or more above the plate for " +
              std::to_string(kMinFreeFlightFrames + 2 * kFreeFlightTrimFrames) + " frames";
    return ff;
  }
  ff.g_fit = gsum / wsum;
  ff.g_fit_err = exact ? 0.0 : std::sqrt(1.0 / wsum);
  return ff;
}

}  // namespace dimer::compare
