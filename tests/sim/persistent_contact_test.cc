#include "sim/persistent_contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/sim/test_models.h"

namespace dimer::sim {
namespace {

// Contact-point accelerations from the CM accelerations (docs/MODEL.md, "Contact kinematics"), computed here
// independently of the solver.
struct ContactAcc {
  double udot, vdot;
};
ContactAcc ContactAcceleration(const Model& m, const State& q, const ContactForces& f, int s) {
  const Arm r = ContactArm(m, q.th, s);
  return {f.ax - f.aw * r.rz - q.w * q.w * r.rx, f.az + f.aw * r.rx - q.w * q.w * (r.rz + m.R)};
}

State RestingOn(const Model& m, int s, double th, double w, double u) {
  State q;
  q.th = th;
  q.w = w;
  const Arm r = ContactArm(m, th, s);
  q.z = -r.rz;
  q.v = -w * r.rx;
  q.u = u;
  return q;
}

TEST(PersistentContact, StickKeepsBothContactVelocitiesConstant) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> uni(-1, 1);
  for (int i = 0; i < 500; ++i) {
    SimOptions o;
    o.ar = 1.05 + 9 * (0.5 + 0.5 * uni(rng));
    o.tilt_deg = 10 * uni(rng);
    const Model m = Model::FromOptions(o);
    const int s = i % 2;
    const State q0 = RestingOn(m, s, 0.6 * uni(rng), 5 * uni(rng), 0.0);
    State q = q0;
    q.u = q0.w * ContactArm(m, q0.th, s).rz;  // U = 0
    ContactConfig cfg;
    cfg.resting[s] = true;
    const ContactForces f = SolveContactForces(m, 0.01 * i, q, cfg);
    ASSERT_TRUE(f.ok);
    const ContactAcc a = ContactAcceleration(m, q, f, s);
    EXPECT_NEAR(a.udot, 0.0, 1e-9);
    EXPECT_NEAR(a.vdot, 0.0, 1e-9);
  }
}

TEST(PersistentContact, SlideObeysCoulombAndKeepsTheNormalConstraint) {
  const Model m = testing::PaperModel();
  for (int sigma : {-1, 1}) {
    const State q = RestingOn(m, kLeft, 0.2, -3.0, 0.1 * sigma);
    ContactConfig cfg;
    cfg.resting[kLeft] = true;
    cfg.slide[kLeft] = sigma;
    const ContactForces f = SolveContactForces(m, 0.0, q, cfg);
    ASSERT_TRUE(f.ok);
    EXPECT_NEAR(f.f[kLeft], -sigma * m.mu * f.n[kLeft], 1e-12);
    EXPECT_NEAR(ContactAcceleration(m, q, f, kLeft).vdot, 0.0, 1e-9);
    EXPECT_GT(f.n[kLeft], 0.0);
  }
}

// Both spheres resting (flat, closed form in the solver): every friction combination satisfies
// its rows — V' = 0 at both contacts, U' = 0 where sticking (both sticking: only the sum of the
// tangential forces is fixed; it is shared like the normal ones), F = -sgn(U) mu N where sliding
// — and the accelerations are those of the forces.
TEST(PersistentContact, FlatPairSatisfiesEveryRowInEachFrictionCombination) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uni(-1, 1);
  for (int i = 0; i < 400; ++i) {
    SimOptions o;
    o.ar = 1.5 + 8 * (0.5 + 0.5 * uni(rng));
    o.tilt_deg = 15 * uni(rng);
    o.gamma = 0.9 * (0.5 + 0.5 * uni(rng));
    const Model m = Model::FromOptions(o);
    State q;
    q.th = (i % 4 < 2) ? 0.0 : M_PI;
    q.z = m.R;
    q.u = 0.05 * uni(rng);
    ContactConfig cfg;
    cfg.resting = {true, true};
    cfg.slide = {i % 3 - 1, (i / 3) % 3 - 1};
    const double t = 0.001 * i;
    const ContactForces f = SolveContactForces(m, t, q, cfg);
    ASSERT_TRUE(f.ok) << i;
    const double g = kGravity;
    for (int s = 0; s < 2; ++s) {
      const ContactAcc a = ContactAcceleration(m, q, f, s);
      EXPECT_NEAR(a.vdot, 0.0, 1e-12 * g) << i;
      if (cfg.slide[s] != 0) {
        EXPECT_NEAR(f.f[s], -cfg.slide[s] * m.mu * f.n[s], 1e-12 * g) << i;
      } else {
        EXPECT_NEAR(a.udot, 0.0, 1e-12 * g) << i;
      }
    }
    if (cfg.slide[0] == 0 && cfg.slide[1] == 0 && f.n[0] + f.n[1] > 0) {
      EXPECT_NEAR(f.f[0] * f.n[1], f.f[1] * f.n[0], 1e-12 * g * g) << i;  // shared like N
    }
    // Accelerations from the forces (docs/MODEL.md).
    const Arm r0 = ContactArm(m, q.th, 0), r1 = ContactArm(m, q.th, 1);
    EXPECT_NEAR(f.ax, m.Gx() + f.f[0] + f.f[1], 1e-12 * g) << i;
    EXPECT_NEAR(f.az, m.Gz(t) + f.n[0] + f.n[1], 1e-12 * g) << i;
    EXPECT_NEAR(f.aw / m.inv_I,
                r0.rx * f.n[0] + r1.rx * f.n[1] - r0.rz * f.f[0] - r1.rz * f.f[1],
                1e-12 * g * m.R) << i;
  }
}

