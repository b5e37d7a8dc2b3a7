// A film with no dimer is refused: exit 1 (InputError), one line saying what was found instead,
// nothing written. A film whose dimer leaves the view for good is tracked where it is in view.
#include "tracking/dimer_presence.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "common/error.h"
#include "common/h5_file.h"
#include "render/scene_renderer.h"
#include "tests/common/test_tmpdir.h"
#include "tests/tracking/synthetic.h"
#include "tracking/run_track.h"

namespace dimer::tracking {
namespace dimer_presence_test {
namespace {

constexpr int kFrames = 30;

// Writes `frames` PNG frames made by `frame_at(i)` into dir/frames.
void WriteFilm(const std::filesystem::path& dir, const std::function<cv::Mat(int)>& frame_at,
               int frames = kFrames) {
  std::filesystem::create_directories(dir / "frames");
  for (int i = 0; i < frames; ++i) {
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

// A bright elongated blob on black, moving right a pixel a frame.
cv::Mat BlobAt(int i) {
  cv::Mat img(256, 512, CV_8U, cv::Scalar(10));
  cv::ellipse(img, {200 + i, 120}, {60, 18}, 20.0, 0, 360, cv::Scalar(230), cv::FILLED,
              cv::LINE_AA);
  return img;
}

// Runs `track` on dir/frames; the error's text, or "" when it was tracked. `notes` (if given)
// collects the notes and warnings.
std::string TrackError(const std::filesystem::path& dir, std::string* notes = nullptr) {
  TrackArgs t;
  t.input = dir / "frames";
  t.output = dir / "track.h5";
  t.quiet = true;
  t.m_per_px = 2e-4;
  t.method = Method::kCentroid;
  if (notes) t.on_diagnostic = [notes](const Diagnostic& d) { *notes += d.message + "\n"; };
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
  EXPECT_EQ(e.find("without --m-per-px"), std::string::npos) << "the scale was given: " << e;
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
    WriteFilm(dir.path(), BlobAt);
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
    // Tracked without the scale: the line says the spheres were sized by the silhouettes.
    EXPECT_NE(std::string(e.what()).find("without --m-per-px"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "track.h5"));
}

// A long drift run's dimer leaves the field of view, one sphere after the other, often for
// good. Sliding right 5 px a frame over 60 frames (512 px wide), its right sphere leaves by the
// edge over frames 10-19 and the left one over 38-47; nothing is in view after. Both spheres
// are in view in fewer than half of the frames, yet the film is tracked (a note says so): each
// sphere found under its own name while whole in view, neither once out of it. Where 12 frames
// of the dimer are followed by a sphere alone whose partner's place is in view (not a dimer
// leaving), those 12 are not most of the frames that show anything: refused.
TEST(RunTrack, ADimerThatLeavesTheViewIsTrackedWhereItIsInView) {
  constexpr int kSlide = 60;
  constexpr double kRadius = 23.75, kStart = 300, kStep = 5;
  const double length = 2.0 * (testing::kAspectRatio - 1.0) * kRadius;
  {
    dimer::testing::TempDir dir;
    WriteFilm(dir.path(), [&](int i) { return DimerAt(kStart + kStep * i, i); }, kSlide);
    std::string notes;
    ASSERT_EQ(TrackError(dir.path(), &notes), "");
    std::printf("[ stats    ] %s", notes.c_str());
    EXPECT_NE(notes.find("the dimer is in view in "), std::string::npos) << notes;
    EXPECT_NE(notes.find(" of 60 frames"), std::string::npos) << notes;
    H5Reader track((dir.path() / "track.h5").string());
    const std::vector<double> found = track.ReadDoubles("found");
    const std::vector<double> left = track.ReadDoubles("pixels/left");
    const std::vector<double> right = track.ReadDoubles("pixels/right");
    ASSERT_EQ(found.size(), size_t(2 * kSlide));
    for (int i = 0; i < kSlide; ++i) {
      const std::array<double, 2> col{kStart + kStep * i, kStart + kStep * i + length};
      const std::array<double, 2> tracked{left[size_t(2 * i)], right[size_t(2 * i)]};
      for (size_t k = 0; k < 2; ++k) {
        const double f = found[size_t(2 * i) + k];
        if (col[k] + kRadius < 511) {  // whole in view
          EXPECT_NE(f, 0) << k << " frame " << i;
        }
        if (col[k] - kRadius > 512) {  // out of view
          EXPECT_EQ(f, 0) << k << " frame " << i;
        }
        if (f != 0) {
          EXPECT_NEAR(tracked[k], col[k], 2.0) << k << " frame " << i;
        }
      }
    }
  }
  {
    dimer::testing::TempDir dir;
    WriteFilm(dir.path(), [&](int i) {
      cv::Mat frame = DimerAt(150.0, i);
      if (i >= 12) {  // the right sphere painted out: the plate where it stood
        const cv::Rect right(int(150.0 + length - kRadius - 6), 0, int(2 * kRadius + 12),
                             frame.rows);
        DimerAt(900.0, i)(right).copyTo(frame(right));
      }
      return frame;
    });
    ExpectRefused(dir.path(), "in 12 of 30 frames (needed: half of the 30 that show anything");
  }
}

}  // namespace
}  // namespace dimer_presence_test
}  // namespace dimer::tracking
