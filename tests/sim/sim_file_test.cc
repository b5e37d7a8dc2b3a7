#include "sim/sim_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "common/error.h"
#include "common/h5_file.h"
#include "common/trajectory_io.h"
#include "sim/reference_frames.h"
#include "sim/run_sim.h"
#include "tests/common/test_tmpdir.h"

namespace dimer::sim {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

TEST(SimFile, FollowsTheSharedLayoutWithEveryParameter) {
  dimer::testing::TempDir dir;
  SimOptions o;
  o.cycles = 5;
  o.tilt_deg = 3;
  const SimResult r = RunSimulation(o);
  WriteSimFile(dir / "s.h5", false, o, r);
  H5Reader h(dir / "s.h5");
  EXPECT_EQ(FileKind(h), "sim");
  for (const char* key : {"ar", "diameter", "freq", "gamma", "tilt_deg", "eps", "mu", "mu_s",
                          "mu_hat", "mu_hat_s", "lift", "release_phase", "fps", "gap_tol",
                          "collapse_vc", "contact_tol", "drift_speed", "drift_scaled",
                          "events_per_period", "max_penetration_m"}) {
    EXPECT_TRUE(h.AttrDouble("/", key).has_value()) << key;
  }
  EXPECT_EQ(h.AttrString("/", "init"), "drift");
  EXPECT_TRUE(h.AttrString("/", "created").has_value());
  const Trajectory traj = ReadTrajectory(h);
  ASSERT_EQ(traj.size(), r.t.size());
  Dims dims;
  const auto state = h.ReadDoubles("/state", &dims);
  ASSERT_EQ(dims, (Dims{r.t.size(), 6}));
  // Tips, theta and plate height agree with the lab state and the model.
  const Model& m = r.model;
  for (size_t i = 0; i < traj.size(); i += 17) {
    const State q{state[6 * i], state[6 * i + 1], state[6 * i + 2], 0, 0, 0};
    const double k = m.A * m.R;
    EXPECT_NEAR(traj.tip_right[i].x() - traj.tip_left[i].x(), 2 * k * std::cos(q.th), 1e-15);
    EXPECT_NEAR(traj.tip_right[i].y() - traj.tip_left[i].y(), 2 * k * std::sin(q.th), 1e-15);
    EXPECT_EQ(traj.theta[i], q.th);
    EXPECT_NEAR(traj.plate_z[i], PlateSurfaceZ(m, traj.t[i], q.x), 1e-15);
  }
  const auto kinds = h.ReadStrings("/events/kind");
  EXPECT_EQ(kinds.size(), r.events.size());
  EXPECT_EQ(h.ReadDoubles("/events/before").size(), 6 * r.events.size());
  EXPECT_EQ(h.ReadInt8("/events/sphere").size(), r.events.size());
  EXPECT_EQ(h.AttrString("/t", "units"), "s");
}

TEST(SimFile, RunSimRefusesToOverwriteAndRerunsBitIdentically) {
  dimer::testing::TempDir dir;
  SimRunArgs a;
  a.options.cycles = 3;
  a.output = dir / "a.h5";
  a.progress = false;
  setenv("SOURCE_DATE_EPOCH", "1763770000", 1);
  ASSERT_EQ(RunSim(a), 0);
  EXPECT_THROW(RunSim(a), InputError);  // exists, no --force
  SimRunArgs b = a;
  b.output = dir / "b.h5";
  ASSERT_EQ(RunSim(b), 0);
  unsetenv("SOURCE_DATE_EPOCH");
  auto slurp = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), {});
  };
  EXPECT_EQ(slurp(a.output), slurp(b.output));
  a.force = true;
  a.options.cycles = 4;
  EXPECT_EQ(RunSim(a), 0);
  EXPECT_NE(slurp(a.output), slurp(b.output));
}

