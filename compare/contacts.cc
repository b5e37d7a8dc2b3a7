#include "compare/contacts.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "compare/noise.h"

namespace dimer::compare {
namespace {

// The rest level: the densest band of width 2 thr that starts among the lowest 2 % of the gaps
// (a sphere cannot rest above where it touches; the slow apex of a bounce is dense too, but
// high); NaN if that band holds too few frames, or if they are not gathered about its middle
// as a rest's noise is. A sphere that only passes through the band on its way to and from the
// plate fills it evenly: at a camera's noise (thr of 0.1-0.3 mm) that can be 5-10 % of a
// bouncing end's frames (a POV-Ray film of the drift: 8 %, its level then 0.14 mm high).
double RestLevel(const std::vector<double>& gap, double thr) {
  std::vector<double> v;
  for (double g : gap)
    if (std::isfinite(g)) v.push_back(g);
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  size_t best_i = 0, best_n = 0, j = 0;
  const size_t starts = std::max<size_t>(1, v.size() / 50);
  for (size_t i = 0; i < starts; ++i) {
    j = std::max(j, i);
    while (j < v.size() && v[j] <= v[i] + 2 * thr) ++j;
    if (j - i > best_n) best_n = j - i, best_i = i;
  }
  if (best_n < kRestLevelMinFraction * v.size()) return kNaN;
  const double mid = v[best_i + best_n / 2];
  size_t core = 0;  // within thr / 2 (2 sigma) of the middle: 95 % for a rest, 50 % if even
  for (size_t k = best_i; k < best_i + best_n; ++k) core += std::abs(v[k] - mid) <= 0.5 * thr;
  if (core < kRestCoreMinFraction * best_n) return kNaN;
  return mid;
}

struct Quadratic {  // g(tau) = c0 + c1 tau + c2 tau^2, tau in frames
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  int points = 0;
  double At(double tau) const { return c(0) + tau * (c(1) + tau * c(2)); }
  double Slope(double tau) const { return c(1) + 2 * c(2) * tau; }
};

// Least-squares polynomial (degree 2, or 1 with fewer than 4 points) through frames `idx`.
Quadratic FitFrames(const std::vector<double>& g, const std::vector<long>& idx, double tau0) {
  Quadratic q;
  q.points = static_cast<int>(idx.size());
  if (q.points < 2) return q;
  const int deg = q.points >= 4 ? 2 : 1;
  Eigen::MatrixXd a(q.points, deg + 1);
  Eigen::VectorXd b(q.points);
  for (int k = 0; k < q.points; ++k) {
    const double tau = static_cast<double>(idx[k]) - tau0;
    for (int p = 0; p <= deg; ++p) a(k, p) = std::pow(tau, p);
    b(k) = g[idx[k]];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  for (int p = 0; p <= deg; ++p) q.c(p) = c(p);
  return q;
}

// Root of p(tau) = 0 in [lo, hi] nearest `lo` (p quadratic); NaN if none.
double RootIn(const Quadratic& p, double lo, double hi) {
  const double a = p.c(2), b = p.c(1), c = p.c(0);
  std::vector<double> roots;
  if (std::abs(a) < 1e-300) {
    if (b != 0) roots.push_back(-c / b);
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      roots.push_back(q / a);
      if (q != 0) roots.push_back(c / q);
    }
  }
  double best = kNaN;
  for (double r : roots)
    if (r >= lo && r <= hi && !(r >= best)) best = r;
  return best;
}

// Where the approach `a` and the departure `d` meet in [lo, hi] (nearest lo); NaN if they do not.
double Meet(const Quadratic& a, const Quadratic& d, double lo, double hi) {
  Quadratic diff;
  diff.c = a.c - d.c;
  return RootIn(diff, lo, hi);
}

constexpr int kLandingBisections = 40;  // landing time to 1e-12 of a frame

class ImpactFinder {
 public:
  ImpactFinder(const SampledRun& run, const PlateDrive& plate, int s, SphereContacts* c)
      : run_(run), plate_(plate), s_(s), c_(*c) {
    // Fits are made in the lab frame (gap + the plate model): a tip in flight is a parabola
    // there, while the gap also carries the plate's sinusoid, which a quadratic follows less
    // well over the fitted frames.
    lab_.resize(c_.gap.size());
    for (size_t k = 0; k < lab_.size(); ++k) lab_[k] = c_.gap[k] + plate_.Z(run_.Time(k));
  }

