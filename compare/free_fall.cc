#include "compare/free_fall.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace dimer::compare {
namespace {

// One flight [a, b): the centre of mass's acceleration, as g along -x and along -z, with their
// variances from a quadratic fit of each, the residuals giving the noise.
struct FlightFit {
  double gx = 0, gz = 0, var_x = 0, var_z = 0;
};

bool FitFlight(const SampledRun& run, size_t a, size_t b, FlightFit* f) {
  const int n = static_cast<int>(b - a);
  Eigen::MatrixXd m(n, 3);
  Eigen::MatrixXd xz(n, 2);
  const double tm = run.Time((a + b) / 2);
  for (int k = 0; k < n; ++k) {
    const double t = run.Time(a + k) - tm;
    m.row(k) << 1.0, t, t * t;
    xz(k, 0) = 0.5 * (run.x[0][a + k] + run.x[1][a + k]);
    xz(k, 1) = 0.5 * (run.z[0][a + k] + run.z[1][a + k]);
  }
  const Eigen::Matrix3d mtm = m.transpose() * m;
  const Eigen::MatrixXd c = mtm.ldlt().solve(m.transpose() * xz);
  const double scale = 4.0 / std::max(1, n - 3) * mtm.inverse()(2, 2);
  f->gx = -2.0 * c(2, 0);
  f->gz = -2.0 * c(2, 1);
  f->var_x = scale * (xz.col(0) - m * c.col(0)).squaredNorm();
  f->var_z = scale * (xz.col(1) - m * c.col(1)).squaredNorm();
  return std::isfinite(f->gx) && std::isfinite(f->gz);
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
  // Inverse-variance sums of g along -x and -z; a noise-free flight (simulation) is exact, and
  // is used alone.
  double wx = 0, sx = 0, wz = 0, sz = 0;
  bool exact = false;
  size_t i = 0;
  while (i < run.n) {
    if (!airborne(i)) {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < run.n && airborne(j) && !impact_after[j - 1]) ++j;
    const size_t a = i + kFreeFlightTrimFrames, b = j - kFreeFlightTrimFrames;
    FlightFit f;
    if (b > a && b - a >= static_cast<size_t>(kMinFreeFlightFrames) && FitFlight(run, a, b, &f)) {
      ++ff.flights;
      ff.frames += static_cast<int>(b - a);
      if (f.var_z <= 0) {
        exact = true, sx = f.gx, wx = 1, sz = f.gz, wz = 1;
      } else if (!exact) {
        // x can be exact where z is not (a flight straight up): its weight is then z's.
        const double vx = f.var_x > 0 ? f.var_x : f.var_z;
        sx += f.gx / vx, wx += 1 / vx, sz += f.gz / f.var_z, wz += 1 / f.var_z;
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
  const double gx = sx / wx, gz = sz / wz;
  const double var_x = exact ? 0.0 : 1.0 / wx, var_z = exact ? 0.0 : 1.0 / wz;
  const double g2 = gx * gx + gz * gz;
  ff.g_fit = std::sqrt(g2);
  ff.g_fit_err = std::sqrt((gx * gx * var_x + gz * gz * var_z) / g2);
  ff.tilt_deg = std::atan2(gx, gz) * 180 / std::numbers::pi;
  ff.tilt_deg_err = std::sqrt((gz * gz * var_x + gx * gx * var_z) / (g2 * g2)) * 180 / std::numbers::pi;
  return ff;
}

}  // namespace dimer::compare
