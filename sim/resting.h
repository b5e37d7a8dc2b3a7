#pragma once
// The rest state in closed form: a flat dimer with both spheres sticking on the plate, at rest
// relative to it. Its contact forces (persistent_contact.h, flat pair with w = 0) are
//   N_0 + N_1 = g cos(alpha) + zddot_p(t),   F_0 + F_1 = g sin(alpha),
//   N_0 - N_1 = cos(theta) (F_0 + F_1) / A    (torque balance about the CM, r_z = -R: the
//                                              downhill sphere presses more),
// and its accelerations are exactly zero. With zddot_p(t) >= -a Omega^2 the state provably stays
// put over the whole plate cycle (no lift-off, no slip, for every t) when
//   g cos(alpha) - a Omega^2 > g |sin(alpha)| / A        (both normal forces stay positive),
//   g |sin(alpha)| <= mu_s (g cos(alpha) - a Omega^2)    (the sum, hence each contact's
//                                                          proportional share, stays inside
//                                                          the static cone),
// each with a margin far above round-off. Nothing then changes in the plate frame, so the
// simulator advances such a state by whole stages at no cost (simulator.cc); the step-by-step
// path gives the same samples (tests/sim/resting_test.cc). A flat dimer with Gamma >= cos(alpha),
// beyond the friction angle, or sliding, is never taken for resting. One sphere alone on the
// plate never rests: gravity's torque about its contact turns the dimer unless theta = pi/2.
#include "sim/model.h"
#include "sim/persistent_contact.h"
#include "sim/state.h"

namespace dimer::sim {

// True when the plate's drive and tilt keep a flat, sticking dimer inside its cones for the
// whole cycle (the inequalities above, with margin): a property of the model alone.
bool RestHoldsOverTheCycle(const Model& m);

// True when (cfg, q) is the rest state (both spheres sticking, flat as projected, no velocity
// relative to the plate) and RestHoldsOverTheCycle(m): q then stays exactly where it is.
bool StaysPut(const Model& m, const ContactConfig& cfg, const State& q);

}  // namespace dimer::sim