// The closed-form projection is the mass-metric one: it zeroes the constrained contact
// velocities and removes the least kinetic energy, i.e. what is removed is M-orthogonal to
// every velocity the constraints allow (checked against the rolling direction and the free
// ones).
TEST(PersistentContact, ProjectionZeroesTheConstrainedVelocitiesAndIsOrthogonalInTheMassMetric) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> uni(-1, 1);
  const Model m = testing::PaperModel();
  const double I = 1.0 / m.inv_I;
  for (int i = 0; i < 200; ++i) {
    const int s = i % 2;
    State q;
    q.th = 0.5 * uni(rng);
    q.z = -ContactArm(m, q.th, s).rz;
    q.u = uni(rng), q.v = uni(rng), q.w = 20 * uni(rng);
    ContactConfig cfg;
    cfg.resting[s] = true;
    cfg.slide[s] = i % 4 < 2 ? 0 : 1;
    State p = q;
    ProjectOnContacts(m, cfg, &p);
    const Arm r = ContactArm(m, p.th, s);
    EXPECT_NEAR(NormalV(r, p), 0.0, 1e-13) << i;
    if (cfg.slide[s] == 0) {
      EXPECT_NEAR(SlipU(r, p), 0.0, 1e-13) << i;
    }
    // Removed velocity d = q - p; allowed directions a: d^T M a = 0.
    const double du = q.u - p.u, dv = q.v - p.v, dw = q.w - p.w;
    auto m_dot = [&](double au, double av, double aw) { return du * au + dv * av + I * dw * aw; };
    EXPECT_NEAR(m_dot(r.rz, -r.rx, 1.0), 0.0, 1e-12) << i;  // rolling about the contact
    if (cfg.slide[s] != 0) {
      EXPECT_NEAR(m_dot(1.0, 0.0, 0.0), 0.0, 1e-12) << i;  // sliding
    }
  }
}

// docs/MODEL.md check 4 at the force level: a flat dimer on a still plate tilted by alpha sticks
// iff tan(alpha) <= mu_s; the normal forces carry the weight and the friction its slope part.
TEST(PersistentContact, FlatDimerOnATiltSticksBelowTheFrictionAngle) {
  for (double factor : {0.5, 0.99, 1.01, 2.0}) {
    SimOptions o;
    o.gamma = 0;
    o.tilt_deg = std::atan(factor * o.mu_s) * 180 / M_PI;
    const Model m = Model::FromOptions(o);
    State q;
    q.z = m.R;
    const ModeChoice mc = ChooseContactMode(m, 0.0, q, {true, true});
    ASSERT_EQ(mc.cfg.Count(), 2);
    const bool sticks = factor <= 1;
    EXPECT_EQ(mc.cfg.slide[0] == 0 && mc.cfg.slide[1] == 0, sticks) << "factor " << factor;
    EXPECT_NEAR(mc.forces.n[0] + mc.forces.n[1], kGravity * m.cos_a, 1e-12);
    if (sticks) {
      EXPECT_NEAR(mc.forces.f[0] + mc.forces.f[1], kGravity * m.sin_a, 1e-12);
      EXPECT_NEAR(mc.forces.ax, 0.0, 1e-12);
    } else {
      EXPECT_NEAR(mc.forces.ax, -kGravity * (m.sin_a - m.mu * m.cos_a), 1e-12);
    }
  }
}

TEST(PersistentContact, NegativeNormalForceLiftsTheContact) {
  // A plate accelerating downward faster than g (Gamma > 1 near its top) cannot hold the dimer.
  SimOptions o;
  o.gamma = 2.0;
  const Model m = Model::FromOptions(o);
  State q;
  q.z = m.R;
  const double t_top = 0.25 * m.period;  // plate acceleration -Gamma g
  const ModeChoice mc = ChooseContactMode(m, t_top, q, {true, true});
  EXPECT_EQ(mc.cfg.Count(), 0);
  const ModeChoice bottom = ChooseContactMode(m, 0.75 * m.period, q, {true, true});
  EXPECT_EQ(bottom.cfg.Count(), 2);
}

// Painleve's paradox: with a large sliding friction some sliding configurations admit neither
// contact nor lift-off; the chooser must say so rather than return a negative normal force.
TEST(PersistentContact, PainleveConfigurationIsDetected) {
  SimOptions o;
  o.ar = 2.0;
  o.mu = 10;
  o.mu_s = 10;
  o.gamma = 0;
  const Model m = Model::FromOptions(o);
  int detected = 0;
  for (double th : {-0.3, -0.1, 0.1, 0.3}) {
    for (int sigma : {-1, 1}) {
      State q = RestingOn(m, kLeft, th, 0.0, 0.2 * sigma);
      const ModeChoice mc = ChooseContactMode(m, 0.0, q, {true, false});
      if (mc.painleve_sphere >= 0) {
        ++detected;
      } else if (mc.cfg.resting[kLeft]) {
        EXPECT_GE(mc.forces.n[kLeft], 0.0);
      }
    }
  }
  EXPECT_GT(detected, 0);
}

}  // namespace
}  // namespace dimer::sim