// The file's chunks are compressed on worker threads (common/h5_chunk_filter.h): the same bytes
// on 1, 2 or 5 threads as through HDF5's own filter pipeline, with samples and events only.
TEST(SimFile, BytesDoNotDependOnTheCompressionThreads) {
  dimer::testing::TempDir dir;
  setenv("SOURCE_DATE_EPOCH", "0", 1);
  auto slurp = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), {});
  };
  for (double fps : {0.0, 2000.0}) {
    SimOptions o;
    o.cycles = 200;  // 16001 samples: /state in 3 chunks, the last partial
    o.fps = fps;
    const SimResult r = RunSimulation(o);
    H5WriteOptions hdf5;
    hdf5.direct_chunks = false;
    WriteSimFile(dir / "hdf5.h5", true, o, r, hdf5);
    const std::string oracle = slurp(dir / "hdf5.h5");
    for (int threads : {1, 2, 5}) {
      H5WriteOptions direct;
      direct.threads = threads;
      WriteSimFile(dir / "direct.h5", true, o, r, direct);
      EXPECT_TRUE(slurp(dir / "direct.h5") == oracle) << "fps " << fps << ", " << threads;
    }
  }
  unsetenv("SOURCE_DATE_EPOCH");
}

TEST(SimFile, BadInitStateIsAClearError) {
  EXPECT_THROW(ParseInitState("1,2,3"), InputError);
  EXPECT_THROW(ParseInitState("1,2,3,4,5,x"), InputError);
  const auto v = ParseInitState("0,0.006,0.1,0,-1e-3,2");
  EXPECT_EQ(v[1], 0.006);
  EXPECT_EQ(v[4], -1e-3);
  SimOptions o;
  o.init_state = std::array<double, 6>{0, -0.01, 0, 0, 0, 0};  // below the plate
  EXPECT_THROW(RunSimulation(o), InputError);
}

}  // namespace
}  // namespace dimer::sim

namespace dimer::sim {
namespace {

// An initial condition that does not reach its mode says so: the mode reached and the likely
// reason, on stderr and in the file's `mode_note`; a run that does reach it says nothing.
TEST(SimFile, AnInitThatMissesItsModeSaysWhichModeAndWhy) {
  dimer::testing::TempDir dir;
  SimRunArgs a;
  a.options.init = InitKind::kFlutter;  // at the paper's Gamma 0.9
  a.options.cycles = 40;
  a.output = dir / "flutter.h5";
  a.progress = false;
  ASSERT_EQ(RunSim(a), 0);
  H5Reader h(a.output);
  const std::string settled = h.AttrString("/", "settled_mode").value_or("");
  ASSERT_NE(settled, "flutter");
  const std::string note = h.AttrString("/", "mode_note").value_or("");
  EXPECT_NE(note.find("--init flutter settled in " + settled + " mode"), std::string::npos)
      << note;
  EXPECT_NE(note.find("not reachable from the default launch"), std::string::npos) << note;
  SimRunArgs drift = a;
  drift.options.init = InitKind::kDrift;
  drift.output = dir / "drift.h5";
  ASSERT_EQ(RunSim(drift), 0);
  H5Reader hd(drift.output);
  EXPECT_EQ(hd.AttrString("/", "settled_mode"), "drift");
  EXPECT_EQ(hd.AttrString("/", "mode_note"), "");
}

}  // namespace
}  // namespace dimer::sim

namespace dimer::sim {
namespace {

// RunSim compresses the samples' whole chunks while the simulation runs (run_sim.cc): its file
// is HDF5's own, byte for byte, on 1 and 2 threads. 500 periods: 40001 samples, so /t has one
// whole chunk ahead and /state seven.
TEST(SimFile, RunSimGivesHdf5sBytes) {
  dimer::testing::TempDir dir;
  setenv("SOURCE_DATE_EPOCH", "0", 1);
  SimOptions o;
  o.cycles = 500;
  H5WriteOptions hdf5;
  hdf5.direct_chunks = false;
  WriteSimFile(dir / "hdf5.h5", true, o, RunSimulation(o), hdf5);
  const std::string oracle = Slurp(dir / "hdf5.h5");
  for (int threads : {1, 2}) {
    SimRunArgs a;
    a.options = o;
    a.output = dir / "run.h5";
    a.force = true;
    a.progress = false;
    a.threads = threads;
    ASSERT_EQ(RunSim(a), 0);
    EXPECT_TRUE(Slurp(a.output) == oracle) << threads << " threads";
  }
  unsetenv("SOURCE_DATE_EPOCH");
}

}  // namespace
}  // namespace dimer::sim
