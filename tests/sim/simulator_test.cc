#include "sim/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <ostream>
#include <random>

#include "common/error.h"
#include "sim/reference_frames.h"
#include "sim/initial_conditions.h"
#include "tests/sim/test_models.h"

namespace dimer::sim {
namespace {

using testing::Scaled;

SimOptions EventsOnly(SimOptions o) {
  o.fps = 0;
  return o;
}

// docs/MODEL.md check 1: a flat, non-rotating dimer hitting with both spheres at once is a bouncing
// ball; on the period-1 orbit every impact is at the same plate phase and leaves at gT/2.
TEST(Simulator, JumpModeFollowsTheBouncingBallPeriodOneOrbit) {
  SimOptions o = EventsOnly({});
  o.init = InitKind::kJump;
  o.cycles = static_cast<double>(Scaled(1000));
  const SimResult r = RunSimulation(o);
  const Model& m = r.model;
  const double phase_star = PeriodOneImpactPhase(m);
  const double takeoff = kGravity * m.period / 2;
  ASSERT_GE(r.events.size(), static_cast<size_t>(o.cycles) - 1);
  for (const EventRecord& e : r.events) {
    ASSERT_EQ(e.kind, EventKind::kDoubleImpact);
    const double phase = std::remainder(m.omega_p * e.t + m.phi0 - phase_star, 2 * M_PI);
    EXPECT_NEAR(phase, 0.0, 1e-9 * 2 * M_PI) << "impact at t = " << e.t;
    const State lab = LabFromPlate(m, e.t, e.after);
    EXPECT_NEAR(lab.v, takeoff, 1e-9 * takeoff) << "impact at t = " << e.t;
    EXPECT_NEAR(lab.w, 0.0, 1e-9);
    // Lab-frame identity of docs/MODEL.md: w - V_p = eps g T / (1 + eps).
    EXPECT_NEAR(lab.v - m.PlateV(e.t), m.eps * kGravity * m.period / (1 + m.eps), 1e-9 * takeoff);
  }
  EXPECT_EQ(r.mode.label, "jump");
}

double TotalEnergy(const Model& m, const State& q) { return Energy(m, q); }

// docs/MODEL.md check 3: with a still plate, eps = 1 and no friction, kinetic + potential energy is
// the same after any number of impacts; with dissipation it never increases.
struct EnergyRun {
  double eps, mu_hat, mu;
  bool conserved;
};
void PrintTo(const EnergyRun& c, std::ostream* os) { *os << "eps " << c.eps << " mu " << c.mu; }
class SimulatorEnergy : public ::testing::TestWithParam<EnergyRun> {};

TEST_P(SimulatorEnergy, ConservedOrNeverCreatedOverRandomFlights) {
  const EnergyRun c = GetParam();
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> uni(0, 1);
  long impacts = 0;
  const long wanted = Scaled(100000);
  for (int run = 0; impacts < wanted && run < 5000; ++run) {
    SimOptions o = EventsOnly({});
    o.gamma = 0;
    o.ar = 1.05 + 9 * uni(rng);
    o.eps = c.eps;
    o.mu_hat = o.mu_hat_s = c.mu_hat;
    o.mu = o.mu_s = c.mu;
    o.collapse_rel = 1e-9;
    o.contact_tol = 1e-12;  // integration error far below the energy bounds checked here
    o.cycles = 200;
    o.max_events_per_period = 1e4;
    const Model m = Model::FromOptions(o);
    const double th = M_PI * (uni(rng) - 0.5);
    const double z = m.R + m.A * m.R * std::abs(std::sin(th)) + 0.01 * uni(rng);
    o.init_state = std::array<double, 6>{0, z, th, uni(rng) - 0.5, uni(rng) - 0.5,
                                         40 * (uni(rng) - 0.5)};
    const SimResult r = RunSimulation(o);
    ASSERT_TRUE(r.error.empty()) << r.error;
    const double e0 = TotalEnergy(m, PlateFromLab(m, 0, State{0, z, th, (*o.init_state)[3],
                                                               (*o.init_state)[4],
                                                               (*o.init_state)[5]}));
    double last = e0;
    for (const EventRecord& e : r.events) {
      const double eb = TotalEnergy(m, e.before), ea = TotalEnergy(m, e.after);
      const double scale = std::abs(e0) + 1e-3;
      if (c.conserved) {
        ASSERT_NEAR(ea, e0, 1e-9 * scale) << "run " << run << " t " << e.t;
      } else {
        ASSERT_LE(eb, last + 1e-9 * scale)
            << "run " << run << " created " << eb - last << " in flight/contact before t " << e.t;
        ASSERT_LE(ea, eb + 1e-12 * scale) << "run " << run << " impact created energy";
      }
      last = ea;
      impacts += e.kind == EventKind::kImpact || e.kind == EventKind::kDoubleImpact ||
                 e.kind == EventKind::kCollapse;
    }
  }
  EXPECT_GE(impacts, wanted);
}

INSTANTIATE_TEST_SUITE_P(Laws, SimulatorEnergy,
                         ::testing::Values(EnergyRun{1.0, 0.0, 0.0, true},
                                           EnergyRun{0.65, 0.1, 0.2, false},
                                           EnergyRun{0.99, 0.5, 0.5, false}),
                         [](const ::testing::TestParamInfo<EnergyRun>& p) {
                           return "eps" + std::to_string(int(p.param.eps * 100)) + "_mu" +
                                  std::to_string(int(p.param.mu * 100));
                         });

// docs/MODEL.md check 4: a flat dimer stays on a plate with Gamma < 1, and does not slide on a
// still plate tilted below the friction angle.
TEST(Simulator, FlatDimerRestsBelowGammaOne) {
  for (double gamma : {0.0, 0.5, 0.9, 0.999}) {
    SimOptions o;
    o.init = InitKind::kRest;
    o.gamma = gamma;
    o.cycles = 50;
    o.fps = 500;
    const SimResult r = RunSimulation(o);
    EXPECT_TRUE(r.events.empty()) << "Gamma " << gamma;
    for (size_t i = 0; i < r.t.size(); ++i) {
      const State q = PlateFromLab(r.model, r.t[i], r.lab[i]);
      ASSERT_NEAR(q.z, r.model.R, 1e-15);
      ASSERT_NEAR(q.x, 0.0, 1e-15);
      ASSERT_NEAR(q.th, 0.0, 1e-15);
    }
    EXPECT_EQ(r.mode.label, "rest");
  }
}

TEST(Simulator, NoSlideOnATiltBelowTheFrictionAngleAndCoulombSlideAbove) {
  for (double factor : {0.5, 0.95, 1.05, 1.5}) {
    SimOptions o;
    o.init = InitKind::kRest;
    o.gamma = 0;
    o.tilt_deg = std::atan(factor * o.mu_s) * 180 / M_PI;
    o.duration_s = 0.2;
    o.fps = 100;
    const SimResult r = RunSimulation(o);
    const Model& m = r.model;
    const State end = PlateFromLab(m, r.t.back(), r.lab.back());
    const double elapsed = r.t.back() - r.t.front();
    if (factor < 1) {
      EXPECT_NEAR(end.x, 0.0, 1e-15) << "factor " << factor;
    } else {
      const double acc = -kGravity * (m.sin_a - m.mu * m.cos_a);  // down the slope (-x)
      EXPECT_NEAR(end.x, 0.5 * acc * elapsed * elapsed, 1e-9) << "factor " << factor;
    }
  }
}

// The paper's drift mode (its Fig. 3 and 4): stable, toward the bouncing end at A_r = 3.9,
// backward at A_r = 6.1, and <u> f / g independent of f.
TEST(Simulator, DriftModeIsStableAndDriftsTowardTheBouncingEnd) {
  SimOptions o = EventsOnly({});
  o.cycles = static_cast<double>(std::max(200L, Scaled(1000)));
  const SimResult r = RunSimulation(o);
  ASSERT_EQ(r.mode.label, "drift");
  EXPECT_EQ(r.mode.bouncing_sphere, kRight);  // the lifted end keeps bouncing
  EXPECT_GT(r.mode.drift_speed, 0.0);
  EXPECT_LT(r.mode.drift_speed_err, 0.01 * r.mode.drift_speed);
  // Stable over the whole run, not only at its end: every period after the transient is drift.
  int bad = 0;
  for (size_t k = 20; k < r.periods.size(); ++k) {
    bad += r.periods[k].impacts[kRight] != 1 || r.periods[k].rest_time[kLeft] < 0.2 * r.model.period;
  }
  EXPECT_EQ(bad, 0);
}

TEST(Simulator, LongDimerDriftsBackward) {
  SimOptions o = EventsOnly({});
  o.ar = 6.1;
  o.cycles = 300;
  const SimResult r = RunSimulation(o);
  ASSERT_EQ(r.mode.label, "drift");
  EXPECT_LT(r.mode.drift_speed, 0.0);
}

TEST(Simulator, ScaledDriftSpeedDoesNotDependOnFrequency) {
  double scaled[2];
  const double freqs[2] = {25, 75};
  for (int i = 0; i < 2; ++i) {
    SimOptions o = EventsOnly({});
    o.freq_hz = freqs[i];
    o.cycles = 300;
    const SimResult r = RunSimulation(o);
    ASSERT_EQ(r.mode.label, "drift") << freqs[i] << " Hz";
    scaled[i] = r.mode.drift_speed * freqs[i] / kGravity;
  }
  RecordProperty("drift_scaled_25", std::to_string(scaled[0]));
  RecordProperty("drift_scaled_75", std::to_string(scaled[1]));
  EXPECT_NEAR(scaled[1], scaled[0], 0.05 * std::abs(scaled[0]));
}

TEST(Simulator, InvalidParametersAreReportedTogether) {
  SimOptions o;
  o.gamma = -1;
  o.ar = 0.5;
  o.eps = 1.5;
  o.mu = -0.1;
  try {
    RunSimulation(o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const char* flag : {"--gamma", "--ar", "--eps", "--mu"}) {
      EXPECT_NE(msg.find(flag), std::string::npos) << msg;
    }
  }
  SimOptions jump;
  jump.init = InitKind::kJump;
  jump.eps = 0.0;  // needs Gamma >= pi
  EXPECT_THROW(RunSimulation(jump), InputError);
}

TEST(SimOptions, OnlyTheRootCauseIsReported) {
  // The default lift depends on --freq and its bound on --ar: a bad --ar or --freq must not add
  // a --lift error for a flag never given.
  SimOptions bad_ar;
  bad_ar.ar = 0.5;
  ASSERT_EQ(bad_ar.Check().size(), 1u);
  EXPECT_EQ(bad_ar.Check()[0].rfind("--ar", 0), 0u) << bad_ar.Check()[0];
  SimOptions bad_freq;
  bad_freq.freq_hz = 0;
  ASSERT_EQ(bad_freq.Check().size(), 1u);
  EXPECT_EQ(bad_freq.Check()[0].rfind("--freq", 0), 0u) << bad_freq.Check()[0];
  // A valid but low --freq makes the derived lift too large: reported, saying it is the default.
  SimOptions low_freq;
  low_freq.freq_hz = 2;
  ASSERT_EQ(low_freq.Check().size(), 1u);
  EXPECT_NE(low_freq.Check()[0].find("default lift"), std::string::npos) << low_freq.Check()[0];
  // An explicit lift is still checked against a valid --ar.
  SimOptions high_lift;
  high_lift.lift = 5;
  ASSERT_EQ(high_lift.Check().size(), 1u);
  EXPECT_EQ(high_lift.Check()[0].rfind("--lift", 0), 0u);
}

TEST(Simulator, SameInputsGiveBitIdenticalResults) {
  SimOptions o;
  o.cycles = 30;
  const SimResult a = RunSimulation(o), b = RunSimulation(o);
  ASSERT_EQ(a.t.size(), b.t.size());
  ASSERT_EQ(a.events.size(), b.events.size());
  for (size_t i = 0; i < a.lab.size(); ++i) {
    ASSERT_EQ(a.lab[i].x, b.lab[i].x);
    ASSERT_EQ(a.lab[i].th, b.lab[i].th);
  }
}

// RunControls::on_samples: once a period, the same arrays (RunSim's workers read them while
// the run goes on), a count that only grows, and rows that are final when reported.
TEST(Simulator, SampleCallbackSeesFinalRowsAtFixedAddresses) {
  SimOptions o;
  o.cycles = 30;
  const double* t0 = nullptr;
  const State* lab0 = nullptr;
  size_t calls = 0, last = 0;
  std::vector<double> seen_t, seen_x;
  RunControls c;
  c.on_samples = [&](const double* t, const State* lab, size_t n) {
    if (calls++ == 0) t0 = t, lab0 = lab;
    ASSERT_EQ(t, t0);
    ASSERT_EQ(lab, lab0);
    ASSERT_GE(n, last);
    for (size_t i = last; i < n; ++i) seen_t.push_back(t[i]), seen_x.push_back(lab[i].x);
    last = n;
  };
  const SimResult r = RunSimulation(o, c);
  EXPECT_EQ(calls, 30u);
  EXPECT_EQ(r.t.data(), t0) << "the result keeps the arrays the callback saw";
  ASSERT_GT(seen_t.size(), 2000u);
  ASSERT_LE(seen_t.size(), r.t.size());
  for (size_t i = 0; i < seen_t.size(); ++i) {
    ASSERT_EQ(seen_t[i], r.t[i]) << i;
    ASSERT_EQ(seen_x[i], r.lab[i].x) << i;
  }
}

// The event sink (RunControls::on_event) sees every event of the log, in order and equal to the
// kept record, and the run is the same whether the log is kept or not.
TEST(Simulator, EventSinkSeesTheWholeLogWithoutKeepingIt) {
  SimOptions o;
  o.cycles = 40;
  const SimResult kept = RunSimulation(o);
  std::vector<EventRecord> seen;
  RunControls c;
  c.keep_events = false;
  c.on_event = [&](const EventRecord& e) { seen.push_back(e); };
  const SimResult r = RunSimulation(o, c);
  EXPECT_TRUE(r.events.empty());
  ASSERT_EQ(seen.size(), kept.events.size());
  ASSERT_GT(seen.size(), 100u);
  for (size_t i = 0; i < seen.size(); ++i) {
    ASSERT_EQ(seen[i].t, kept.events[i].t) << i;
    ASSERT_EQ(seen[i].kind, kept.events[i].kind) << i;
    ASSERT_EQ(seen[i].sphere, kept.events[i].sphere) << i;
    ASSERT_EQ(seen[i].detail, kept.events[i].detail) << i;
    ASSERT_EQ(seen[i].after.x, kept.events[i].after.x) << i;
  }
  ASSERT_EQ(r.lab.size(), kept.lab.size());
  EXPECT_EQ(r.lab.back().x, kept.lab.back().x);
}

}  // namespace
}  // namespace dimer::sim