  void Run() {
    const auto& g = c_.gap;
    const long n = static_cast<long>(g.size());
    const double lvl = c_.level_m, thr = c_.threshold_m;
    double peak = -INFINITY;  // highest gap since the last contact
    bool in_flight = false;
    for (long i = 0; i < n; ++i) {
      if (!std::isfinite(g[i])) {  // a gap in the data ends any flight unseen
        in_flight = false, peak = -INFINITY;
        continue;
      }
      const bool on = g[i] - lvl <= thr;  // below the level counts as touching
      if (!on) {
        // A minimum the gap fell into by more than thr (not a dip of noise on the way up).
        if (in_flight && IsBounceMinimum(i) && peak >= lvl + 2 * thr && peak - g[i] > thr &&
            AddImpact(i, /*touch_end=*/i, /*bounce=*/true, peak)) {
          peak = -INFINITY;
        }
        in_flight = true;
        peak = std::max(peak, g[i]);
        continue;
      }
      if (on && in_flight && peak >= lvl + 2 * thr) {
        long end = i;  // the touch: frames on the plate from i
        for (;;) {
          while (end + 1 < n && std::isfinite(g[end + 1]) && g[end + 1] - lvl <= thr) ++end;
          // Frames above thr that come back to the plate without rising 2 thr (no flight, by
          // the rule above) are part of the touch: camera noise lifts a frame of it now and then.
          long k = end + 1;
          while (k < n && std::isfinite(g[k]) && g[k] - lvl > thr && g[k] - lvl < 2 * thr) ++k;
          if (k == end + 1 || k >= n || !std::isfinite(g[k]) || g[k] - lvl > thr) break;
          end = k;
        }
        const bool lifts = end + 1 < n && std::isfinite(g[end + 1]) && g[end + 1] > lvl + thr;
        bool bounce = end - i + 1 < kMinRestFrames && lifts;
        // A touch of kMinRestFrames or more that the bounce's V (the flights before and after
        // it, meeting at the plate) passes less than thr below in every frame was no rest: with
        // a camera's noise the bottom of a V holds 3-5 frames within thr of the plate.
        if (!bounce && lifts && TouchOnTheBouncesV(i, end)) {
          bounce = true;
          std::fill(c_.resting.begin() + i, c_.resting.begin() + end + 1, 0);
        }
        // A touch too short to be a rest, with no frame after it (the data ends or has a gap),
        // is unresolved: the impact may be at the data's edge or beyond. Not counted.
        const bool unresolved = !bounce && end - i + 1 < kMinRestFrames &&
                                (end + 1 >= n || !std::isfinite(g[end + 1]));
        if (!unresolved) AddImpact(i, end, bounce, peak);
      }
      in_flight = false;
      peak = -INFINITY;
    }
  }

 private:
  // A local minimum of the gap from which the plate is within one frame's travel.
  bool IsBounceMinimum(long i) const {
    const auto& g = c_.gap;
    if (i < 1 || i + 1 >= static_cast<long>(g.size())) return false;
    if (!std::isfinite(g[i - 1]) || !std::isfinite(g[i + 1])) return false;
    if (!(g[i] <= g[i - 1] && g[i] < g[i + 1])) return false;
    const double reach = std::max(g[i - 1] - g[i], g[i + 1] - g[i]);
    return g[i] - c_.level_m <= c_.threshold_m + reach;
  }

  // Whether the approach before `first` and the departure after `last`, fitted as flights in the
  // lab frame, meet between them and pass less than thr below every frame from `first` to
  // `last`. A rest holds the sphere above the V (which runs on into the plate); a frame below
  // it is noise, or a bounce deeper than fitted, never a rest.
  bool TouchOnTheBouncesV(long first, long last) const {
    const std::vector<long> before = Side(first - 1, -1), after = Side(last + 1, +1);
    if (before.size() < kImpactMinFitFrames || after.size() < kImpactMinFitFrames) return false;
    const double tau0 = static_cast<double>(first);
    const Quadratic qa = FitFrames(lab_, before, tau0), qd = FitFrames(lab_, after, tau0);
    const double kink = Meet(qa, qd, static_cast<double>(before.back()) - tau0,
                             static_cast<double>(after.front()) - tau0);
    if (!std::isfinite(kink)) return false;
    for (long k = first; k <= last; ++k) {
      const double tau = static_cast<double>(k) - tau0;
      const double v = tau < kink ? qa.At(tau) : qd.At(tau);
      if (!(lab_[k] - v <= c_.threshold_m)) return false;
    }
    return true;
  }

