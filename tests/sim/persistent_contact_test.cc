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