namespace dimer::sim {
namespace {

// Ctrl-C: the run stops at a period boundary with everything before it intact.
TEST(Simulator, StopRequestEndsTheRunCleanlyAtAPeriodBoundary) {
  SimOptions o;
  o.cycles = 100;
  RunControls c;
  int polls = 0;
  c.should_stop = [&] { return ++polls >= 7; };
  const SimResult r = RunSimulation(o, c);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.periods.size(), 7u);
  ASSERT_FALSE(r.t.empty());
  // The last sample is the last grid point at or before the boundary (one interval at most).
  EXPECT_LE(r.t.back(), r.t_start + 7 * r.model.period + 1e-12);
  EXPECT_GT(r.t.back(), r.t_start + 7 * r.model.period - 1.0 / o.fps - 1e-12);
  const SimResult full = RunSimulation(o);
  for (size_t i = 0; i < r.t.size(); ++i) ASSERT_EQ(r.lab[i].x, full.lab[i].x);
}

}  // namespace
}  // namespace dimer::sim

namespace dimer::sim {
namespace {

// Dynamic similarity: with lengths scaled as g T^2 (diameter ~ 1/f^2, same lift in diameters)
// the model is the same in units of g and T, so <u> f / g must not depend on f. (At a fixed
// diameter it does, by a few per cent: a finite-size effect, see docs/MODEL.md, "Finite size".)
TEST(Simulator, DriftIsDynamicallySimilarWhenTheDiameterScalesAsOneOverFSquared) {
  double scaled[3];
  const double freqs[3] = {25, 50, 75};
  for (int i = 0; i < 3; ++i) {
    SimOptions o = EventsOnly({});
    o.freq_hz = freqs[i];
    o.diameter_m = 9.5e-3 * (25 / freqs[i]) * (25 / freqs[i]);
    o.lift = 0.3;
    o.cycles = 200;
    const SimResult r = RunSimulation(o);
    ASSERT_EQ(r.mode.label, "drift");
    scaled[i] = r.mode.drift_speed * freqs[i] / kGravity;
  }
  // Only the absolute gap tolerance (1e-13 m) is not scaled; it moves the speed by < 1e-5.
  EXPECT_NEAR(scaled[1], scaled[0], 1e-5 * scaled[0]);
  EXPECT_NEAR(scaled[2], scaled[0], 1e-5 * scaled[0]);
}

}  // namespace
}  // namespace dimer::sim

