// A resting sphere's rows refereed by the plate it stands on (tracking/plate_agreement.h):
// plate and sphere rows made up over learning frames, the truth known.
#include "tracking/plate_agreement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

struct Rows {
  std::vector<double> edge, row;
};

// `n` learning frames spread over the plate's cycle (amplitude `amp` px): the edge found with
// noise 0.03 px; the sphere rests on it (its rows moving `gain` px per px of the edge's, noise
// 0.03 px) except in every `flight_every`-th frame, where it is `lift` px up in flight.
Rows Resting(int n, double amp, double gain, unsigned seed, int flight_every = 0,
             double lift = 0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 0.03);
  Rows r;
  for (int i = 0; i < n; ++i) {
    const double plate = 200 + amp * std::sin(2 * M_PI * 0.37 * i);
    const bool flight = flight_every > 0 && i % flight_every == 0;
    r.edge.push_back(plate + noise(rng));
    r.row.push_back(176 + gain * (plate - 200) - (flight ? lift : 0.0) + noise(rng));
  }
  return r;
}

TEST(PlateAgreement, ARestingSphereThatMovesWithThePlateAgrees) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Rows r = Resting(20, 0.25, 1.0, seed);
    const PlateAgreement a = AgreementWithPlate(r.edge, r.row);
    EXPECT_TRUE(a.agrees) << seed;
    EXPECT_NEAR(a.slope, 1.0, 4 * a.slope_err) << seed;
    EXPECT_EQ(a.frames, 20u) << seed;
  }
}

// An edge seen nearer or further than the dimer moves 0.7-1.4 times the contact line (POV-Ray
// mirror_plate 1.19, front_point 0.86 over its learning frames): a slope of its own, not a
// held sphere.
TEST(PlateAgreement, AnEdgeSeenNearerOrFurtherThanTheDimerAgrees) {
  for (double gain : {0.7, 0.86, 1.19, 1.4}) {
    for (unsigned seed = 1; seed <= 10; ++seed) {
      const Rows r = Resting(48, 1.0, gain, seed);
      EXPECT_TRUE(AgreementWithPlate(r.edge, r.row).agrees) << gain << " " << seed;
    }
  }
}

// POV-Ray ruler_above_plate: the resting sphere's rows moved 0.09 px per px of the plate's
// (held by the ruler's edge behind it) over a plate that moved 0.5 px.
TEST(PlateAgreement, RowsHeldByWhatStandsStillAreRejected) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Rows r = Resting(20, 0.25, 0.09, seed);
    const PlateAgreement a = AgreementWithPlate(r.edge, r.row);
    EXPECT_FALSE(a.agrees) << seed;
    EXPECT_NEAR(a.slope, 0.09, 0.2) << seed;
  }
}

// Frames in flight (the sphere 3 px up in every fourth) are not resting frames: left out of
// the fit, which still sees the held rows.
TEST(PlateAgreement, FramesInFlightAreLeftOut) {
  const Rows moving = Resting(40, 0.5, 1.0, 3, 4, 3.0);
  const PlateAgreement a = AgreementWithPlate(moving.edge, moving.row);
  EXPECT_TRUE(a.agrees);
  EXPECT_EQ(a.frames, 30u);
  EXPECT_NEAR(a.slope, 1.0, 0.1);
  const Rows held = Resting(40, 0.5, 0.1, 3, 4, 3.0);
  EXPECT_FALSE(AgreementWithPlate(held.edge, held.row).agrees);
}

// Too few resting frames, or a plate too still for the slope to be known, decide nothing.
TEST(PlateAgreement, TooLittleEvidenceDecidesNothing) {
  const Rows few = Resting(kMinPlateAgreementFrames - 1, 0.5, 0.0, 1);
  EXPECT_TRUE(AgreementWithPlate(few.edge, few.row).agrees);
  const Rows still = Resting(20, 0.005, 0.0, 1);
  EXPECT_TRUE(AgreementWithPlate(still.edge, still.row).agrees);
  EXPECT_TRUE(AgreementWithPlate({}, {}).agrees);
}

TEST(PlateAgreement, ANewAppearanceIsTakenOnlyWhereItMovesNearerWithThePlate) {
  PlateAgreement held, better, same;
  held.slope = 0.09, held.slope_err = 0.01;
  better.slope = 0.55, better.slope_err = 0.04;
  same.slope = 0.12, same.slope_err = 0.04;
  EXPECT_TRUE(MovesMoreWithThePlate(better, held));
  EXPECT_FALSE(MovesMoreWithThePlate(same, held));
  EXPECT_FALSE(MovesMoreWithThePlate(held, better));
  EXPECT_FALSE(MovesMoreWithThePlate(PlateAgreement{}, held));
}

// The rows' stated uncertainty covers how far held rows part from the plate's motion, only
// where they were held.
TEST(PlateAgreement, HeldRowsWidenTheirStatedUncertainty) {
  PlateAgreement a;
  a.slope = 0.55, a.slope_err = 0.04, a.edge_sd = 0.17;
  EXPECT_NEAR(WidenForPlate(a, true, 0.03), std::hypot(0.03, 0.45 * 0.17), 1e-12);
  EXPECT_EQ(WidenForPlate(a, false, 0.03), 0.03);
  EXPECT_EQ(WidenForPlate(PlateAgreement{}, true, 0.03), 0.03);
}

}  // namespace
}  // namespace dimer::tracking
