#include "render/render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/h5_file.h"
#include "common/provenance.h"
#include "common/trajectory_io.h"
#include "tests/common/test_tmpdir.h"
#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace {

RenderArgs SmallRender(const dimer::testing::TempDir& dir) {
  RenderArgs a;
  a.input = dir / "sim.h5";
  a.output = dir / "frames";
  a.quiet = true;
  a.image.lighting = Lighting::kBacklit;
  return a;
}

// A sim file of a tilted plate (tilt_deg 3): drawn in the plate's frame (the renderer's plate
// is level), so a dimer lying on the plate lies level on the drawn plate, R above it.
TEST(RunRender, ATiltedPlatesSimIsDrawnInThePlatesFrame) {
  dimer::testing::TempDir dir;
  const double a = 3.0 * M_PI / 180, c = std::cos(a), s = std::sin(a), r = 0.5 * testing::kDiameterM;
  const double half = 13.8e-3;
  Trajectory lab;
  for (int i = 0; i < 3; ++i) {
    const double along = 0.002 * i, zp = 1e-4 * i;  // drifting up the plate, which rises
    const Eigen::Vector2d t(c, s), n(-s, c), cm = along * t + (zp + r) * n;
    lab.Append(i / 2000.0, cm - half * t, cm + half * t, (zp + cm.x() * s) / c, a);
  }
  {
    H5Writer w(dir / "sim.h5");
    WriteProvenance(w, "sim", {{"fps", 2000.0}, {"freq", 25.0}, {"diameter", testing::kDiameterM},
                               {"tilt_deg", 3.0}});
    WriteTrajectory(w, lab);
  }
  RenderArgs args = SmallRender(dir);
  RunRender(args);
  std::ifstream truth(args.output + "/truth.csv");
  std::string line;
  for (int k = 0; k < 3; ++k) std::getline(truth, line);  // comments and column names
  double m = 2e-4;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::getline(truth, line));
    double t, lc, lr, rc, rr, pr;
    int frame;
    char file[64];
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%63[^,],%lf,%lf,%lf,%lf,%lf,%lf", &frame, file, &t, &lc, &lr,
                          &rc, &rr, &pr), 8);
    EXPECT_NEAR(lr, rr, 1e-6) << i;                      // level on the drawn plate
    EXPECT_NEAR(pr - lr, r / m, 1e-6) << i;              // R above it
    EXPECT_NEAR(rc - lc, 2 * half / m, 1e-6) << i;       // the full length along the plate
  }
  std::ifstream json(args.output + "/render.json");
  const std::string j((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(j.find("\"frame\": \"plate\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"tilt_deg\": 3,"), std::string::npos) << j;
}

TEST(RunRender, WritesFramesTruthAndMapping) {
  dimer::testing::TempDir dir;
  const Trajectory traj = testing::DriftTrajectory(6, 2000.0);
  testing::WriteSimFile(dir / "sim.h5", traj, 2000.0);
  RenderArgs a = SmallRender(dir);
  RunRender(a);
  for (int i = 0; i < 6; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06d.png", i);
    EXPECT_TRUE(std::filesystem::exists(a.output + name)) << name;
  }
  EXPECT_TRUE(std::filesystem::exists(a.output + "/render.json"));
  std::ifstream truth(a.output + "/truth.csv");
  std::string line, header;
  std::getline(truth, line);
  std::getline(truth, header);  // mapping comment
  double m = 0, row0 = 0, col_offset = 0;
  ASSERT_EQ(std::sscanf(header.c_str(), "# m_per_px=%lf row0=%lf col_offset=%lf", &m, &row0,
                        &col_offset), 3);
  std::getline(truth, line);  // column names
  std::getline(truth, line);  // frame 0
  double t, lc, lr, rc, rr, pr;
  int frame;
  char file[64];
  ASSERT_EQ(std::sscanf(line.c_str(), "%d,%63[^,],%lf,%lf,%lf,%lf,%lf,%lf", &frame, file, &t, &lc,
                        &lr, &rc, &rr, &pr), 8);
  EXPECT_NEAR(lc, traj.tip_left[0].x() / m + col_offset, 1e-5);  // col = x / m_per_px + offset
  EXPECT_NEAR(lr, row0 - traj.tip_left[0].y() / m, 1e-5);         // row = row0 - z / m_per_px
  EXPECT_NEAR(pr, row0 - traj.plate_z[0] / m, 1e-5);
  EXPECT_NEAR(m, 2e-4, 0);
  EXPECT_NEAR(row0, 0.78 * 256, 1e-9);
  // An existing output is refused without --force and replaced with it.
  EXPECT_THROW(RunRender(a), InputError);
  a.force = true;
  EXPECT_NO_THROW(RunRender(a));
}

TEST(RunRender, BadInputsNameTheProblem) {
  dimer::testing::TempDir dir;
  RenderArgs a = SmallRender(dir);
  auto message = [&](const RenderArgs& args) -> std::string {
    try {
      RunRender(args);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message(a).find("sim.h5"), std::string::npos);  // missing file
  testing::WriteSimFile(dir / "sim.h5", testing::DriftTrajectory(3, 2000.0), 2000.0, false);
  EXPECT_NE(message(a).find("diameter"), std::string::npos);  // no diameter attribute
  Trajectory nan_traj = testing::DriftTrajectory(3, 2000.0);
  nan_traj.tip_left[1].x() = std::nan("");
  testing::WriteSimFile(dir / "sim.h5", nan_traj, 2000.0);
  EXPECT_NE(message(a).find("sample 1"), std::string::npos);
  RenderArgs bad = a;
  bad.exposure = 2;
  const std::string m = message(bad);
  EXPECT_NE(m.find("--exposure"), std::string::npos);
  EXPECT_THROW(ParseFrameFormat("gif"), UsageError);  // typed where the command line is read
  EXPECT_FALSE(std::filesystem::exists(a.output));  // nothing left behind
}

}  // namespace
}  // namespace dimer::tracking
