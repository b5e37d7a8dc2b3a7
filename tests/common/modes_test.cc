// The project's one definition of the modes (common/modes.h) on per-period statistics made by
// hand: the paper's drift mode is one end resting while the other bounces, whatever the
// bounce's period and however the resting end is knocked about.
#include "common/modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace dimer {
namespace {

constexpr double kT = 0.04;  // s, 25 Hz

// `n` periods in which sphere 0 hits `hits0[k % size]` times and rests `rest0` of the period,
// sphere 1 likewise; the CM moves `dx` per period.
std::vector<PeriodStats> Periods(int n, std::vector<int> hits0, double rest0, std::vector<int> hits1,
                                 double rest1, double dx) {
  std::vector<PeriodStats> p(n);
  for (int k = 0; k < n; ++k) {
    p[k].impacts = {hits0[k % hits0.size()], hits1[k % hits1.size()]};
    p[k].rest_time = {rest0 * kT, rest1 * kT};
    p[k].x_start = k * dx;
  }
  return p;
}

ModeSummary Label(const std::vector<PeriodStats>& p, double dx) {
  const int n = static_cast<int>(p.size());
  return ClassifyPeriods(p, 0, n, kT, n * dx, {-1, 1});
}

// sim --ar 2.6 --cycles 200: the left end hops 3 times a period and rests 10 % of it, the
// right bounces once a period; its state repeats to 1e-14 every period. A rule asking the
// resting end to rest >= 20 % calls it irregular.
TEST(Modes, ShortDimersHoppingEndIsDrift) {
  const double dx = 6.8e-4;  // m per period toward the right: 16.9 mm/s
  const ModeSummary ms = Label(Periods(100, {3}, 0.1028, {1}, 0, dx), dx);
  EXPECT_EQ(ms.label, "drift");
  EXPECT_EQ(ms.bouncing_sphere, 1);
  EXPECT_NEAR(ms.drift_speed, dx / kT, 1e-12);
}

// A_r 2.5 (Fig. 4a, 25 Hz): the resting end rests only 0.9 % but hops 4 times a period.
TEST(Modes, RestingEndThatBarelyRestsButHopsIsDrift) {
  EXPECT_EQ(Label(Periods(100, {4}, 0.0089, {1}, 0, 1e-4), 1e-4).label, "drift");
}

// A period-2 bounce: the bouncing end hits in every other period.
TEST(Modes, BounceOfPeriodTwoIsDrift) {
  const ModeSummary ms = Label(Periods(100, {1}, 0.4, {1, 0}, 0, 1e-4), 1e-4);
  EXPECT_EQ(ms.label, "drift");
  EXPECT_EQ(ms.bouncing_sphere, 1);
}

// sim --ar 3.0 --gamma 1.15 --eps 0.5 ... : the simulator measures a rest fraction of 0.198,
// compare 0.213 on the same file, either side of a 20 % threshold. Both are drift.
TEST(Modes, RestFractionEitherSideOfTheFormerThresholdGivesOneLabel) {
  EXPECT_EQ(Label(Periods(55, {3}, 0.198, {1}, 0, 1e-4), 1e-4).label, "drift");
  EXPECT_EQ(Label(Periods(55, {3}, 0.213, {1}, 0, 1e-4), 1e-4).label, "drift");
}

// One settled period gives a speed but no scatter to estimate its error from.
TEST(Modes, OnePeriodHasNoError) {
  const ModeSummary ms = Label(Periods(1, {3}, 0.3, {1}, 0, 2e-4), 2e-4);
  EXPECT_NEAR(ms.drift_speed, 2e-4 / kT, 1e-12);
  EXPECT_TRUE(std::isnan(ms.drift_speed_err));
  EXPECT_EQ(Label(Periods(2, {3}, 0.3, {1}, 0, 2e-4), 2e-4).drift_speed_err, 0.0);
}

// The orbit's period is its own figure, apart from the label.
TEST(Modes, OrbitPeriodIsReportedApartFromTheLabel) {
  EXPECT_EQ(Label(Periods(100, {3}, 0.1028, {1}, 0, 6.8e-4), 6.8e-4).orbit_periods, 1);
  const ModeSummary two = Label(Periods(100, {1}, 0.4, {1, 0}, 0, 1e-4), 1e-4);
  EXPECT_EQ(two.label, "drift");
  EXPECT_EQ(two.orbit_periods, 2);
  // A resting end that creeps: its advance changes from period to period.
  std::vector<PeriodStats> creep = Periods(40, {3}, 0.3, {1}, 0, 1e-4);
  for (int k = 0; k < 40; ++k) creep[k].x_start = 1e-4 * k + 1e-6 * k * k;
  EXPECT_EQ(ClassifyPeriods(creep, 0, 40, kT, 1e-4 * 40 + 1e-6 * 1600, {-1, 1}).orbit_periods, 0);
}

TEST(Modes, OtherModesKeepTheirRules) {
  EXPECT_EQ(Label(Periods(20, {0}, 1.0, {0}, 1.0, 0), 0).label, "rest");
  EXPECT_EQ(Label(Periods(20, {1}, 0, {1}, 0, 0), 0).label, "jump");
  EXPECT_EQ(Label(Periods(20, {1, 0}, 0, {0, 1}, 0, 0), 0).label, "flutter");
  // Neither end at the plate: one bounces, the other once a period without resting: jump.
  EXPECT_EQ(Label(Periods(20, {1}, 0.01, {1}, 0, 0), 0).label, "jump");
  // Both ends rest part of the period and hop: not one end resting while the other bounces.
  EXPECT_EQ(Label(Periods(20, {3}, 0.3, {1}, 0.3, 0), 0).label, "irregular");
  // The bouncing end hits twice a period: not a bounce of one period or more.
  EXPECT_EQ(Label(Periods(20, {3}, 0.3, {2}, 0, 0), 0).label, "irregular");
}

}  // namespace
}  // namespace dimer
