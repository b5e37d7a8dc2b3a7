#include "sim/flight.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim/constants.h"
#include "tests/sim/test_models.h"

namespace dimer::sim {
namespace {

Model DrivenModel(double gamma, double tilt_deg = 0, double ar = 3.9) {
  SimOptions o;
  o.gamma = gamma;
  o.tilt_deg = tilt_deg;
  o.ar = ar;
  return Model::FromOptions(o);
}

TEST(Flight, PropagationComposesExactly) {
  const Model m = DrivenModel(0.9, 5.0);
  const State q0{0.001, 0.02, 0.3, 0.1, 0.5, 12.0};
  const double t0 = 0.0137, a = 0.0123, b = 0.0311;
  const State direct = FlightPropagate(m, q0, t0, a + b);
  const State split = FlightPropagate(m, FlightPropagate(m, q0, t0, a), t0 + a, b);
  EXPECT_NEAR(direct.x, split.x, 1e-15);
  EXPECT_NEAR(direct.z, split.z, 1e-15);
  EXPECT_NEAR(direct.th, split.th, 1e-14);
  EXPECT_NEAR(direct.v, split.v, 1e-14);
}

// The plate-frame motion must be the lab's ballistic motion minus the plate's displacement.
TEST(Flight, PlateFrameMatchesBallisticLabMotion) {
  const Model m = DrivenModel(0.9);
  const State q0{0.0, 0.02, 0.0, 0.1, 0.5, 0.0};
  const double t0 = 0.005, dt = 0.03;
  const double z_lab0 = q0.z + m.PlateZ(t0), v_lab0 = q0.v + m.PlateV(t0);
  const double z_lab1 = z_lab0 + v_lab0 * dt - 0.5 * kGravity * dt * dt;
  const State q1 = FlightPropagate(m, q0, t0, dt);
  EXPECT_NEAR(q1.z + m.PlateZ(t0 + dt), z_lab1, 1e-15);
  EXPECT_NEAR(q1.v + m.PlateV(t0 + dt), v_lab0 - kGravity * dt, 1e-14);
}

// A fast-spinning dimer at the top of its flight whose right sphere sweeps past the plate with
// a minimum gap of exactly `delta` at tau_star: a grazing contact by construction.
struct Grazing {
  Model m;
  State q0;
  double tau_star;
};
Grazing MakeGrazing(double delta, double omega) {
  Grazing g{DrivenModel(0.0), {}, 0.004};
  const Model& m = g.m;
  const double arm = m.A * m.R;
  // At tau_star: CM at its apex, theta = -pi/2 (right sphere straight below).
  g.q0.w = omega;
  g.q0.th = -M_PI / 2 - omega * g.tau_star;
  g.q0.v = kGravity * g.tau_star;
  const double z_star = m.R + arm + delta;
  g.q0.z = z_star - 0.5 * kGravity * g.tau_star * g.tau_star;
  return g;
}

TEST(Flight, GrazingRootsAreFoundAndNearMissesAreNot) {
  for (double omega : {60.0, 200.0, -150.0}) {
    for (double delta : {1e-6, 1e-9, 1e-11, -1e-11, -1e-9, -1e-6}) {
      const Grazing g = MakeGrazing(delta, omega);
      ASSERT_GT(FlightGap(g.m, g.q0, 0, 0, kRight).h, 0.0);
      const double window = g.tau_star + 0.3 * M_PI / std::abs(omega);
      const ImpactSearch is = FindFlightImpact(g.m, g.q0, 0.0, window, kRight);
      EXPECT_FALSE(is.capped);
      if (delta > 0) {
        EXPECT_FALSE(is.found) << "near miss by " << delta << " m reported, omega " << omega;
      } else {
        ASSERT_TRUE(is.found) << "grazing penetration of " << -delta << " m missed";
        EXPECT_LT(is.dt, g.tau_star);
        EXPECT_NEAR(FlightGap(g.m, g.q0, 0, is.dt, kRight).h, 0.0, 1e-15);
      }
    }
  }
}

// Property: over random flights (driven, tilted, spinning), the finder's first root agrees
// with a dense brute-force scan refined by bisection, and is never a false alarm.
TEST(Flight, NoMissedImpactAgainstDenseScan) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(0, 1);
  const long n = testing::Scaled(3000);
  int found = 0;
  for (long i = 0; i < n; ++i) {
    const Model m = DrivenModel(1.5 * uni(rng), 10 * (uni(rng) - 0.5), 1.05 + 9 * uni(rng));
    State q;
    q.th = 2 * M_PI * uni(rng);
    q.w = 200 * (uni(rng) - 0.5);
    q.z = m.A * m.R * std::abs(std::sin(q.th)) + m.R + 0.003 * uni(rng) + 1e-9;
    q.v = 0.4 * (uni(rng) - 0.5);
    q.u = 0.1 * (uni(rng) - 0.5);
    const double t0 = m.period * uni(rng), window = 0.05;
    const int s = i % 2;
    if (FlightGap(m, q, t0, 0, s).h <= 0) continue;
    const ImpactSearch is = FindFlightImpact(m, q, t0, window, s);
    ASSERT_FALSE(is.capped);
    // Dense scan: 20000 samples; a sign change is then bisected.
    const int k = 20000;
    double t_scan = -1;
    double prev = FlightGap(m, q, t0, 0, s).h;
    for (int j = 1; j <= k && t_scan < 0; ++j) {
      const double tj = window * j / k, hj = FlightGap(m, q, t0, tj, s).h;
      if (hj < 0 && prev > 0) {
        double lo = window * (j - 1) / k, hi = tj;
        for (int b = 0; b < 80; ++b) {
          const double mid = 0.5 * (lo + hi);
          (FlightGap(m, q, t0, mid, s).h > 0 ? lo : hi) = mid;
        }
        t_scan = hi;
      }
      prev = hj;
    }
    if (t_scan >= 0) {
      ASSERT_TRUE(is.found) << "flight " << i << ": missed a root at " << t_scan;
      // Finder may only be earlier than the scan (a dip the scan stepped over), never later.
      EXPECT_LE(is.dt, t_scan + 1e-12) << "flight " << i;
      ++found;
    }
    if (is.found) {
      EXPECT_NEAR(FlightGap(m, q, t0, is.dt, s).h, 0.0, 1e-14) << "flight " << i;
      EXPECT_LT(FlightGap(m, q, t0, is.dt, s).hd, 0.0) << "flight " << i;
    }
  }
  EXPECT_GT(found, n / 4) << "the random flights should mostly end in impacts";
}

}  // namespace
}  // namespace dimer::sim
