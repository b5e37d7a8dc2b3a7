// The POV-Ray footage generator: its truth is the scene geometry seen through the camera that
// POV-Ray really uses (markers rendered by POV-Ray land where Camera::Project says), the folder
// holds what docs/FORMATS.md promises, and the output is deterministic.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"
#include "tests/footage/povray_footage.h"

namespace dimer::footage {
namespace {

// Intensity centroid of `img` in the (2 half + 1)^2 window around `guess`.
Eigen::Vector2d Centroid(const cv::Mat& img, const Eigen::Vector2d& guess, int half) {
  double s = 0, sx = 0, sy = 0;
  const int c0 = int(std::lround(guess.x())), r0 = int(std::lround(guess.y()));
  for (int r = r0 - half; r <= r0 + half; ++r) {
    for (int c = c0 - half; c <= c0 + half; ++c) {
      const double v = img.at<float>(r, c);
      s += v;
      sx += v * c;
      sy += v * r;
    }
  }
  return {sx / s, sy / s};
}

const char* kGlow = "texture { pigment { rgb 1 } finish { ambient 0 diffuse 0 emission 1 } }";

// Glowing 2 mm marker spheres at known lab points, rendered by POV-Ray with heavy antialiasing:
// each centroid must be the projected centre to 0.02 px, for the default camera (axis low in
// the frame: top rows of a taller render), for a camera above the plate with its axis high
// in the frame (bottom rows), at several depths, and for the default camera turned 2 degrees
// about its axis (not level).
TEST(PovrayGenerator, MarkersLandWhereTheCameraModelProjectsThem) {
  dimer::testing::TempDir dir;
  Camera level;
  level.centre_x = 0.012;
  Camera high = level;
  high.distance = 0.5;
  high.elevation = 0.004;
  high.horizon_row = 60;
  high.centre_x = -0.003;
  Camera rolled = level;
  rolled.roll_deg = 2.0;
  int tested = 0;
  for (const Camera& cam : {level, high, rolled}) {
    const double pts[][3] = {{0.01234, 0, 0.00517}, {-0.03517, 0, 0.01233}, {0.05513, 0, -0.00711},
                             {0.05037, 0.01, 0.00213}, {-0.02029, -0.015, -0.01003}};
    std::string scene = "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n" +
                        cam.PovCamera() + "background { rgb 0 }\n";
    for (const auto& p : pts) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "sphere { <%.9g, %.9g, %.9g>, 1 %s }\n",
                    1000 * (p[0] - cam.centre_x), 1000 * p[2], 1000 * p[1], kGlow);
      scene += buf;
    }
    const cv::Mat img = RenderPov(scene, cam, 1, 5, dir / "work").at(0);
    for (const auto& p : pts) {
      const Eigen::Vector2d want = cam.Project(p[0], p[1], p[2]);
      ASSERT_GT(want.x(), 12);
      ASSERT_LT(want.x(), cam.width - 13);
      ASSERT_GT(want.y(), 12);
      ASSERT_LT(want.y(), cam.height - 13);
      const Eigen::Vector2d got = Centroid(img, want, 12);
      EXPECT_NEAR(got.x(), want.x(), 0.02) << "marker " << p[0] << "," << p[1] << "," << p[2];
      EXPECT_NEAR(got.y(), want.y(), 0.02) << "marker " << p[0] << "," << p[1] << "," << p[2];
      ++tested;
    }
  }
  EXPECT_EQ(tested, 15);
}

// The plate's top edge (camera level with it) is at Camera::PlateRow: a glowing plate's
// coverage summed down each column puts the edge within 0.02 px. POV-Ray's adaptive
// antialiasing quantises a straight edge's coverage to 1 / 2^depth (measured: rounded up), so
// this test traces to depth 6 (1/64 px); the footage's depth 4 leaves the plate edge up to
// 1/16 px high.
// With the camera turned about its axis the edge slopes, and the coverage of a column is the
// straight edge's row at the column's centre: Camera::PlateRowAt.
TEST(PovrayGenerator, PlateEdgeLandsOnThePlateRow) {
  dimer::testing::TempDir dir;
  Camera cam;
  cam.centre_x = 0;
  cam.horizon_row = 249;  // odd render height: the axis on a pixel centre
  for (double roll : {0.0, 1.5}) {
    cam.roll_deg = roll;
    const std::string scene = "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n" +
                              cam.PovCamera() + "background { rgb 0 }\nbox { <-2000, -30, -20>, "
                              "<2000, 0, 20> " + kGlow + " }\n";
    const cv::Mat img = RenderPov(scene, cam, 1, 6, dir / "work").at(0);
    for (int col : {20, 320, 600}) {
      const double covered = cv::sum(img.col(col))[0];
      const double edge = cam.height - 0.5 - covered;  // rows below the edge are covered
      EXPECT_NEAR(edge, cam.PlateRowAt(0.0, col), 0.02) << "column " << col << ", roll " << roll;
      if (roll == 0) {
        EXPECT_NEAR(edge, cam.PlateRow(0.0), 0.02) << "column " << col;
      }
    }
  }
}