  // Whether the gap after the minimum at frame `i` rises more than thr above it before it is
  // on the plate again (the data's end or a gap in it: unknown, taken as yes).
  bool RisesFromTheMinimum(long i) const {
    const auto& g = c_.gap;
    for (long k = i + 1; k < static_cast<long>(g.size()) && std::isfinite(g[k]); ++k) {
      if (g[k] - g[i] > c_.threshold_m) return true;
      if (g[k] - c_.level_m <= c_.threshold_m) return false;
    }
    return true;
  }

  // Frames of the approach (before `first`) or departure (after `last`) that are airborne.
  std::vector<long> Side(long from, int dir) const {
    std::vector<long> idx;
    const auto& g = c_.gap;
    for (long k = from; k >= 0 && k < static_cast<long>(g.size()) &&
                        static_cast<int>(idx.size()) < kImpactFitFrames;
         k += dir) {
      if (!std::isfinite(g[k]) || g[k] <= c_.level_m + c_.threshold_m) break;
      idx.push_back(k);
    }
    if (dir < 0) std::reverse(idx.begin(), idx.end());
    return idx;
  }

  struct Solution {
    double tau = kNaN;  // impact, frames from tau0
    double v_before = kNaN, v_after = kNaN, level = kNaN;
    Quadratic approach;  // fitted to the approach (points < 2: none)
  };

  // The impact from approach frames `before` and departure frames `after` (empty: a landing,
  // the approach meets the contact level before frame `land_limit`).
  Solution Solve(const std::vector<long>& before, const std::vector<long>& after, double tau0,
                 double land_limit) const {
    Solution sol;
    const Quadratic qa = FitFrames(lab_, before, tau0);
    sol.approach = qa;
    if (qa.points < 2) return sol;
    auto time = [&](double tau) { return run_.t0 + (tau0 + tau) * run_.dt; };
    const double lo = static_cast<double>(before.back()) - tau0;
    if (after.size() >= 2) {
      const Quadratic qd = FitFrames(lab_, after, tau0);
      sol.tau = Meet(qa, qd, lo, static_cast<double>(after.front()) - tau0);
      if (std::isfinite(sol.tau)) sol.v_after = qd.Slope(sol.tau) / run_.dt - plate_.V(time(sol.tau));
    }
    if (!std::isfinite(sol.tau)) {  // landing: the approach meets the plate + contact level
      auto h = [&](double tau) { return qa.At(tau) - plate_.Z(time(tau)) - c_.level_m; };
      double a = lo, b = land_limit;
      if (h(a) > 0 && h(b) <= 0) {
        for (int it = 0; it < kLandingBisections; ++it) (h(0.5 * (a + b)) > 0 ? a : b) = 0.5 * (a + b);
        sol.tau = 0.5 * (a + b);
      }
    }
    if (std::isfinite(sol.tau)) {
      sol.v_before = qa.Slope(sol.tau) / run_.dt - plate_.V(time(sol.tau));
      sol.level = qa.At(sol.tau) - plate_.Z(time(sol.tau));
    }
    return sol;
  }

  // Impact::speed_bound for a flight whose highest sampled gap was `peak`: the apex can fall
  // between two samples, at most (1 + Gamma) g dt^2 / 8 above the higher of them.
  double SpeedBound(double peak) const {
    const double accel = (1 + plate_.gamma) * kGravity;
    const double h = peak - c_.level_m + accel * run_.dt * run_.dt / 8;
    return std::sqrt(2 * accel * std::max(0.0, h));
  }

