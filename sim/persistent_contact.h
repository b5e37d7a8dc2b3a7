#pragma once
// Persistent contact ("rolling", docs/MODEL.md phase 3): one or both spheres stay on the plate with
// V_s = 0 and normal force N_s >= 0; each such contact either sticks (U_s = 0, |F_T| <= mu_s N)
// or slides (F_T = -sgn(U_s) mu N). Forces are per unit mass.
//
// The contact accelerations are affine in the contact forces:
//   dU_s/dt = u' - w' r_z - w^2 r_x,   dV_s/dt = v' + w' r_x - w^2 (r_z + R),
// with u' = g_x + sum F_T, v' = g_z(t) + sum N, w' = (1/I) sum (r_x N - r_z F_T).
// Requiring dV_s/dt = 0 (and dU_s/dt = 0 when sticking) gives a linear system for the forces.
// Both spheres sticking on a flat dimer make the tangential forces indeterminate (only their sum
// matters); the minimum-norm solution splits it evenly.
#include <array>

#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

// slide[s]: 0 sticking, +1 / -1 sliding with U_s > 0 / < 0. Only meaningful where resting[s].
struct ContactConfig {
  std::array<bool, 2> resting{};
  std::array<int, 2> slide{};
  int Count() const { return int(resting[0]) + int(resting[1]); }
};

struct ContactForces {
  std::array<double, 2> n{}, f{};  // normal and tangential force per unit mass, m/s^2
  double ax = 0, az = 0, aw = 0;   // CM and angular accelerations
  bool ok = true;
};

ContactForces SolveContactForces(const Model& m, double t, const State& q,
                                 const ContactConfig& cfg);
// The same with the plate's phase at t already computed (bit-identical to the above; only
// its sin is used: Model::SinPhase is enough).
ContactForces SolveContactForces(const Model& m, Model::PlatePhase phase, const State& q,
                                 const ContactConfig& cfg);

struct ModeChoice {
  ContactConfig cfg;
  ContactForces forces;
  int painleve_sphere = -1;  // >= 0: sliding contact that can neither press nor lift (Painleve)
};
// The consistent contact mode at (t, q) among the `candidates` (spheres at the plate with
// V = 0): sticking where U = 0 and the static cone holds, sliding otherwise, dropping contacts
// whose normal force would be negative (lift-off).
ModeChoice ChooseContactMode(const Model& m, double t, const State& q,
                             std::array<bool, 2> candidates);

// Puts q back on the constraint manifold of cfg (gap, normal velocity, and slip if sticking):
// the integrator drifts by its tolerance; this keeps the drift from accumulating.
void ProjectOnContacts(const Model& m, const ContactConfig& cfg, State* q);

// With one sphere resting: putting it on the plate (ProjectOnContacts) lowers the other sphere
// by as much as the resting one stood above the plate, up to kTouchTol_m when it was taken
// into contact there. A sphere that has just left an impact at the surface then starts its
// next flight below -gap_tol, where the impact event cannot see it cross (it sank through
// the plate: SimulatorTest.ResettledSphereNextToARestingOneIsStillWatched). The dimer is then
// flat with both spheres at the plate: lay it flat. Returns whether it did.
bool LayFlatOnTouchingSphere(const Model& m, const ContactConfig& cfg, State* q);

}  // namespace dimer::sim