// A stand-in for POV-Ray that fails its first `failures` runs with `message` (and, with `crash`,
// a segmentation fault rather than exit 1), then runs the real one; it counts its runs in
// `dir`/runs.
std::string FlakyPovray(const dimer::testing::TempDir& dir, int failures, const char* message,
                        bool crash = false) {
  const std::string path = dir / "flaky_povray.sh", runs = dir / "runs";
  std::ofstream(path) << "#!/bin/sh\nn=$(cat '" << runs << "' 2>/dev/null || echo 0)\n"
                      << "echo $((n + 1)) > '" << runs << "'\n"
                      << "if [ \"$n\" -lt " << failures << " ]; then echo '" << message << "' >&2; "
                      << (crash ? "kill -SEGV $$" : "exit 1") << "; fi\nexec povray \"$@\"\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  return path;
}

int Runs(const dimer::testing::TempDir& dir) {
  int n = 0;
  std::ifstream(dir / "runs") >> n;
  return n;
}

// POV-Ray 3.7 under load sometimes stops before it starts ("Timed out waiting for worker thread
// startup"; a long render died of it with the test suite running beside it) or crashes before
// it has written an image: that run is made again, twice at most. Any other failure is reported
// at once, naming POV-Ray's message.
TEST(PovrayGenerator, APovrayThatNeverStartedIsRunAgain) {
  Camera cam;
  cam.width = 48;
  cam.height = 24;
  cam.horizon_row = 12;
  cam.centre_x = 0;
  const std::string scene = "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n" +
                            cam.PovCamera() + "background { rgb 0.5 }\n";
  {
    dimer::testing::TempDir dir;
    const std::string povray =
        FlakyPovray(dir, 2, "Timed out waiting for worker thread startup");
    const cv::Mat img = RenderPov(scene, cam, 1, 0, dir / "work", povray).at(0);
    EXPECT_EQ(Runs(dir), 3);
    EXPECT_NEAR(cv::mean(img)[0], 0.5, 0.01);
  }
  {
    dimer::testing::TempDir dir;
    const std::string povray =
        FlakyPovray(dir, 3, "Timed out waiting for worker thread startup");
    EXPECT_THROW(RenderPov(scene, cam, 1, 0, dir / "work", povray), InputError);
    EXPECT_EQ(Runs(dir), 3) << "three runs in all";
  }
  {
    dimer::testing::TempDir dir;
    const std::string povray = FlakyPovray(dir, 1, "Parse Error: No matching } in object");
    try {
      RenderPov(scene, cam, 1, 0, dir / "work", povray);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Parse Error"), std::string::npos) << e.what();
    }
    EXPECT_EQ(Runs(dir), 1) << "a scene POV-Ray cannot read is not run again";
  }
  {  // A crash while parsing, before any image (one chunk of front_point_ar2_0 in a CI run).
    dimer::testing::TempDir dir;
    const std::string povray = FlakyPovray(dir, 2, "==== [Parsing...] ====", true);
    const cv::Mat img = RenderPov(scene, cam, 1, 0, dir / "work", povray).at(0);
    EXPECT_EQ(Runs(dir), 3);
    EXPECT_NEAR(cv::mean(img)[0], 0.5, 0.01);
  }
}

std::vector<std::vector<std::string>> ReadCsv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

FootageOptions Quick() {
  FootageOptions o;
  o.subframes = 2;
  o.aa_depth = 0;
  o.quiet = true;
  return o;
}