  // `first`: first frame of the touch (or the bounce minimum); `last`: its last frame; `peak`:
  // the highest gap of the flight that ends there.
  // Returns false, adding nothing, for a minimum that is noise on a flight (below).
  bool AddImpact(long first, long last, bool bounce, double peak) {
    const bool minimum = first == last && c_.gap[first] > c_.level_m + c_.threshold_m;
    const double tau0 = static_cast<double>(first);
    const double land_limit = static_cast<double>(last - first) + 1.0;
    std::vector<long> before = Side(first - 1, -1);
    std::vector<long> after = bounce ? Side(minimum ? first + 1 : last + 1, +1) : std::vector<long>{};
    Solution sol = Solve(before, after, tau0, land_limit);
    // Second pass without the frames within one frame of the impact: their exposure may straddle
    // it (motion blur lifts them above the V), and the tracker is least sure next to the plate.
    if (std::isfinite(sol.tau)) {
      const double t_imp = tau0 + sol.tau;
      std::vector<long> b2, a2;
      for (long k : Side(static_cast<long>(std::floor(t_imp - 1.0)), -1)) b2.push_back(k);
      if (bounce) a2 = Side(static_cast<long>(std::ceil(t_imp + 1.0)), +1);
      if (b2.size() >= kImpactMinFitFrames && (!bounce || a2.size() >= kImpactMinFitFrames)) {
        const Solution refined = Solve(b2, a2, tau0, land_limit);
        if (std::isfinite(refined.tau)) sol = refined;
      }
    }
    // A minimum above the plate is an impact only where a falling flight meets a rising one.
    // Camera noise (sigma a third of a frame's travel) also makes minima on the way down, the
    // plate reached a frame or two later, and on the way up: the gap does not rise more than
    // thr from it before it is back on the plate, or the approach fitted to it rises.
    if (minimum && (!RisesFromTheMinimum(first) || sol.v_before >= 0)) return false;
    Impact imp;
    imp.sphere = s_;
    imp.bounce = bounce;
    if (!std::isfinite(sol.tau)) sol.tau = minimum ? 0.0 : -0.5;  // no usable fit: the frame itself
    // Flights too short for the approach and departure to meet (a resting end's micro-bounces
    // of a few frames): the approach's slope at that frame is the best measure of its speed,
    // which decides whether it counts (periods.h; ImpactCount.*).
    if (!std::isfinite(sol.v_before) && sol.approach.points >= 2) {
      const double t = run_.t0 + (tau0 + sol.tau) * run_.dt;
      sol.v_before = sol.approach.Slope(sol.tau) / run_.dt - plate_.V(t);
    }
    imp.v_before = sol.v_before;
    imp.v_after = sol.v_after;
    imp.speed_bound = SpeedBound(peak);
    imp.level_m = sol.level;
    imp.frame = tau0 + sol.tau;
    imp.t = run_.t0 + imp.frame * run_.dt;
    imp.plate_phase = std::isfinite(plate_.freq_hz) ? plate_.PhaseFraction(imp.t) : kNaN;
    c_.impacts.push_back(imp);
    return true;
  }

  const SampledRun& run_;
  const PlateDrive& plate_;
  int s_;
  SphereContacts& c_;
  std::vector<double> lab_;  // gap + plate model: the sphere bottom's lab height, m
};

void MarkResting(SphereContacts* c) {
  const auto& g = c->gap;
  const size_t n = g.size();
  c->resting.assign(n, 0);
  size_t i = 0;
  while (i < n) {
    if (!(g[i] - c->level_m <= c->threshold_m)) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < n && g[j] - c->level_m <= c->threshold_m) ++j;
    if (j - i >= static_cast<size_t>(kMinRestFrames)) std::fill(c->resting.begin() + i, c->resting.begin() + j, 1);
    i = j;
  }
}

}  // namespace

std::vector<Impact> Contacts::AllImpacts() const {
  std::vector<Impact> all = sphere[0].impacts;
  all.insert(all.end(), sphere[1].impacts.begin(), sphere[1].impacts.end());
  std::sort(all.begin(), all.end(), [](const Impact& a, const Impact& b) { return a.t < b.t; });
  return all;
}

Contacts FindContacts(const SampledRun& run, const PlateDrive& plate,
                      const std::array<double, 2>& min_threshold_m) {
  Contacts out;
  const double radius = 0.5 * run.diameter_m;
  std::array<double, 2> levels{kNaN, kNaN};
  for (int s = 0; s < 2; ++s) {
    SphereContacts& c = out.sphere[s];
    c.gap.assign(run.n, kNaN);
    for (size_t i = 0; i < run.n; ++i) {
      // A fitted plate is a sinusoid: using it rather than each frame's plate row keeps the
      // plate's own tracking noise out of the gap (a sim file's plate is exact either way).
      const bool fitted = plate.source == "fit";
      const double pz = !fitted && std::isfinite(run.plate_z[i]) ? run.plate_z[i] : plate.Z(run.Time(i));
      c.gap[i] = run.z[s][i] - pz - radius;
    }
    c.noise_m = NoiseSigma(c.gap);
    c.threshold_m = std::max(kContactSigmas * c.noise_m, kContactFloorRel * run.diameter_m);
    if (std::isfinite(min_threshold_m[s])) c.threshold_m = std::max(c.threshold_m, min_threshold_m[s]);
    levels[s] = RestLevel(c.gap, c.threshold_m);
  }
  for (int s = 0; s < 2; ++s) {
    SphereContacts& c = out.sphere[s];
    c.level_m = std::isfinite(levels[s]) ? levels[s] : std::isfinite(levels[1 - s]) ? levels[1 - s] : 0.0;
    MarkResting(&c);
    ImpactFinder(run, plate, s, &c).Run();
  }
  return out;
}

}  // namespace dimer::compare
