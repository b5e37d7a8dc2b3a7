#include "tracking/sphere/impact_vertex.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/median.h"

namespace dimer::tracking {
namespace {

// A straight line fitted to (t, y): its mean point and slope, and what is needed to state the
// uncertainty of its value at another t (Sxx) and how well it fits (the residual sum).
struct Line {
  double t_mean = 0, y_mean = 0, slope = 0, sxx = 0, ssr = 0;
  int n = 0;
  double At(double t) const { return y_mean + slope * (t - t_mean); }
  // Variance of At(t) for unit noise per point.
  double Var(double t) const { return 1.0 / n + (t - t_mean) * (t - t_mean) / sxx; }
};

// Fits y[0..count) at frames first, first + 1, ...; false where one is not finite.
bool FitArm(const double* y, size_t first, int count, Line* l) {
  l->n = count;
  double st = 0, sy = 0;
  for (int j = 0; j < count; ++j) {
    if (!std::isfinite(y[j])) return false;
    st += double(first + j);
    sy += y[j];
  }
  l->t_mean = st / count;
  l->y_mean = sy / count;
  double sty = 0;
  l->sxx = 0;
  for (int j = 0; j < count; ++j) {
    const double dt = double(first + j) - l->t_mean;
    l->sxx += dt * dt;
    sty += dt * (y[j] - l->y_mean);
  }
  l->slope = sty / l->sxx;
  l->ssr = 0;
  for (int j = 0; j < count; ++j) {
    const double r = y[j] - l->At(double(first + j));
    l->ssr += r * r;
  }
  return true;
}

// The V with the approach ending at frame `last_approach` (the rebound starting after it), or
// false where it is not one. `bend`: the gap's second difference in flight there (px per
// frame^2), taken out of both arms before the lines are fitted and put back at the vertex.
bool FitV(const std::vector<double>& gap, size_t last_approach, double noise, double bend,
          ImpactVertex* v, double* ssr) {
  constexpr int k = kImpactArmFrames;
  if (last_approach + 1 < size_t(k) || last_approach + 1 + k > gap.size()) return false;
  const size_t first = last_approach + 1 - k;
  const double t0 = double(last_approach) + 0.5;
  const auto parabola = [&](double t) { return 0.5 * bend * (t - t0) * (t - t0); };
  double y[2 * k];
  for (int j = 0; j < 2 * k; ++j) y[j] = gap[first + j] - parabola(double(first + j));
  Line in, out;
  if (!FitArm(y, first, k, &in) || !FitArm(y + k, last_approach + 1, k, &out)) return false;
  // Each arm sloped beyond its noise, the right way.
  if (!(in.slope < -kImpactMinSlopeSigmas * noise / std::sqrt(in.sxx))) return false;
  if (!(out.slope > kImpactMinSlopeSigmas * noise / std::sqrt(out.sxx))) return false;
  // Straight: the residual over both arms, per degree of freedom (4 parameters).
  const double rms = std::sqrt((in.ssr + out.ssr) / double(2 * k - 4));
  if (!(rms <= kImpactMaxResidualNoise * noise)) return false;
  // Where the lines meet: between the approach's last frame and the rebound's first, within half
  // a frame either way (noise moves the meeting point by that much).
  const double t = (out.y_mean - in.y_mean - out.slope * out.t_mean + in.slope * in.t_mean) /
                   (in.slope - out.slope);
  if (!(t >= double(last_approach) - 0.5 && t <= double(last_approach) + 1.5)) return false;
  v->time = t;
  v->value = in.At(t) + parabola(t);
  v->approach = in.slope;
  v->rebound = out.slope;
  // The meeting point moves with each line's error at t: by a1 / (a1 - b1) of the approach's
  // and -b1 / (a1 - b1) of the rebound's (b1 < 0 < a1 the slopes).
  const double wi = out.slope / (out.slope - in.slope), wo = -in.slope / (out.slope - in.slope);
  v->err = noise * std::sqrt(wi * wi * in.Var(t) + wo * wo * out.Var(t));
  v->frame = t < double(last_approach) + 0.5 ? last_approach : last_approach + 1;
  *ssr = in.ssr + out.ssr;
  return true;
}

}  // namespace

double GapNoise(const std::vector<double>& gap) {
  std::vector<double> d2;
  for (size_t i = 1; i + 1 < gap.size(); ++i) {
    const double d = gap[i + 1] - 2 * gap[i] + gap[i - 1];
    if (std::isfinite(d)) d2.push_back(std::abs(d));
  }
  if (d2.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  return MedianOf(d2) / 0.6745 / std::sqrt(6.0);
}

std::vector<ImpactVertex> ImpactVertices(const std::vector<double>& gap, double noise,
                                         const std::vector<double>& bend) {
  std::vector<ImpactVertex> found;
  std::vector<double> fit;  // the residual sum of each found V
  if (!(noise > 0)) return found;
  for (size_t i = 1; i + 1 < gap.size(); ++i) {
    // The lowest frame of three is the last of the approach or the first of the rebound.
    if (!(gap[i] <= gap[i - 1] && gap[i] <= gap[i + 1])) continue;
    // Of the two, the one whose lines meet between its arms (the lowest frame on the side of the
    // impact it lies on: near the vertex it fits either line, and on the wrong one it bends
    // that arm's slope by noise), else the better fit.
    ImpactVertex best;
    double best_ssr = std::numeric_limits<double>::infinity();
    bool best_between = false;
    for (size_t last_approach : {i, i - 1}) {
      ImpactVertex v;
      double ssr = 0;
      const double b = last_approach < bend.size() && std::isfinite(bend[last_approach])
                           ? bend[last_approach]
                           : 0.0;
      if (!FitV(gap, last_approach, noise, b, &v, &ssr)) continue;
      const bool between =
          v.time >= double(last_approach) && v.time <= double(last_approach) + 1.0;
      if ((between && !best_between) || (between == best_between && ssr < best_ssr)) {
        best = v, best_ssr = ssr, best_between = between;
      }
    }
    if (!std::isfinite(best_ssr)) continue;
    // Two candidates sharing frames (a noisy bottom with two low frames): the better fit.
    if (!found.empty() && best.frame < found.back().frame + 2 * kImpactArmFrames) {
      if (best_ssr < fit.back()) found.back() = best, fit.back() = best_ssr;
      continue;
    }
    found.push_back(best);
    fit.push_back(best_ssr);
  }
  return found;
}

std::vector<double> GapBend(const std::vector<double>& plate_rows, double gravity_px) {
  constexpr int h = kPlateBendHalfWindow;
  // The quadratic coefficient over t = -h..h by the polynomial t^2 - <t^2>, orthogonal there to
  // 1 and t: a2 = sum (t^2 - <t^2>) y / sum (t^2 - <t^2>)^2.
  double mean_t2 = 0;
  for (int t = -h; t <= h; ++t) mean_t2 += double(t * t);
  mean_t2 /= double(2 * h + 1);
  double norm = 0;
  for (int t = -h; t <= h; ++t) norm += (t * t - mean_t2) * (t * t - mean_t2);
  const double g = std::isfinite(gravity_px) ? gravity_px : 0.0;
  std::vector<double> bend(plate_rows.size(), -g);
  for (size_t i = h; i + h < plate_rows.size(); ++i) {
    double sum = 0;
    for (int t = -h; t <= h; ++t) sum += (t * t - mean_t2) * plate_rows[i + t];
    if (std::isfinite(sum)) bend[i] += 2.0 * sum / norm;
  }
  return bend;
}

}  // namespace dimer::tracking
