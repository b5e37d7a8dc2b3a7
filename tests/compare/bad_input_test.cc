// Bad input to `compare` gives one clear line (an InputError naming the file and the problem)
// and writes nothing; a partly bad track is analysed where it is good, with its gaps listed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "../common/test_tmpdir.h"
#include "common/error.h"
#include "common/h5_file.h"
#include "common/provenance.h"
#include "common/trajectory_io.h"
#include "compare/analysis.h"
#include "compare/run_compare.h"
#include "sim/sim_file.h"
#include "sim/simulator.h"

namespace dimer::compare {
namespace {

std::string WriteSim(const testing::TempDir& dir, const std::string& name, double ar, double cycles,
                     double fps = 2000) {
  sim::SimOptions o;
  o.ar = ar;
  o.cycles = cycles;
  o.fps = fps;
  const sim::SimResult r = sim::RunSimulation(o);
  sim::WriteSimFile(dir / name, false, o, r);
  return dir / name;
}

// A track file from a simulation's trajectory, with `edit` applied to it first.
std::string WriteTrack(const testing::TempDir& dir, const std::string& name, const std::string& sim_path,
                       const std::function<void(Trajectory*)>& edit) {
  H5Reader r(sim_path);
  Trajectory traj = ReadTrajectory(r);
  edit(&traj);
  H5Writer w(dir / name);
  WriteProvenance(w, "track", {{"fps", 2000.0}, {"diameter", 9.5e-3}, {"m_per_px", 2e-4}, {"row0", 200.0}});
  WriteTrajectory(w, traj);
  w.Close();
  return dir / name;
}

// RunCompare must throw InputError whose message contains every `needles`, and create nothing.
void ExpectRefused(CompareArgs args, const std::vector<std::string>& needles) {
  args.quiet = true;
  try {
    RunCompare(args);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    for (const std::string& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << msg;
  }
  EXPECT_FALSE(std::filesystem::exists(args.output));
  const auto parent = std::filesystem::path(args.output).parent_path();
  for (const auto& e : std::filesystem::directory_iterator(parent))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

class BadInput : public ::testing::Test {
 protected:
  testing::TempDir dir;
  CompareArgs Args(const std::string& input) {
    CompareArgs a;
    a.input = input;
    a.output = dir / "report";
    return a;
  }
};

TEST_F(BadInput, NotHdf5) {
  std::ofstream(dir / "notes.h5") << "not an HDF5 file\n";
  ExpectRefused(Args(dir / "notes.h5"), {"notes.h5"});
}

TEST_F(BadInput, WrongKind) {
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 4);
  CompareArgs a = Args(sim);
  a.output = dir / "first";
  a.quiet = true;
  RunCompare(a);
  ExpectRefused(Args(dir / "first/compare.h5"), {"compare.h5", "kind is 'compare'"});
}

TEST_F(BadInput, ShorterThanTwoPeriods) {
  ExpectRefused(Args(WriteSim(dir, "short.h5", 3.9, 1.5)), {"short.h5", "at least 2"});
}

TEST_F(BadInput, NoPlateAndNoFrequency) {
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 6);
  const std::string track = WriteTrack(dir, "noplate.h5", sim, [](Trajectory* t) {
    for (double& z : t->plate_z) z = NAN;
  });
  ExpectRefused(Args(track), {"noplate.h5", "--freq", "--gamma"});
  // With them the same track is analysed.
  CompareArgs a = Args(track);
  a.analysis.freq_hz = 25;
  a.analysis.gamma = 0.9;
  a.quiet = true;
  EXPECT_EQ(RunCompare(a), 0);
}

TEST_F(BadInput, SphereNaNThroughout) {
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 6);
  const std::string track = WriteTrack(dir, "lost.h5", sim, [](Trajectory* t) {
    for (auto& p : t->tip_right) p.setConstant(NAN);
  });
  ExpectRefused(Args(track), {"lost.h5", "right sphere is NaN in every frame"});
}

TEST_F(BadInput, SimulationOfAnotherDimerOrRate) {
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 6);
  CompareArgs a = Args(sim);
  a.sim_path = WriteSim(dir, "long.h5", 6.1, 6);
  ExpectRefused(a, {"different dimers", "A_r"});
  a.sim_path = WriteSim(dir, "slow.h5", 3.9, 6, 1000);
  ExpectRefused(a, {"different sample rates"});
}

