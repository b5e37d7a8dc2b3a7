// The rest state's fast path (sim/resting.h): a flat, sticking dimer whose contact forces stay
// inside their cones over the whole plate cycle skips its stages, and gives the same samples
// as integrating it step by step; anything else is integrated.
#include "sim/resting.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/reference_frames.h"
#include "sim/simulator.h"

namespace dimer::sim {
namespace {

SimOptions RestOptions(double gamma, double tilt_deg) {
  SimOptions o;
  o.init = InitKind::kRest;
  o.gamma = gamma;
  o.tilt_deg = tilt_deg;
  o.cycles = 20;
  o.fps = 1000;
  return o;
}

SimResult Simulate(const SimOptions& o, bool skip_rest) {
  RunControls c;
  c.skip_rest = skip_rest;
  return RunSimulation(o, c);
}

// Fast and step-by-step runs agree sample by sample (to round-off: both keep the state put),
// in the per-period statistics and the mode.
void ExpectSameRun(const SimResult& fast, const SimResult& slow, const char* what) {
  ASSERT_EQ(fast.t.size(), slow.t.size()) << what;
  for (size_t i = 0; i < fast.t.size(); ++i) {
    ASSERT_EQ(fast.t[i], slow.t[i]) << what << " sample " << i;
    const State& a = fast.lab[i];
    const State& b = slow.lab[i];
    const double len = 1e-15, vel = 1e-15;  // m, m/s (positions ~1e-2 m, ~10 ulp)
    ASSERT_NEAR(a.x, b.x, len) << what << " sample " << i;
    ASSERT_NEAR(a.z, b.z, len) << what << " sample " << i;
    ASSERT_NEAR(a.th, b.th, 1e-15) << what << " sample " << i;
    ASSERT_NEAR(a.u, b.u, vel) << what << " sample " << i;
    ASSERT_NEAR(a.v, b.v, vel) << what << " sample " << i;
    ASSERT_NEAR(a.w, b.w, 1e-13) << what << " sample " << i;
  }
  EXPECT_EQ(fast.events.size(), slow.events.size()) << what;
  ASSERT_EQ(fast.periods.size(), slow.periods.size()) << what;
  for (size_t k = 0; k < fast.periods.size(); ++k) {
    EXPECT_NEAR(fast.periods[k].x_start, slow.periods[k].x_start, 1e-15) << what;
    for (int s = 0; s < 2; ++s) {
      EXPECT_DOUBLE_EQ(fast.periods[k].rest_time[s], slow.periods[k].rest_time[s]) << what;
    }
  }
  EXPECT_EQ(fast.mode.label, slow.mode.label) << what;
}

TEST(Resting, FastPathGivesTheStepByStepSamples) {
  struct Case {
    const char* what;
    double gamma, tilt_deg;
  };
  for (const Case& c : {Case{"still plate", 0.0, 0.0}, Case{"Gamma 0.9", 0.9, 0.0},
                        Case{"Gamma 0.99", 0.99, 0.0}, Case{"Gamma 0.5, tilt 5", 0.5, 5.0},
                        Case{"Gamma 0.3, tilt -10", 0.3, -10.0}}) {
    const SimOptions o = RestOptions(c.gamma, c.tilt_deg);
    const SimResult fast = Simulate(o, true), slow = Simulate(o, false);
    ASSERT_TRUE(fast.error.empty() && slow.error.empty()) << c.what;
    // The fast run skipped every stage; the step-by-step run integrated them.
    EXPECT_EQ(fast.diag.rest_stages, static_cast<long>(o.cycles)) << c.what;
    EXPECT_EQ(fast.diag.contact_steps, 0) << c.what;
    EXPECT_EQ(slow.diag.rest_stages, 0) << c.what;
    EXPECT_GT(slow.diag.contact_steps, 0) << c.what;
    ExpectSameRun(fast, slow, c.what);
    EXPECT_EQ(fast.mode.label, "rest") << c.what;
  }
}

TEST(Resting, AFlatDimerSlidingToAStopIsIntegratedUntilItRests) {
  // Released flat with a push along a still plate: it slides (integrated), sticks, then rests
  // (fast path); both runs end at the same place.
  SimOptions o = RestOptions(0.0, 0.0);
  const double R = 0.5 * o.diameter_m;
  o.init_state = std::array<double, 6>{0.0, R, 0.0, 0.05, 0.0, 0.0};
  const SimResult fast = Simulate(o, true), slow = Simulate(o, false);
  ASSERT_TRUE(fast.error.empty() && slow.error.empty());
  EXPECT_GT(fast.diag.contact_steps, 0);  // the slide, within the first period
  // Then rest: the rest of the first period and every later one are skipped.
  EXPECT_EQ(fast.diag.rest_stages, static_cast<long>(o.cycles));
  // Coulomb: it stops after u0^2 / (2 mu g).
  const double stop = 0.05 * 0.05 / (2 * o.mu * kGravity);
  EXPECT_NEAR(fast.lab.back().x, stop, 1e-9);
  ExpectSameRun(fast, slow, "slide to a stop");
}

TEST(Resting, StatesThatDoNotStayPutAreNotSkipped) {
  struct Case {
    const char* what;
    double gamma, tilt_deg;
  };
  const double friction_angle = std::atan(SimOptions{}.mu_s) * 180 / M_PI;
  for (const Case& c : {Case{"Gamma 1.2 (lifts off)", 1.2, 0.0},
                        Case{"tilt beyond the friction angle", 0.0, 1.05 * friction_angle},
                        Case{"Gamma 0.6 lowers the cone below a tilt that holds on a still plate",
                             0.6, 0.5 * friction_angle}}) {
    const SimOptions o = RestOptions(c.gamma, c.tilt_deg);
    EXPECT_FALSE(RestHoldsOverTheCycle(Model::FromOptions(o))) << c.what;
    const SimResult r = Simulate(o, true);
    EXPECT_EQ(r.diag.rest_stages, 0) << c.what;
    // And it does move: it lifts off (events) or slides along the plate.
    const State end = PlateFromLab(r.model, r.t.back(), r.lab.back());
    EXPECT_TRUE(!r.events.empty() || std::abs(end.x) > 1e-4) << c.what;
  }
}

TEST(Resting, TheCycleBoundIsTheClosedForm) {
  // Flat on a level plate: stays put iff Gamma < 1 (with the margin just below 1).
  for (double gamma : {0.0, 0.9, 0.999999}) {
    EXPECT_TRUE(RestHoldsOverTheCycle(Model::FromOptions(RestOptions(gamma, 0)))) << gamma;
  }
  for (double gamma : {1.0 - 1e-13, 1.0, 1.5}) {
    EXPECT_FALSE(RestHoldsOverTheCycle(Model::FromOptions(RestOptions(gamma, 0)))) << gamma;
  }
  // Still plate, tilt: holds iff tan(alpha) <= mu_s (both normal forces stay positive: A_r 3.9).
  const double mu_s = SimOptions{}.mu_s;
  for (double factor : {0.5, 0.99}) {
    const double tilt = std::atan(factor * mu_s) * 180 / M_PI;
    EXPECT_TRUE(RestHoldsOverTheCycle(Model::FromOptions(RestOptions(0, tilt)))) << factor;
    EXPECT_FALSE(RestHoldsOverTheCycle(Model::FromOptions(RestOptions(0, tilt / factor * 1.01))))
        << factor;
  }
  // A short dimer on a tilt tips over its lower sphere first: the upper normal force
  // (N_sum - g sin(alpha) / A) / 2 goes negative while the cone would still hold.
  SimOptions shortie = RestOptions(0, 20);  // tan 20 deg = 0.36 < mu_s = 0.4
  shortie.ar = 1.2;                         // A = 0.2 < tan(alpha)
  EXPECT_FALSE(RestHoldsOverTheCycle(Model::FromOptions(shortie)));
  shortie.ar = 3.9;
  EXPECT_TRUE(RestHoldsOverTheCycle(Model::FromOptions(shortie)));
}

TEST(Resting, OnlyTheProjectedStickingRestStateStaysPut) {
  const Model m = Model::FromOptions(RestOptions(0.9, 0));
  ContactConfig stick;
  stick.resting = {true, true};
  State q;
  q.z = m.R;
  EXPECT_TRUE(StaysPut(m, stick, q));
  q.th = M_PI;  // flipped: the same rest state
  EXPECT_TRUE(StaysPut(m, stick, q));
  State moving = q;
  moving.u = 1e-18;
  EXPECT_FALSE(StaysPut(m, stick, moving));
  State spinning = q;
  spinning.w = 1e-18;
  EXPECT_FALSE(StaysPut(m, stick, spinning));
  State lifted = q;
  lifted.z = m.R * (1 + 1e-12);
  EXPECT_FALSE(StaysPut(m, stick, lifted));
  ContactConfig slide = stick;
  slide.slide = {1, 1};
  EXPECT_FALSE(StaysPut(m, slide, q));
  ContactConfig one;
  one.resting = {true, false};
  EXPECT_FALSE(StaysPut(m, one, q));
}

}  // namespace
}  // namespace dimer::sim
