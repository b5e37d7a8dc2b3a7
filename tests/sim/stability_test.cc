// Numerical stability at the extremes (the simulator's robustness targets): every run must end without NaN, without
// penetration deeper than the gap tolerance, with a bounded number of events per period and
// without numerical failures; the counts are reported as test properties.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <sstream>

#include "sim/reference_frames.h"
#include "sim/simulator.h"
#include "tests/sim/test_models.h"

namespace dimer::sim {
namespace {

struct Extreme {
  const char* name;
  void (*apply)(SimOptions&);
};

void ExpectHealthy(const SimOptions& o, const SimResult& r, const std::string& what) {
  EXPECT_TRUE(r.error.empty()) << what << ": " << r.error;
  for (size_t i = 0; i < r.lab.size(); ++i) {
    const State& q = r.lab[i];
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.z) && std::isfinite(q.th) &&
                std::isfinite(q.u) && std::isfinite(q.v) && std::isfinite(q.w))
        << what << ": NaN at sample " << i;
  }
  EXPECT_LE(r.diag.max_penetration_m, o.gap_tol * (1 + 1e-6)) << what;
  EXPECT_EQ(r.diag.impact_failures, 0) << what;
  EXPECT_EQ(r.diag.capped_searches, 0) << what;
  EXPECT_LE(r.diag.max_events_in_period, 200) << what << ": event storm";
}

void PrintTo(const Extreme& e, std::ostream* os) { *os << e.name; }
class Extremes : public ::testing::TestWithParam<Extreme> {};

TEST_P(Extremes, NoNaNNoPenetrationNoEventStorm) {
  for (InitKind init : {InitKind::kDrift, InitKind::kRest, InitKind::kFlutter}) {
    SimOptions o;
    o.cycles = 60;
    o.fps = 1000;
    o.init = init;
    GetParam().apply(o);
    if (init == InitKind::kFlutter && M_PI * (1 - o.eps) / (1 + o.eps) > o.gamma) continue;
    const SimResult r = RunSimulation(o);
    std::ostringstream what;
    what << GetParam().name << " init " << ToString(init);
    ExpectHealthy(o, r, what.str());
    RecordProperty(std::string(GetParam().name) + "_" + ToString(init) + "_max_events_in_period",
                   r.diag.max_events_in_period);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Sim, Extremes,
    ::testing::Values(Extreme{"eps0", [](SimOptions& o) { o.eps = 0; }},
                      Extreme{"eps0_01", [](SimOptions& o) { o.eps = 0.01; }},
                      Extreme{"eps0_99", [](SimOptions& o) { o.eps = 0.99; }},
                      Extreme{"eps1", [](SimOptions& o) { o.eps = 1; }},
                      Extreme{"mu0", [](SimOptions& o) { o.mu = o.mu_s = o.mu_hat = o.mu_hat_s = 0; }},
                      Extreme{"mu10", [](SimOptions& o) { o.mu = o.mu_s = o.mu_hat = o.mu_hat_s = 10; }},
                      Extreme{"gamma0", [](SimOptions& o) { o.gamma = 0; }},
                      Extreme{"gamma0_999", [](SimOptions& o) { o.gamma = 0.999; }},
                      Extreme{"gamma1_5", [](SimOptions& o) { o.gamma = 1.5; }},
                      Extreme{"gamma3", [](SimOptions& o) { o.gamma = 3; }},
                      Extreme{"ar1_05", [](SimOptions& o) { o.ar = 1.05; o.lift = 0.02; }},
                      Extreme{"ar20", [](SimOptions& o) { o.ar = 20; }},
                      Extreme{"tilt10", [](SimOptions& o) { o.tilt_deg = 10; }},
                      Extreme{"tilt_minus30", [](SimOptions& o) { o.tilt_deg = -30; }}),
    [](const ::testing::TestParamInfo<Extreme>& p) { return std::string(p.param.name); });

// An exactly flat dimer dropped flat: both spheres hit at the same instant, every time.
TEST(Stability, FlatDimerDroppedFlatStaysFlat) {
  SimOptions o;
  o.gamma = 0;
  o.cycles = 50;
  o.fps = 0;
  o.init_state = std::array<double, 6>{0, 0.02, 0, 0, 0, 0};
  const SimResult r = RunSimulation(o);
  ExpectHealthy(o, r, "flat drop");
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(r.events.front().kind, EventKind::kDoubleImpact);
  for (const EventRecord& e : r.events) {
    EXPECT_EQ(e.after.th, 0.0);
    EXPECT_EQ(e.after.w, 0.0);
  }
  EXPECT_EQ(r.mode.label, "rest");
}

// Simultaneous contacts that are not flat: a dimer landing on both spheres after a half turn.
TEST(Stability, HalfTurnLandingOnBothSpheres) {
  SimOptions o;
  o.gamma = 0.9;
  o.cycles = 40;
  o.fps = 0;
  o.init_state = std::array<double, 6>{0, 0.03, M_PI, 0.01, 0, 0};
  const SimResult r = RunSimulation(o);
  ExpectHealthy(o, r, "half turn");
}

// A long run: 10^6 periods of the drift mode (scaled down under sanitizers).
TEST(Stability, LongDriftRunStaysHealthyAndInTheDriftMode) {
  SimOptions o;
  o.cycles = static_cast<double>(testing::Scaled(1000000));
  o.fps = 0;
  RunControls c;
  c.keep_events = false;
  const SimResult r = RunSimulation(o, c);
  ExpectHealthy(o, r, "long run");
  EXPECT_EQ(r.mode.label, "drift");
  EXPECT_EQ(static_cast<double>(r.periods.size()), o.cycles);
  RecordProperty("events_per_period", std::to_string(r.diag.events / o.cycles));
}

}  // namespace
}  // namespace dimer::sim