TEST_F(BadInput, OptionsAreCheckedTogether) {
  CompareArgs a = Args(dir / "whatever.h5");
  a.analysis.phase_bins = 1;
  a.analysis.window_periods = 0;
  ExpectRefused(a, {"--phase-bins", "--mode-window"});
}

TEST_F(BadInput, GapsAreAnalysedAroundAndListed) {
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 40);
  // Frames 1000..1039 lost entirely (a skipped file run), and the left sphere lost in 2000..2009.
  const std::string track = WriteTrack(dir, "gappy.h5", sim, [](Trajectory* t) {
    for (size_t i = 2000; i < 2010; ++i) t->tip_left[i].setConstant(NAN);
    auto drop = [&](auto& v) { v.erase(v.begin() + 1000, v.begin() + 1040); };
    drop(t->t), drop(t->tip_left), drop(t->tip_right), drop(t->plate_z), drop(t->theta);
  });
  CompareArgs a = Args(track);
  a.quiet = true;
  ASSERT_EQ(RunCompare(a), 0);
  std::ifstream in(dir / "report/summary.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("1000"), std::string::npos);
  EXPECT_NE(md.find("2000"), std::string::npos);
  H5Reader r(dir / "report/compare.h5");
  EXPECT_EQ(r.AttrString("/", "settled_mode").value_or(""), "drift");
}

// A track of a lossy video (track's video_codec attributes) is analysed with a warning in the
// report; a lossless one and a folder of frames without.
TEST_F(BadInput, ATrackOfALossyVideoIsWarnedAbout) {
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 12);
  H5Reader r(sim);
  const Trajectory traj = ReadTrajectory(r);
  auto analysed = [&](const std::string& codec, int64_t lossless) {
    const std::string path = dir / ("video_" + codec + ".h5");
    {
      H5Writer w(path);
      WriteProvenance(w, "track", {{"fps", 2000.0}, {"diameter", 9.5e-3}, {"m_per_px", 2e-4}, {"row0", 200.0}});
      WriteTrajectory(w, traj);
      if (!codec.empty()) {
        w.SetAttr("/", "video_codec", codec);
        w.SetAttr("/", "video_codec_lossless", lossless);
      }
    }
    return Analyze(LoadSampledRun(path), {});
  };
  auto warned = [](const Analysis& a) {
    for (const std::string& w : a.warnings)
      if (w.find("lossy video (codec 'h264')") != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(warned(analysed("h264", 0)));
  EXPECT_FALSE(warned(analysed("FFV1", 1)));
  EXPECT_FALSE(warned(analysed("", 0)));  // a folder of frames
}

TEST_F(BadInput, ATrackWhoseEndIsLostIsJudgedWhereItIsGood) {
  // The dimer drifts out of the frame: the last 300 frames have no right sphere.
  const std::string sim = WriteSim(dir, "sim.h5", 3.9, 40);
  const std::string track = WriteTrack(dir, "leaves.h5", sim, [](Trajectory* t) {
    for (size_t i = t->size() - 300; i < t->size(); ++i) t->tip_right[i].setConstant(NAN);
  });
  CompareArgs a = Args(track);
  a.quiet = true;
  ASSERT_EQ(RunCompare(a), 0);
  H5Reader r(dir / "report/compare.h5");
  EXPECT_EQ(r.AttrString("/", "settled_mode").value_or(""), "drift");
  EXPECT_TRUE(std::isfinite(r.AttrDouble("/", "drift_speed").value_or(NAN)));
}

}  // namespace
}  // namespace dimer::compare
