// A simulation beside a track is analysed as the camera saw the track (compare/analysis.h,
// SeenAsTrack): the track's contact thresholds and slip filter. The slip of the drift's resting
// end is read over the frames its gap puts in contact; a camera's noise raises that threshold
// (4 sigma), and the resting end lifts by tens of micrometres at fixed plate phases, so a
// simulation read with its own threshold reports the slip over other frames. On POV-Ray films
// (bench/povray_film.sh) the slip before the impact read 2.7-3.7 mm/s against the simulation's
// 2.30 read with its own threshold.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../common/test_tmpdir.h"
#include "common/h5_file.h"
#include "common/provenance.h"
#include "common/trajectory_io.h"
#include "compare/analysis.h"
#include "compare/run_compare.h"
#include "sim/sim_file.h"
#include "sim/simulator.h"

namespace dimer::compare {
namespace {

TEST(SeenAsTrack, TheSimulationsSlipIsReadAsTheCameraSawTheTrack) {
  testing::TempDir dir;
  sim::SimOptions o;  // the sample drift scene: A_r 3.9, Gamma 0.9, 25 Hz
  o.cycles = 40;
  o.fps = 2000;
  const sim::SimResult r = sim::RunSimulation(o);
  const std::string sim_path = dir / "sim.h5";
  sim::WriteSimFile(sim_path, false, o, r);
  // The camera: 35 um of noise on each centre (0.09 px at 0.4 mm/px), the plate exact.
  Trajectory traj;
  {
    H5Reader in(sim_path);
    traj = ReadTrajectory(in);
  }
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0, 35e-6);
  for (auto* tips : {&traj.tip_left, &traj.tip_right}) {
    for (Eigen::Vector2d& p : *tips) p += Eigen::Vector2d(noise(rng), noise(rng));
  }
  const std::string track_path = dir / "track.h5";
  {
    H5Writer w(track_path);
    WriteProvenance(w, "track", {{"fps", 2000.0}, {"diameter", o.diameter_m}, {"m_per_px", 4e-4},
                                 {"row0", 200.0}});
    WriteTrajectory(w, traj);
    w.Close();
  }
  const Analysis track = Analyze(LoadSampledRun(track_path), {});
  const Analysis own = Analyze(LoadSampledRun(sim_path), {});
  const Analysis seen = Analyze(LoadSampledRun(sim_path), SeenAsTrack(track, {}));
  ASSERT_EQ(track.periods.settled.summary.label, "drift");
  for (int s = 0; s < 2; ++s) {
    EXPECT_GT(track.contacts.sphere[s].threshold_m, own.contacts.sphere[s].threshold_m) << s;
    EXPECT_GE(seen.contacts.sphere[s].threshold_m, track.contacts.sphere[s].threshold_m) << s;
  }
  EXPECT_EQ(seen.slip.half_window, track.slip.half_window);
  const double err = std::hypot(track.slip.before_err, seen.slip.before_err);
  std::printf("slip before the impact: track %.3f, simulation seen so %.3f, read alone %.3f mm/s "
              "(+- %.3f)\n",
              track.slip.before * 1e3, seen.slip.before * 1e3, own.slip.before * 1e3, err * 1e3);
  EXPECT_LE(std::abs(track.slip.before - seen.slip.before), 3 * err);
  EXPECT_GT(std::abs(track.slip.before - own.slip.before), 3 * err)
      << "the camera's threshold no longer changes which frames the slip is read over";

  // compare --sim reports the simulation so seen (compare.h5's headline attributes).
  CompareArgs a;
  a.input = track_path;
  a.sim_path = sim_path;
  a.output = dir / "report";
  a.quiet = true;
  ASSERT_EQ(RunCompare(a), 0);
  H5Reader out(dir / "report/compare.h5");
  EXPECT_EQ(out.AttrDouble("/", "sim_slip_before").value_or(NAN), seen.slip.before);
  EXPECT_EQ(out.AttrDouble("/", "sim_slip_after").value_or(NAN), seen.slip.after);
}

}  // namespace
}  // namespace dimer::compare
