// compare on a tilted plate (sim --tilt-deg, the paper's Fig. 4b): simulations are analysed in
// the plate's frame, the frame a track of the tilted plate is in (common/plate_frame.h). Along
// the plate, the drift is the simulator's (measured along the plate too), the plate's motion along
// its normal gives the simulated Gamma, the slip is relative to the plate, a free flight gives
// the tilt back, a sim file reads as the simulation in memory, and a tilted simulation is never
// mirrored onto a track (its mirror image is the opposite tilt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../common/test_tmpdir.h"
#include "compare/comparison.h"
#include "compare/simulate.h"
#include "compare/tilt_notes.h"
#include "sim/reference_frames.h"
#include "sim/sim_file.h"
#include "sim/state.h"
#include "tests/compare/exact_slip.h"

namespace dimer::compare {
namespace {

sim::SimOptions Tilted(double tilt_deg, sim::InitKind init, double cycles) {
  sim::SimOptions o;
  o.ar = 3.9;
  o.tilt_deg = tilt_deg;
  o.init = init;
  o.cycles = cycles;
  o.fps = 2000;
  return o;
}

double Cos(double deg) { return std::cos(deg * std::numbers::pi / 180); }

TEST(TiltedPlate, DriftAlongThePlateAndTheDriveAlongItsNormal) {
  for (double tilt : {-2.0, 3.0}) {
    sim::SimResult r;
    const Analysis a = SimulateAndAnalyze(Tilted(tilt, sim::InitKind::kDrift, 120), {}, "tilted", &r);
    ASSERT_EQ(a.periods.settled.summary.label, "drift") << tilt;
    ASSERT_EQ(r.mode.label, "drift") << tilt;
    EXPECT_EQ(a.run.sim_tilt_deg, tilt);
    // The centre of mass climbs (or descends) the plate: compare's drift along it is the
    // simulator's, which is measured along the plate too (not the horizontal, cos(tilt) of it).
    const double along = r.mode.drift_speed;
    EXPECT_NEAR(a.drift.speed, along, 1e-6 * std::abs(along)) << tilt;
    EXPECT_GT(std::abs(a.drift.speed - along * Cos(tilt)), 1e-4 * std::abs(along)) << tilt;
    // The plate moves along its normal (sim/model.h), the same height under the dimer wherever
    // it is: the fit gives the simulated drive.
    EXPECT_NEAR(a.plate.gamma, 0.9, 1e-3) << tilt;
    EXPECT_NEAR(a.plate.freq_hz, 25.0, 1e-6) << tilt;
    // The resting sphere sits on the plate: its gap along the normal is ~0 while it rests.
    const int rs = a.slip.resting_sphere;
    ASSERT_GE(rs, 0);
    EXPECT_LT(std::abs(a.contacts.sphere[rs].level_m), 1e-6) << tilt;
  }
}

TEST(TiltedPlate, SlipIsTheContactsVelocityRelativeToThePlate) {
  sim::SimResult r;
  const Analysis a = SimulateAndAnalyze(Tilted(3.0, sim::InitKind::kDrift, 200), {}, "slip", &r);
  ASSERT_EQ(a.periods.settled.summary.label, "drift");
  const ExactSlip x = ExactSlipProfile(a, r);
  const double peak = x.peak;
  const std::vector<double>& mean = x.mean;
  ASSERT_GT(peak, 0);
  // Most bins agree to 1e-4 of the peak. Where the slip sticks (phase 0.5-0.65: a kink in U(t))
  // the positions' slope filter rounds the kink off, up to 3.8 % of the peak here (2.3 % on a
  // level plate, SimSlip above); the lab frame's slip would be 5 % off in the median bin.
  std::vector<double> off;
  for (size_t b = 0; b < mean.size(); ++b) {
    if (!std::isfinite(mean[b])) continue;
    EXPECT_NEAR(a.slip.profile[b], mean[b], 0.05 * peak) << "bin " << b;
    off.push_back(std::abs(a.slip.profile[b] - mean[b]));
  }
  ASSERT_GE(off.size(), 20u);
  std::nth_element(off.begin(), off.begin() + off.size() / 2, off.end());
  EXPECT_LT(off[off.size() / 2], 0.005 * peak);
}

TEST(TiltedPlate, FreeFlightsGiveTheTiltBack) {
  for (double tilt : {-5.0, 0.0, 3.0}) {
    const Analysis a = SimulateAndAnalyze(Tilted(tilt, sim::InitKind::kJump, 30), {}, "jump");
    ASSERT_EQ(a.periods.settled.summary.label, "jump") << tilt;
    const FreeFall& f = a.free_fall;
    ASSERT_GT(f.flights, 5) << f.note;
    EXPECT_NEAR(f.tilt_deg, tilt, 1e-6) << tilt;
    EXPECT_NEAR(f.g_fit, kGravity, 1e-6 * kGravity) << tilt;
  }
}

TEST(TiltedPlate, ASimFileReadsAsTheSimulationInMemory) {
  testing::TempDir dir;
  const sim::SimOptions o = Tilted(3.0, sim::InitKind::kDrift, 60);
  sim::SimResult r;
  const Analysis mem = SimulateAndAnalyze(o, {}, "mem", &r);
  sim::WriteSimFile(dir / "sim.h5", false, o, r);
  const SampledRun run = LoadSampledRun(dir / "sim.h5");
  EXPECT_EQ(run.sim_tilt_deg, 3.0);
  const Analysis file = Analyze(run, {});
  EXPECT_EQ(file.periods.settled.summary.label, "drift");
  EXPECT_NEAR(file.drift.speed, mem.drift.speed, 1e-9);
  ASSERT_EQ(run.n, mem.run.n);
  for (size_t i = 0; i < run.n; i += 97) {
    EXPECT_NEAR(run.z[0][i], mem.run.z[0][i], 1e-12) << i;
    EXPECT_NEAR(run.plate_z[i], mem.run.plate_z[i], 1e-12) << i;
    // The exact state is turned alike: its height along the normal is the tips' mean.
    EXPECT_NEAR(run.state[i][1], 0.5 * (run.z[0][i] + run.z[1][i]), 1e-12) << i;
  }
  // The scene simulated beside a track keeps the tilt the user gave, and says so.
  std::vector<std::string> notes;
  const sim::SimOptions scene = SceneFromTrack(file, o, 10, &notes);
  EXPECT_EQ(scene.tilt_deg, 3.0);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("tilt 3 deg (compared in the plate's frame)"), std::string::npos) << notes[0];
}

// The run seen in a mirror (x -> -x, left <-> right): what a camera on the other side films.
SampledRun Mirrored(SampledRun r) {
  for (size_t i = 0; i < r.n; ++i) {
    std::swap(r.x[0][i], r.x[1][i]);
    std::swap(r.z[0][i], r.z[1][i]);
    r.x[0][i] = -r.x[0][i];
    r.x[1][i] = -r.x[1][i];
    r.theta[i] = -r.theta[i];
  }
  FindGaps(&r);
  return r;
}

TEST(TiltedPlate, ATiltedSimulationIsNeverMirrored) {
  for (double tilt : {0.0, 3.0}) {
    const Analysis sim = SimulateAndAnalyze(Tilted(tilt, sim::InitKind::kDrift, 60), {}, "sim");
    SampledRun seen = Mirrored(sim.run);
    seen.kind = "track";
    const Analysis track = Analyze(seen, {});
    ASSERT_NE(track.periods.settled.summary.bouncing_sphere, sim.periods.settled.summary.bouncing_sphere);
    const Comparison c = CompareWithSimulation(track, sim);
    EXPECT_EQ(c.mirrored, tilt == 0) << tilt;
  }
}

TEST(TiltNotes, TheEdgesSlopeAndAFlightTiltApartFromTheSimulationsAreNoted) {
  Analysis a;
  a.run.kind = "track";
  EXPECT_TRUE(TiltNotes(a, NAN).empty());  // a level edge, no flights
  a.run.plate_slope = -std::tan(1.0 * std::numbers::pi / 180);  // rising 1 degree toward +x
  std::vector<std::string> n = TiltNotes(a, NAN);
  ASSERT_EQ(n.size(), 1u);
  EXPECT_NE(n[0].find("slopes by 1 deg"), std::string::npos) << n[0];
  a.free_fall.tilt_deg = 2.2, a.free_fall.tilt_deg_err = 0.12;
  EXPECT_EQ(TiltNotes(a, 2.0).size(), 1u);  // 0.2 deg off: within 0.3 deg, no note
  n = TiltNotes(a, 0.0);
  ASSERT_EQ(n.size(), 2u);
  EXPECT_NE(n[1].find("flights fall 2.2 +- 0.12 deg"), std::string::npos) << n[1];
  a.free_fall.tilt_deg_err = 1.0;  // 2.2 deg off but within 3 sigma: no note
  EXPECT_EQ(TiltNotes(a, 0.0).size(), 1u);
  a.run.kind = "sim";  // a sim's frame is its own: no slope note
  EXPECT_TRUE(TiltNotes(a, 0.0).empty());
}

}  // namespace
}  // namespace dimer::compare
