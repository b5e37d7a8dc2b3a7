// One definition of a significant impact (common/modes.h: approaching faster than 0.05 g/f)
// gives one count on one file: compare, reading the sampled positions of a simulation, counts
// in every period of the settled window the impacts the simulator counted from its events.
// The resting end's micro-bounces last a few frames, too few to fit an approach; counted as
// significant, they made 5 impacts a period against the simulator's 1 at A_r 3.9 and 3 against
// 0 at A_r 6.1 (periods.h, Impact::speed_bound).
#include <gtest/gtest.h>

#include <cmath>

#include "compare/simulate.h"

namespace dimer::compare {
namespace {

struct Scene {
  const char* name;
  double ar;
};

class ImpactCount : public ::testing::TestWithParam<Scene> {};

TEST_P(ImpactCount, CompareCountsTheSimulatorsSignificantImpacts) {
  sim::SimOptions o;
  o.ar = GetParam().ar;
  o.cycles = 100;
  o.fps = 2000;
  sim::SimResult r;
  const Analysis a = SimulateAndAnalyze(o, {}, GetParam().name, &r);
  const ModeWindow& w = a.periods.settled;
  ASSERT_EQ(w.summary.label, "drift");
  ASSERT_EQ(w.count, r.mode.window_periods);
  ASSERT_GE(r.periods.size(), static_cast<size_t>(w.first + w.count));
  for (int s = 0; s < 2; ++s) {
    EXPECT_DOUBLE_EQ(w.summary.impacts_per_period[s], r.mode.impacts_per_period[s]) << "sphere " << s;
    for (int k = w.first; k < w.first + w.count; ++k) {
      EXPECT_EQ(a.periods.rows[k].stats.impacts[s], r.periods[k].impacts[s]) << "sphere " << s << " period " << k;
    }
  }
  // The resting end does bounce off the plate in micro-bounces, which compare sees: they are
  // found, and left out of the count for being slow, not for being missed.
  const int rs = 1 - w.summary.bouncing_sphere;
  int slow = 0;
  for (const Impact& imp : a.contacts.sphere[rs].impacts) slow += !SignificantImpact(imp, a.periods.period_s);
  EXPECT_GT(slow, w.count);
}

INSTANTIATE_TEST_SUITE_P(Paper, ImpactCount, ::testing::Values(Scene{"ar_3_9", 3.9}, Scene{"ar_6_1", 6.1}),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace dimer::compare
