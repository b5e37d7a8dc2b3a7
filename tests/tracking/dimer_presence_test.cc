// A film with no dimer is refused: exit 1 (InputError), one line saying what was found instead,
// nothing written. A film whose dimer is in view in most frames is tracked.
#include "tracking/dimer_presence.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <functional>
#include <string>

#include "common/error.h"
#include "render/scene_renderer.h"
#include "tests/common/test_tmpdir.h"
#include "tests/tracking/synthetic.h"
#include "tracking/run_track.h"

namespace dimer::tracking {
namespace dimer_presence_test {
namespace {

constexpr int kFrames = 30;

// Writes kFrames PNG frames made by `frame_at(i)` into dir/frames.
void WriteFilm(const std::filesystem::path& dir, const std::function<cv::Mat(int)>& frame_at) {
  std::filesystem::create_directories(dir / "frames");
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    ASSERT_TRUE(cv::imwrite((dir / "frames" / name).string(), frame_at(i)));
  }
}

// The disc-lit dimer with its left sphere at column `col` (its right one 134 px further).
cv::Mat DimerAt(double col, int i) {
  RenderOptions o;
  o.lighting = Lighting::kDisc;
  return RenderFrame({testing::TiltedDimer(col, 200, 23.75, 0.0, 3.75)}, o, uint64_t(i));
}

// Runs `track` on dir/frames; the error's text, or "" when it was tracked.
std::string TrackError(const std::filesystem::path& dir) {
  TrackArgs t;
  t.input = dir / "frames";
  t.output = dir / "track.h5";
  t.quiet = true;
  t.m_per_px = 2e-4;
  t.method = Method::kCentroid;
  try {
    RunTrack(t);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void ExpectRefused(const std::filesystem::path& dir, const std::string& found) {
  const std::string e = TrackError(dir);
  EXPECT_NE(e.find("no dimer"), std::string::npos) << e;
  EXPECT_NE(e.find(found), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir / "track.h5"));
}

TEST(RunTrack, AFilmWithoutADimerIsRefusedAndNothingIsWritten) {
  {  // one sphere: the other out of the frame in every frame
    dimer::testing::TempDir dir;
    WriteFilm(dir.path(), [](int i) { return DimerAt(440 + 0.3 * i, i); });
    ExpectRefused(dir.path(), "one in 30");
  }
  {  // a bright elongated blob on black (a real camera's film of something else)
    dimer::testing::TempDir dir;
    WriteFilm(dir.path(), [](int i) {
      cv::Mat img(256, 512, CV_8U, cv::Scalar(10));
      cv::ellipse(img, {200 + i, 120}, {60, 18}, 20.0, 0, 360, cv::Scalar(230), cv::FILLED,
                  cv::LINE_AA);
      return img;
    });
    ExpectRefused(dir.path(), "of 30 frames");
  }
  {  // the plate alone: the dimer far out of the frame
    dimer::testing::TempDir dir;
    WriteFilm(dir.path(), [](int i) { return DimerAt(900, i); });
    ExpectRefused(dir.path(), "none in 30");
  }
}

// A real Phantom film of something else (pims' cine_legacy.cine, tests/data/cine: one bright
// blob on black, 97 frames) was tracked with exit 0 and "both spheres found in 3".
TEST(RunTrack, ARealCameraFilmWithoutADimerIsRefused) {
  dimer::testing::TempDir dir;
  TrackArgs t;
  t.input = std::string(DIMERLAB_TEST_DATA) + "/cine/cine_legacy.cine";
  t.output = dir / "track.h5";
  t.quiet = true;
  try {
    RunTrack(t);
    FAIL() << "tracked";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no dimer"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "track.h5"));
}

// The dimer walks out of the frame: in view in 18 of 30 frames it is tracked, in 12 refused.
TEST(RunTrack, ADimerInViewInMostFramesIsTracked) {
  for (int in_view : {18, 12}) {
    dimer::testing::TempDir dir;
    WriteFilm(dir.path(), [&](int i) { return DimerAt(i < in_view ? 150.0 : 440.0, i); });
    const std::string e = TrackError(dir.path());
    if (in_view > kFrames / 2) {
      EXPECT_EQ(e, "");
      EXPECT_TRUE(std::filesystem::exists(dir.path() / "track.h5"));
    } else {
      EXPECT_NE(e.find("in 12 of 30 frames"), std::string::npos) << e;
    }
  }
}

}  // namespace
}  // namespace dimer_presence_test
}  // namespace dimer::tracking