namespace dimer::sim {
namespace {

// The paper's Fig. 3(b): on a plate rising toward the bouncing end the drift can go uphill.
TEST(Simulator, DriftGoesUphillOnASmallTilt) {
  SimOptions o = EventsOnly({});
  o.tilt_deg = 2.0;  // rising toward +x, where the bouncing (right) end points
  o.cycles = 300;
  const SimResult r = RunSimulation(o);
  ASSERT_EQ(r.mode.label, "drift");
  EXPECT_EQ(r.mode.bouncing_sphere, kRight);
  EXPECT_GT(r.mode.drift_speed, 0.0);
}

// On a tilted plate the drift is measured along the plate, as the paper measures it and as
// compare reads a track of that plate: the centre of mass's lab displacement over the mode
// window projected on the plate (c dx + s dz; the plate's own motion along its normal drops
// out), not its horizontal part, which is cos(tilt) of it.
TEST(Simulator, DriftSpeedIsMeasuredAlongThePlate) {
  SimOptions o;
  o.tilt_deg = 3.0;
  o.cycles = 120;
  o.fps = 8 * o.freq_hz;  // a sample on every period's start
  const SimResult r = RunSimulation(o);
  ASSERT_EQ(r.mode.label, "drift");
  ASSERT_EQ(r.mode.bouncing_sphere, kRight);  // toward +x: the sign is +1
  const size_t last = r.lab.size() - 1, first = last - 8 * r.mode.window_periods;
  ASSERT_NEAR(r.t[last] - r.t[first], r.mode.window_periods * r.model.period, 1e-9);
  const double a = o.tilt_deg * std::numbers::pi / 180, span = r.t[last] - r.t[first];
  const double dx = r.lab[last].x - r.lab[first].x, dz = r.lab[last].z - r.lab[first].z;
  const double along = (std::cos(a) * dx + std::sin(a) * dz) / span;
  EXPECT_NEAR(r.mode.drift_speed, along, 1e-9 * std::abs(along));
  // The horizontal speed is measurably less (by 1 - cos 3 deg = 0.14 %).
  EXPECT_GT(std::abs(r.mode.drift_speed - dx / span), 1e-3 * std::abs(along));
}

}  // namespace
}  // namespace dimer::sim
