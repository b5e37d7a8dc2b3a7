#include "compare/outliers.h"

#include <algorithm>
#include <cmath>

#include "compare/noise.h"

namespace dimer::compare {
namespace {

double LocalMedian(const std::vector<double>& v, long i) {
  std::vector<double> w;
  const long n = static_cast<long>(v.size());
  for (long k = std::max(0L, i - kOutlierHalfWindow); k <= std::min(n - 1, i + kOutlierHalfWindow); ++k)
    if (std::isfinite(v[k])) w.push_back(v[k]);
  if (w.size() < 3) return NAN;
  std::nth_element(w.begin(), w.begin() + w.size() / 2, w.end());
  return w[w.size() / 2];
}

}  // namespace

std::vector<Outlier> RejectOutliers(SampledRun* run) {
  std::vector<Outlier> out;
  for (int s = 0; s < 2; ++s) {
    const double bound_x = std::max(kOutlierSigmas * NoiseSigma(run->x[s]), kOutlierRel * run->diameter_m);
    const double bound_z = std::max(kOutlierSigmas * NoiseSigma(run->z[s]), kOutlierRel * run->diameter_m);
    std::vector<size_t> bad;
    std::vector<double> dev;
    for (size_t i = 0; i < run->n; ++i) {
      const double dx = std::abs(run->x[s][i] - LocalMedian(run->x[s], static_cast<long>(i)));
      const double dz = std::abs(run->z[s][i] - LocalMedian(run->z[s], static_cast<long>(i)));
      if (dx > bound_x || dz > bound_z) {
        bad.push_back(i);
        dev.push_back(std::max(dx, dz));
      }
    }
    for (size_t k = 0; k < bad.size(); ++k) {
      run->x[s][bad[k]] = run->z[s][bad[k]] = NAN;
      out.push_back({bad[k], s, dev[k]});
    }
  }
  std::sort(out.begin(), out.end(), [](const Outlier& a, const Outlier& b) { return a.frame < b.frame; });
  if (!out.empty()) {
    for (const Outlier& o : out) run->theta[o.frame] = NAN;
    FindGaps(run);
  }
  return out;
}

}  // namespace dimer::compare