// truth.csv has the render layout and the projected pose of each frame; frames are 16-bit
// when asked, of the camera's size; the scene files are kept.
TEST(PovrayGenerator, FolderHoldsFramesTruthAndScenes) {
  dimer::testing::TempDir dir;
  FootageOptions o = Quick();
  o.bit_depth = 16;
  o.exposure_s = 0;
  const std::vector<Pose> poses = {{0.0, 0.001, 0.006, 0.1, 0.0002},
                                   {0.001, -0.002, 0.0052, -0.05, -0.0001},
                                   {0.002, 0.0005, 0.0049, 0.0, 0.0}};
  const Motion motion = PoseMotion(o.shape, poses);
  const FootageResult r = WriteFootage(motion, o, dir / "f");
  EXPECT_EQ(r.frames, 3u);
  const auto rows = ReadCsv(dir / "f/truth.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"frame", "file", "t", "left_col", "left_row",
                                                "right_col", "right_row", "plate_row"}));
  Camera cam = o.camera;
  cam.centre_x = (0.001 - 0.002 + 0.0005) / 3;  // automatic: the mean x of the dimer
  for (size_t i = 0; i < poses.size(); ++i) {
    const Instant s = FromPose(o.shape, poses[i].x, poses[i].z, poses[i].theta, poses[i].plate_z);
    const auto& row = rows[i + 1];
    EXPECT_NEAR(std::stod(row[3]), cam.Project(s.left).x(), 2e-6);
    EXPECT_NEAR(std::stod(row[4]), cam.Project(s.left).y(), 2e-6);
    EXPECT_NEAR(std::stod(row[5]), cam.Project(s.right).x(), 2e-6);
    EXPECT_NEAR(std::stod(row[6]), cam.Project(s.right).y(), 2e-6);
    EXPECT_NEAR(std::stod(row[7]), cam.PlateRow(poses[i].plate_z), 2e-6);
    const cv::Mat img = cv::imread(dir / ("f/" + row[1]), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(img.empty()) << row[1];
    EXPECT_EQ(img.type(), CV_16UC1);
    EXPECT_EQ(img.cols, 640);
    EXPECT_EQ(img.rows, 320);
    EXPECT_TRUE(std::filesystem::exists(dir / ("f/pov/frame_00000" + std::to_string(i) + ".pov")));
  }
  // Centre distance of the truth = (A_r - 1) d / m_per_px for a level dimer at depth 0.
  EXPECT_NEAR(std::stod(rows[3][5]) - std::stod(rows[3][3]), 2.9 * 9.5e-3 / 2e-4, 1e-5);
}

// Same inputs and seed: bit-identical frames whatever the number of POV-Ray processes; an
// up-to-date folder is reused, a changed scene is not.
TEST(PovrayGenerator, DeterministicAndCached) {
  dimer::testing::TempDir dir;
  FootageOptions o = Quick();
  const Motion motion = HopMotion(o.shape, 3, 2000.0);
  o.jobs = 1;
  const FootageResult a = WriteFootage(motion, o, dir / "a");
  o.jobs = 3;
  const FootageResult b = WriteFootage(motion, o, dir / "b");
  EXPECT_EQ(a.scene_hash, b.scene_hash);
  for (int i = 0; i < 3; ++i) {
    const std::string name = "/frame_00000" + std::to_string(i) + ".png";
    const cv::Mat x = cv::imread(dir / ("a" + name), cv::IMREAD_UNCHANGED);
    const cv::Mat y = cv::imread(dir / ("b" + name), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(x.empty());
    EXPECT_EQ(cv::norm(x, y, cv::NORM_INF), 0.0) << name;
  }
  o.reuse = true;
  EXPECT_TRUE(WriteFootage(motion, o, dir / "a").reused);
  o.seed = 2;
  EXPECT_FALSE(WriteFootage(motion, o, dir / "a").reused);
  o.reuse = false;
  EXPECT_THROW(WriteFootage(motion, o, dir / "a"), InputError);  // exists, no --force
}

// A trajectory's samples are the frames; slices between samples interpolate linearly; a NaN
// sample is refused naming the file.
TEST(PovrayGenerator, TrajectoryMotionInterpolatesSamples) {
  Trajectory traj;
  traj.Append(0.0, {0.001, 0.005}, {0.028, 0.006}, 0.0001, 0.03);
  traj.Append(0.0005, {0.002, 0.0052}, {0.029, 0.0064}, -0.0001, 0.04);
  const Motion m = TrajectoryMotion(traj, 0, "sim.h5");
  ASSERT_EQ(m.t.size(), 2u);
  const Instant mid = m.at(0.00025);
  EXPECT_NEAR(mid.left.x(), 0.0015, 1e-15);
  EXPECT_NEAR(mid.right.y(), 0.0062, 1e-15);
  EXPECT_NEAR(mid.plate_z, 0.0, 1e-15);
  EXPECT_EQ(TrajectoryMotion(traj, 1, "sim.h5").t.size(), 1u);
  traj.Append(0.001, {std::nan(""), 0.005}, {0.03, 0.006}, 0.0, 0.0);
  try {
    TrajectoryMotion(traj, 0, "sim.h5");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sim.h5: sample 2"), std::string::npos) << e.what();
  }
}

TEST(PovrayGenerator, BadInputNamesTheProblem) {
  dimer::testing::TempDir dir;
  std::ofstream(dir / "poses.csv") << "t,x,z,theta,plate_z\n0,0,0.005,0,0\n0.001,0,zero,0,0\n";
  try {
    ReadPoseCsv(dir / "poses.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("poses.csv: line 3"), std::string::npos) << e.what();
  }
  FootageOptions o = Quick();
  o.povray = dir / "no_povray_here";
  try {
    WriteFootage(HopMotion(o.shape, 1, 2000.0), o, dir / "f");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_povray_here"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "f"));
  o = Quick();
  o.bit_depth = 12;
  o.subframes = 0;
  try {
    o.Check();
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--bit-depth"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--subframes"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dimer::footage
