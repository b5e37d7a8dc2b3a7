// No sphere through the plate: every impact of either sphere is found, also while the other one
// rests on the plate, at any spin. A run that finds a sphere deeper than gap_tol stops with an
// error naming the time and the state (a missed impact is a simulator error, never a result).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <sstream>

#include "sim/constants.h"
#include "sim/contact_integrator.h"
#include "sim/simulator.h"
#include "tests/sim/test_models.h"

namespace dimer::sim {
namespace {

using testing::Scaled;

// A reproducible uniform draw (a 64-bit LCG's top 53 bits): the same runs on every machine.
struct Uniform {
  uint64_t state;
  double operator()(double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
  }
};

// Deepest penetration a healthy run may show: the gap tolerance, and round-off of a position.
double PenetrationLimit(const SimOptions& o) {
  return o.gap_tol + kPositionRoundoffRel * 0.5 * o.diameter_m;
}

// A dimer at A_r 2 (the rod nearly at the plate) dropped with a fast spin: its inelastic
// collapse ends with one sphere taken into persistent contact within the touching band while
// the other has just bounced; putting the resting one onto the plate lowered the other below
// -gap_tol, where the impact event could no longer see it, and it sank 9 mm through the plate
// while the run reported "rest".
TEST(Penetration, SpinningShortDimerAfterACollapseStaysAboveThePlate) {
  SimOptions o;
  o.ar = 2;
  o.gamma = 0.644;
  o.init_state = {0.0,  0.012765259941775162,  -0.027884728050431185, -0.004834066436121426,
                  -0.004049308417423958, -37.19281778877705};
  o.cycles = 300;
  o.fps = 2000;
  const SimResult r = RunSimulation(o);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.periods.size(), 300u);
  EXPECT_LE(r.diag.max_penetration_m, PenetrationLimit(o));
}

// Property: random releases of short dimers (A_r 2.0-2.4, where the rod nearly touches the
// plate) with large spins over Gamma 0.5-1.0, the range of the mode map where 32 of 606 points
// went through the plate. Every run must end without an error and without penetration.
TEST(Penetration, RandomSpinningReleasesOfShortDimersNeverPassThroughThePlate) {
  Uniform uniform{0x9e3779b97f4a7c15ULL};
  const int runs = static_cast<int>(Scaled(1000));
  int with_rest = 0;
  for (int k = 0; k < runs; ++k) {
    SimOptions o;
    o.ar = uniform(2.0, 2.4);
    o.gamma = uniform(0.5, 1.0);
    const double R = 0.5 * o.diameter_m, arm = (o.ar - 1) * R;
    const double th = uniform(-0.6, 0.6);
    const double z = R + arm * std::abs(std::sin(th)) + uniform(0.0, 2.0) * R;
    const double w = uniform(-60.0, 60.0);
    o.init_state = {0.0, z, th, uniform(-0.05, 0.05), uniform(-0.3, 0.1), w};
    o.cycles = 120;
    o.fps = 500;
    const SimResult r = RunSimulation(o);
    std::ostringstream what;
    what.precision(17);
    what << "run " << k << ": --ar " << o.ar << " --gamma " << o.gamma << " --init-state \"0,"
         << z << "," << th << "," << (*o.init_state)[3] << "," << (*o.init_state)[4] << "," << w
         << "\"";
    ASSERT_TRUE(r.error.empty()) << what.str() << ": " << r.error;
    ASSERT_LE(r.diag.max_penetration_m, PenetrationLimit(o)) << what.str();
    with_rest += r.mode.label == "rest";
  }
  // The releases reach the situation under test: most of them collapse onto the plate.
  EXPECT_GT(with_rest, runs / 4);
}

// Above Gamma 1 the plate pulls away from a resting sphere: a sphere that has just bounced off
// the plate next to it rises and falls back within one integration step, between two ends
// above the plate, while the resting one lifts off in the same step. Its impact must be found
// before the lift-off (a mode map drop at A_r 3.6, Gamma 1.4 went 1e-8 m deep unseen).
TEST(Penetration, ShortFlightsNextToARestingSphereAreSeen) {
  SimOptions o;
  o.ar = 3.6;
  o.gamma = 1.4;
  o.init_state = {0.0, 0.011696949161012942, -0.096183625826159358, 0.013664232895524618,
                  0.0001262430244683425, 15.315363081583742};
  o.cycles = 300;
  o.fps = 25;
  const SimResult r = RunSimulation(o);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_LE(r.diag.max_penetration_m, PenetrationLimit(o));
}

// Property: random drops over the upper half of the mode map (A_r 3-9, Gamma 1.1-1.4), where the
// plate's acceleration exceeds gravity and contacts open and close within a step.
TEST(Penetration, RandomDropsAboveGammaOneNeverPassThroughThePlate) {
  Uniform uniform{0x2545f4914f6cdd1dULL};
  const int runs = static_cast<int>(Scaled(200));
  for (int k = 0; k < runs; ++k) {
    SimOptions o;
    o.ar = uniform(3.0, 9.0);
    o.gamma = uniform(1.1, 1.4);
    const double R = 0.5 * o.diameter_m, arm = (o.ar - 1) * R;
    const double th = uniform(-0.5, 0.5);
    const double z = R + arm * std::abs(std::sin(th)) + uniform(0.1, 1.0) * 2 * R;
    o.init_state = {0.0, z, th, uniform(-0.02, 0.02), uniform(-0.02, 0.02),
                    uniform(-0.5, 0.5) * 0.39 / arm};
    o.cycles = 100;
    o.fps = 25;
    const SimResult r = RunSimulation(o);
    ASSERT_TRUE(r.error.empty()) << "run " << k << ": " << r.error;
    ASSERT_LE(r.diag.max_penetration_m, PenetrationLimit(o)) << "run " << k;
  }
}

// The check itself: a sphere that starts a persistent-contact phase below -gap_tol and keeps
// sinking is reported as a penetration at the first step's end, not integrated on.
TEST(Penetration, ContactPhaseReportsASphereStartingBelowTheTolerance) {
  const Model m = testing::PaperModel(2.0);
  ContactConfig cfg;
  cfg.resting = {true, false};
  State q;
  q.th = -1e-7;  // the right sphere 2 A R |theta| ~ 1e-9 m below the plate
  q.z = -ContactArm(m, q.th, 0).rz;
  q.v = -0.01;
  q.w = -0.01 / (2 * m.A * m.R);  // left contact still, the right sphere sinking
  ASSERT_LT(Gap(m, q, 1), -m.gap_tol);
  double h = 1e-4 * m.period;
  const ContactRun run = IntegrateContact(m, cfg, 0.0, q, m.period, &h, nullptr);
  EXPECT_EQ(run.event, ContactEvent::kPenetration);
  EXPECT_EQ(run.sphere, 1);
  EXPECT_LT(run.t, 0.5 * m.period);
}

}  // namespace
}  // namespace dimer::sim
