#include "sim/flight.h"

#include <algorithm>
#include <cmath>

#include "sim/constants.h"

namespace dimer::sim {

namespace {

GapDerivatives GapAt(const FlightPath& o, double dt, int sphere) {
  const Model::PlatePhase p1 = dt == 0 ? o.start_phase() : o.model().Phase(o.t0() + dt);
  const State q = o.At(dt, p1);  // t0 + 0 is t0: the start's phase
  const Arm r = ContactArm(o.model(), q.th, sphere);
  const double ar_sin = r.rz + o.model().R;  // s A R sin(theta)
  return {q.z + r.rz, NormalV(r, q), o.model().Gz(p1) - ar_sin * q.w * q.w};
}

}  // namespace

// The impact finder evaluates hundreds of points from one start: one sin/cos pair per point
// instead of six calls.
FlightPath::FlightPath(const Model& m, const State& q0, double t0)
    : m_(m), q0_(q0), t0_(t0), p0_(m.Phase(t0)), zp0_(m.PlateZ(p0_)), vp0_(m.PlateV(p0_)) {}

State FlightPath::At(double dt, Model::PlatePhase p1) const {
  const double gz = kGravity * m_.cos_a;
  // Plate displacement beyond its linear extrapolation: the plate frame's fictitious force.
  const double dzp = m_.PlateZ(p1) - zp0_ - vp0_ * dt;
  const double dvp = m_.PlateV(p1) - vp0_;
  State q;
  q.x = q0_.x + q0_.u * dt + 0.5 * m_.Gx() * dt * dt;
  q.z = q0_.z + q0_.v * dt - 0.5 * gz * dt * dt - dzp;
  q.th = q0_.th + q0_.w * dt;
  q.u = q0_.u + m_.Gx() * dt;
  q.v = q0_.v - gz * dt - dvp;
  q.w = q0_.w;
  return q;
}

State FlightPropagate(const Model& m, const State& q0, double t0, double dt) {
  return FlightPath(m, q0, t0).At(dt);
}

GapDerivatives FlightGap(const Model& m, const State& q0, double t0, double dt, int sphere) {
  return GapAt(FlightPath(m, q0, t0), dt, sphere);
}

namespace {

// Largest tau for which c0 + c1 tau - c2 tau^2 - c3 tau^3 > 0 on [0, tau] (c0 > 0, c2, c3 >= 0),
// to 1e-3 relative: the polynomial is concave on tau > 0, so it has one positive root, and a
// bracket [lo, hi] of it shrinks from both sides at once: the chord between the ends lies below
// the polynomial, so its zero is a new lower end (still safe), and the tangent at hi lies
// above it, so its zero (Newton from the right) is a new upper end. A few iterations instead
// of a bisection's ten or more; the lower end is returned, which is always safe.
double SafeCubicStep(double c0, double c1, double c2, double c3, double cap) {
  auto L = [&](double t) { return c0 + t * (c1 - t * (c2 + t * c3)); };
  auto slope = [&](double t) { return c1 - t * (2 * c2 + 3 * t * c3); };
  double hi = cap, fhi = L(cap);
  if (fhi > 0) return cap;
  double lo = 0, flo = c0;
  for (int i = 0; i < 60 && hi - lo > 1e-3 * hi; ++i) {
    const double d = slope(hi);  // < 0: beyond the root of a concave function
    if (d < 0) {
      const double next = hi - fhi / d;
      if (next > lo && next < hi) hi = next, fhi = L(hi);
    }
    const double chord = lo + (hi - lo) * (flo / (flo - fhi));
    const double fc = L(chord);
    if (chord > lo && chord < hi && fc > 0) {
      lo = chord, flo = fc;
    } else {  // round-off at the root: halve instead (the bisection's step)
      const double mid = 0.5 * (lo + hi);
      const double fm = L(mid);
      if (fm > 0) {
        lo = mid, flo = fm;
      } else {
        hi = mid, fhi = fm;
      }
    }
  }
  return lo;
}

}  // namespace

ImpactSearch FindFlightImpact(const Model& m, const State& q0, double t0, double dt_max,
                              int sphere) {
  ImpactSearch out;
  const FlightPath origin(m, q0, t0);
  const double arm = m.A * m.R;
  const double M = kGravity * m.cos_a + m.amp * m.omega_p * m.omega_p + arm * q0.w * q0.w;
  const double aw = std::abs(q0.w);  // cubes by products: pow() cost 3 % of a drift run
  const double J = m.amp * (m.omega_p * m.omega_p * m.omega_p) + arm * (aw * aw * aw);
  // A flight that runs for more than a few hundred thousand safe steps is a grazing pathology;
  // report it rather than hang.
  constexpr int kMaxSteps = 2000000;
  double tau = 0;
  while (out.steps < kMaxSteps) {
    ++out.steps;
    const GapDerivatives g = GapAt(origin, tau, sphere);
    // A sphere at the plate with a round-off-sized approach speed that is already turning
    // away (h'' > 0) dips at most to h - h'^2 / (2 h''): within tolerance it is leaving.
    const bool leaving = g.hdd > 0 && g.h - g.hd * g.hd / (2 * g.hdd) > -m.gap_tol;
    if (g.h <= m.gap_tol && g.hd < 0 && !leaving) {
      // Approaching and within tolerance: Newton to h = 0 (converges from either side).
      for (int i = 0; i < kMaxNewtonIterations; ++i) {
        const GapDerivatives gi = i == 0 ? g : GapAt(origin, tau, sphere);  // g is at tau
        if (gi.hd >= 0) break;
        const double step = -gi.h / gi.hd;
        tau = std::max(0.0, tau + step);
        if (std::abs(step) < kRootTimeTol_s) break;
      }
      if (tau > dt_max) return out;
      out.found = true;
      out.dt = tau;
      return out;
    }
    const double c0 = g.h + m.gap_tol;
    const double remaining = dt_max - tau;
    if (remaining <= 0) return out;
    const double quad = (g.hd + std::sqrt(g.hd * g.hd + 2.0 * M * c0)) / M;
    const double cubic = SafeCubicStep(c0, g.hd, 0.5 * std::max(-g.hdd, 0.0), J / 6.0, remaining);
    tau += std::min(std::max(quad, cubic), remaining);
    if (tau >= dt_max) {
      // Last look at the end point (the step guarantees h > -gap_tol up to here).
      const GapDerivatives ge = GapAt(origin, dt_max, sphere);
      if (!(ge.h <= m.gap_tol && ge.hd < 0)) return out;
      tau = dt_max;
    }
  }
  out.capped = true;
  return out;
}

}  // namespace dimer::sim
