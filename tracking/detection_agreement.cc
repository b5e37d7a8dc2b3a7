#include "tracking/detection_agreement.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dimer::tracking {
namespace {

// Along `axis`: the least-squares slope of the rough positions on the learnt ones, with its
// standard error and both spreads.
DetectionAgreement AlongAxis(const LearntSphere& s, int axis) {
  DetectionAgreement a;
  a.axis = axis;
  const size_t n = std::min(s.rough.size(), s.registered.size());
  if (n < 3) return a;
  double mx = 0, my = 0;
  for (size_t i = 0; i < n; ++i) {
    mx += s.registered[i](axis) / double(n);
    my += s.rough[i](axis) / double(n);
  }
  double sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < n; ++i) {
    const double dx = s.registered[i](axis) - mx, dy = s.rough[i](axis) - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  a.learnt_sd = std::sqrt(sxx / double(n - 1));
  a.rough_sd = std::sqrt(syy / double(n - 1));
  a.residual_sd = std::sqrt(std::max(0.0, sxx + syy - 2 * sxy) / double(n - 1));
  if (!(sxx > 0)) return a;
  a.slope = sxy / sxx;
  a.slope_err = std::sqrt(std::max(0.0, syy - a.slope * sxy) / double(n - 2) / sxx);
  return a;
}

// How many standard errors the slope lies outside the band (<= 0: inside, or undecided; an
// exact line outside it, infinitely many).
double SigmasOutside(const DetectionAgreement& a) {
  if (!std::isfinite(a.slope)) return 0;
  const double outside = std::max(a.slope - kDetectionSlopeBand, 1 / kDetectionSlopeBand - a.slope);
  if (!(a.slope_err > 0)) return outside > 0 ? std::numeric_limits<double>::infinity() : 0;
  return outside / a.slope_err;
}

}  // namespace

DetectionAgreement AgreementWithDetections(const LearntSphere& s) {
  DetectionAgreement col = AlongAxis(s, 0), row = AlongAxis(s, 1);
  DetectionAgreement& worst = SigmasOutside(row) > SigmasOutside(col) ? row : col;
  worst.agrees = !(SigmasOutside(worst) > kDetectionSlopeSigmas);
  return worst;
}

double WidenForDisagreement(const DetectionAgreement& a, double err) {
  if (a.agrees || !std::isfinite(a.residual_sd)) return err;
  return std::hypot(err, a.residual_sd);
}

}  // namespace dimer::tracking
