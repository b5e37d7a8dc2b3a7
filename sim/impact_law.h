#pragma once
// Frictional impacts of one or two spheres with the plate (docs/MODEL.md, phases 2 and 4).
//
// Single contact: Routh's method. The accumulated normal impulse P_N is the independent
// variable; while the contact slides, dP_T = -sgn(U) mu_hat dP_N; when U reaches 0 the contact
// sticks if the tangential/normal impulse ratio needed to keep U = 0 is within mu_hat_s,
// otherwise slip reverses. The impact ends when V reaches Newton's target -eps V_b.
// Every rate is constant between such events, so the integration is exact: a sequence of
// linear segments whose ends are solved in closed form, not an ODE.
//
// Two contacts ("water-filling" law, our documented choice). Each touching contact i has a
// Newton target V_i* = -eps_i min(V_b,i, 0) and a deficit g_i = V_i - V_i*. Impulse always goes
// to the contact(s) with the most negative deficit; when two deficits are equal they receive
// normal impulse in the ratio that keeps them equal (a 2x2 solve, friction included), and a
// contact whose share would turn negative leaves the active set. The impact ends when no
// deficit is negative. Properties (tested in impact_law_test):
//  - a contact whose deficit is never the lowest receives nothing: the law reduces exactly to
//    the single-contact law when the other contact separates at once;
//  - a flat symmetric impact gives V_a = -eps V_b at both contacts;
//  - frictionless: every contact that took impulse ends exactly at its target, so
//    dE = sum_i P_i (1 - eps_i) V_b,i / 2 <= 0, with equality for eps = 1 (energy conserved).
//    With friction, energy is checked by property tests over random impacts.
// Energy: Newton's kinematic restitution with friction can create energy when slip stops or
// reverses during restitution (Stronge 1990). The default law, `capped`, is Newton's wherever
// Newton's creates no energy (every paper case we measured) and otherwise scales all targets
// down by the largest common factor that does not; `newton` is the plain law.
// Inelastic collapse: a contact approaching slower than v_c gets eps_i = 0 (plastic) and
// stays in persistent contact; the decaying series of small bounces is thereby cut off at v_c,
// whose effect is measured in bench/bench_sim_accuracy.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

struct ImpactOutcome {
  State after;
  std::array<double, 2> pn{}, pt{};     // normal / tangential impulse per unit mass, m/s
  std::array<bool, 2> took_part{};      // received normal impulse
  std::array<bool, 2> stuck{};          // ended sticking (U = 0)
  std::array<bool, 2> reversed{};       // slip reversed during the impact
  std::array<bool, 2> collapsed{};      // approach slower than v_c: ended in persistent contact
  std::array<double, 2> v_before{};     // V_b at each contact, m/s
  int segments = 0;
  bool ok = true;                       // false: no progress or segment cap (counted by caller)
  double energy_gain = 0;               // kinetic energy plain Newton would add (>0: capped)
  double restitution_scale = 1;         // capped law: factor applied to the Newton targets
};

// `touching[s]`: sphere s is at the plate. `forced[s]`: treat s as active even with a zero
// deficit (impact without collision, used to resolve Painleve's paradox in persistent contact).
ImpactOutcome ResolveImpact(const Model& m, const State& before, std::array<bool, 2> touching,
                            std::array<bool, 2> forced = {false, false});

}  // namespace dimer::sim
