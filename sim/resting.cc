#include "sim/resting.h"

#include <cmath>

namespace dimer::sim {
namespace {
// Margin of the inequalities, relative to g: far above the round-off of the contact forces
// (~1e-15 g), so that the step-by-step path cannot see an event the closed form excludes.
constexpr double kRestMarginRel = 1e-9;
}  // namespace

bool RestHoldsOverTheCycle(const Model& m) {
  const double margin = kRestMarginRel * kGravity;
  const double n_min = kGravity * m.cos_a - m.amp * m.omega_p * m.omega_p;  // min of N_0 + N_1
  const double f_sum = kGravity * std::abs(m.sin_a);                        // |F_0 + F_1|
  return n_min - f_sum / m.A > margin && m.mu_s * n_min - f_sum > margin;
}

bool StaysPut(const Model& m, const ContactConfig& cfg, const State& q) {
  if (!(cfg.Count() == 2 && cfg.slide[0] == 0 && cfg.slide[1] == 0)) return false;
  // Exactly the projected rest state (ProjectOnContacts sets these for a flat sticking pair).
  if (!(q.u == 0 && q.v == 0 && q.w == 0 && q.z == m.R)) return false;
  if (!(q.th == std::round(q.th / M_PI) * M_PI)) return false;
  return RestHoldsOverTheCycle(m);
}

}  // namespace dimer::sim
