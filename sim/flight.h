#pragma once
// Flight: no contact. The motion is analytic in the plate frame (docs/MODEL.md, phase 1): the CM
// falls under -g cos(alpha) (normal) and -g sin(alpha) (along the plate) minus the plate's own
// displacement, and the dimer spins uniformly.
//
// Impact detection cannot miss a root. For a sphere's gap h(t) we bound the second derivative,
// |h''| <= M = g cos(alpha) + a Omega^2 + A R omega^2, and the third, |h'''| <= J = a Omega^3 +
// A R |omega|^3. From any time, both Taylor bounds h + h' tau - M tau^2/2 and
// h + h' tau + min(h'',0) tau^2/2 - J tau^3/6 are lower bounds of h; stepping by the larger
// interval on which one of them stays above -gap_tol means h cannot reach -gap_tol inside the
// step, grazing roots included. Near a root the steps shrink quadratically; the root of h = 0
// is then polished by Newton's method to kRootTimeTol_s.
#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

// State after flying for dt from q0 at time t0.
State FlightPropagate(const Model& m, const State& q0, double t0, double dt);

// The same flight at any number of times from one start (the output samples, the impact
// finder's points): the start's plate position and velocity are evaluated once, so each time
// costs one sin/cos pair, its own phase. At(dt) is FlightPropagate(m, q0, t0, dt), bit for bit.
class FlightPath {
 public:
  FlightPath(const Model& m, const State& q0, double t0);
  State At(double dt) const { return At(dt, m_.Phase(t0_ + dt)); }
  State At(double dt, Model::PlatePhase p1) const;  // p1: the phase at t0 + dt
  const Model& model() const { return m_; }
  const State& start() const { return q0_; }
  double t0() const { return t0_; }
  Model::PlatePhase start_phase() const { return p0_; }  // also the phase of dt = 0

 private:
  const Model& m_;
  State q0_;
  double t0_;
  Model::PlatePhase p0_;
  double zp0_, vp0_;
};

struct GapDerivatives {
  double h, hd, hdd;  // m, m/s, m/s^2
};
GapDerivatives FlightGap(const Model& m, const State& q0, double t0, double dt, int sphere);

struct ImpactSearch {
  bool found = false;
  double dt = 0;     // time of the root after t0, s
  int steps = 0;     // safe steps taken (diagnostic)
  bool capped = false;  // the step cap was reached before dt_max: result unreliable
};
// Earliest root of the gap of `sphere` in (0, dt_max]. A sphere already touching and leaving
// (h ~ 0, h' >= 0) is not reported until it comes back.
ImpactSearch FindFlightImpact(const Model& m, const State& q0, double t0, double dt_max,
                              int sphere);

}  // namespace dimer::sim
