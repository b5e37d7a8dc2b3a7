// `dimerlab track run.cine` end to end (RunTrack, what the command calls): the same track as the
// same frames in a PNG folder; bit-identical for 1 and 2 threads; the header's frame rate,
// exposure and trigger time in the track file; --frames keeps the original frame indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "common/h5_file.h"
#include "tests/common/schema_check.h"
#include "tests/common/test_tmpdir.h"
#include "tests/common/warm_bayer.h"
#include "tests/tracking/synthetic.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/cine_writer.h"
#include "render/render.h"
#include "tracking/run_track.h"

namespace dimer::tracking {
namespace {

using dimer::testing::TempDir;

constexpr size_t kFrames = 24;

// Renders drift frames as PNG into dir/frames and writes the same frames as dir/run.cine.
void MakeInputs(const TempDir& dir) {
  testing::WriteSimFile(dir / "sim.h5", testing::DriftTrajectory(kFrames, 2000.0), 2000.0);
  RenderArgs a;
  a.input = dir / "sim.h5";
  a.output = dir / "frames";
  a.quiet = true;
  a.image.lighting = Lighting::kReflect;
  RunRender(a);
  auto folder = OpenFrameSource(dir / "frames");
  ASSERT_EQ(folder->size(), kFrames);
  std::vector<cv::Mat> frames;
  for (size_t i = 0; i < kFrames; ++i) frames.push_back(folder->Read(i).image);
  CineWriteOptions o;
  o.frame_rate = 2000;
  o.exposure_ns = 125000;
  o.trigger_seconds = 1763900000u;   // 2025-11-23T12:13:20Z
  o.trigger_fraction = 0x80000000u;  // + 0.5 s
  o.first_image_no = -100;
  WriteCine(dir / "run.cine", frames, o);
}

TrackArgs Args(const TempDir& dir, const std::string& input, const std::string& out, int threads) {
  TrackArgs t;
  t.input = dir / input;
  t.output = dir / out;
  t.quiet = true;
  t.sequence.chunk_frames = 7;  // several chunks, one not full
  t.sequence.threads = threads;
  return t;
}

template <typename T>
bool Bitwise(const std::vector<T>& a, const std::vector<T>& b) {  // NaN == NaN, -0 != +0
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void ExpectSameTrack(const std::string& a_path, const std::string& b_path) {
  H5Reader a(a_path), b(b_path);
  for (const char* name : {"/t", "/pixels/left", "/pixels/right", "/pixels/plate_row"}) {
    EXPECT_TRUE(Bitwise(a.ReadDoubles(name), b.ReadDoubles(name))) << name;
  }
  EXPECT_TRUE(Bitwise(a.ReadUint8("/found"), b.ReadUint8("/found")));
  EXPECT_TRUE(Bitwise(a.ReadInt64("/frame_index"), b.ReadInt64("/frame_index")));
  EXPECT_EQ(a.AttrDouble("/", "m_per_px"), b.AttrDouble("/", "m_per_px"));
  EXPECT_EQ(a.AttrDouble("/", "fps"), b.AttrDouble("/", "fps"));
}

TEST(TrackCine, SameTrackAsThePngFolderAndIdenticalForOneAndTwoThreads) {
  TempDir dir;
  MakeInputs(dir);
  TrackArgs png = Args(dir, "frames", "png.h5", 2);
  png.fps = 2000;
  RunTrack(png);
  RunTrack(Args(dir, "run.cine", "cine1.h5", 1));
  RunTrack(Args(dir, "run.cine", "cine2.h5", 2));
  ExpectSameTrack(dir / "png.h5", dir / "cine1.h5");
  ExpectSameTrack(dir / "cine1.h5", dir / "cine2.h5");

  H5Reader h(dir / "cine2.h5");
  EXPECT_EQ(h.ReadInt64("/frame_index").size(), kFrames);
  EXPECT_EQ(h.AttrDouble("/", "fps"), 2000.0);
  EXPECT_EQ(h.AttrString("/", "fps_source"), "header");
  EXPECT_EQ(h.AttrDouble("/", "exposure_ns"), 125000.0);
  EXPECT_EQ(h.AttrString("/", "trigger_time"), "2025-11-23T12:13:20.500000000Z");
  EXPECT_EQ(h.AttrDouble("/", "trigger_time_seconds"), 1763900000.0);
  EXPECT_EQ(h.AttrDouble("/", "trigger_time_fraction"), 2147483648.0);
  EXPECT_EQ(h.AttrDouble("/", "first_image_no"), -100.0);
  EXPECT_EQ(h.ReadStrings("/frame_files")[3], "run.cine#3");
  EXPECT_EQ(H5Reader(dir / "png.h5").AttrString("/", "fps_source"), "option");
  EXPECT_TRUE(dimer::testing::SchemaProblems(dir / "cine2.h5").empty());
  for (const auto& p : dimer::testing::SchemaProblems(dir / "cine2.h5")) ADD_FAILURE() << p;
}

TEST(TrackCine, GivenFpsWinsWithAWarning) {
  TempDir dir;
  MakeInputs(dir);
  TrackArgs t = Args(dir, "run.cine", "t.h5", 2);
  t.fps = 1000;
  std::string err;  // the lines `dimerlab track` prints
  t.on_diagnostic = [&](const Diagnostic& d) { err += FormatDiagnostic(d) + "\n"; };
  RunTrack(t);
  EXPECT_NE(err.find("dimerlab track: warning: " + t.input +
                     ": --fps 1000 differs from the .cine header's 2000 frames/s; using --fps 1000"),
            std::string::npos)
      << err;
  H5Reader h(t.output);
  EXPECT_EQ(h.AttrDouble("/", "fps"), 1000.0);
  EXPECT_EQ(h.AttrString("/", "fps_source"), "option");
  EXPECT_EQ(h.ReadDoubles("/t")[1], 1.0 / 1000);
}

TEST(TrackCine, FrameRangeKeepsTheOriginalIndicesForCineAndFolder) {
  TempDir dir;
  MakeInputs(dir);
  for (const std::string input : {"run.cine", "frames"}) {
    TrackArgs t = Args(dir, input, input + ".h5", 2);
    t.frames = "5:17";
    t.fps = 2000;
    RunTrack(t);
    H5Reader h(t.output);
    const auto index = h.ReadInt64("/frame_index");
    ASSERT_EQ(index.size(), 12u) << input;
    EXPECT_EQ(index.front(), 5);
    EXPECT_EQ(index.back(), 16);
    EXPECT_EQ(h.ReadDoubles("/t")[0], 5 / 2000.0);
    EXPECT_EQ(h.AttrString("/", "frames"), "5:17");
  }
}

// `dimerlab render --format cine`: the same frames as the PNG render, in one .cine whose header
// says the trajectory's rate and the blur's exposure.
TEST(TrackCine, RenderWritesTheSameFramesAsACine) {
  TempDir dir;
  testing::WriteSimFile(dir / "sim.h5", testing::DriftTrajectory(kFrames, 2000.0), 2000.0);
  RenderArgs a;
  a.input = dir / "sim.h5";
  a.quiet = true;
  a.output = dir / "png";
  RunRender(a);
  a.output = dir / "cine";
  a.format = FrameFormat::kCine;
  RunRender(a);
  auto png = OpenFrameSource(dir / "png");
  auto cine = OpenFrameSource(dir / "cine/frames.cine");
  ASSERT_EQ(cine->size(), kFrames);
  for (size_t i = 0; i < kFrames; ++i) {
    const cv::Mat p = png->Read(i).image, c = cine->Read(i).image;
    ASSERT_EQ(c.size(), p.size());
    EXPECT_EQ(cv::norm(p, c, cv::NORM_INF), 0) << i;
  }
  EXPECT_EQ(cine->recording().fps, 2000.0);
  EXPECT_EQ(cine->recording().exposure_ns, 125000);  // 0.25 of 500 us
}

// A 10-bit camera's packed .cine holds levels 0..1023 in 16-bit frames, and a colour camera's
// raw .cine a Bayer mosaic. The same rendered frames (x4 for 10 bits; seen through a mosaic
// under a warm lamp) must track as the 8-bit folder does. Before the levels were scaled to the
// 16-bit range (level_scale.h) the plate was lost on such 10-bit frames (POV-Ray: rows 4.9 px
// off, here 1.75 px).
TEST(TrackCine, TenBitPackedAndRawColourFilesTrackAsTheGreyFolder) {
  TempDir dir;
  MakeInputs(dir);
  auto folder = OpenFrameSource(dir / "frames");
  std::vector<cv::Mat> ten, mosaic;
  for (size_t i = 0; i < kFrames; ++i) {
    const cv::Mat f = folder->Read(i).image;
    cv::Mat t;
    f.convertTo(t, CV_16U, 4);
    ten.push_back(t);
    mosaic.push_back(dimer::testing::WarmBayerMosaic(f));  // a colour sensor under a warm lamp
  }
  CineWriteOptions o;
  o.pixels = CinePixels::k10BitPacked;
  WriteCine(dir / "ten.cine", ten, o);
  o.pixels = CinePixels::k8Bit;
  o.cfa = 3;
  WriteCine(dir / "raw.cine", mosaic, o);
  // The render's scale given, as a calibrated user would: the mosaic's blur then does not
  // move the rows through the radius measured on the outline.
  for (const auto& [in, out] : {std::pair<std::string, std::string>{"frames", "png.h5"},
                                {"ten.cine", "ten.h5"}, {"raw.cine", "raw.h5"}}) {
    TrackArgs a = Args(dir, in, out, 2);
    a.fps = 2000;
    a.m_per_px = 2e-4;
    RunTrack(a);
  }
  H5Reader p(dir / "png.h5");
  // Per frame within the 0.1 px of the 8-bit folder: 10 bits (0.05 px seen; 1.75 px
  // before the scaling); the warm-lit mosaic (0.07 px seen; 0.22 px on the plate row and the
  // rows resting on it when every pixel was filtered, the blur after the sensor clipped not being
  // the clipped plate edge's model).
  for (const auto& [name, tolerance] : {std::pair<std::string, double>{"ten.h5", 0.1},
                                        std::pair<std::string, double>{"raw.h5", 0.1}}) {
    H5Reader h(dir / name);
    EXPECT_EQ(h.ReadUint8("/found"), p.ReadUint8("/found")) << name;
    for (const char* set : {"/pixels/left", "/pixels/right", "/pixels/plate_row"}) {
      const auto a = h.ReadDoubles(set), b = p.ReadDoubles(set);
      ASSERT_EQ(a.size(), b.size());
      double worst = 0;
      for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
      EXPECT_LE(worst, tolerance) << name << " " << set;
    }
    for (const auto& problem : dimer::testing::SchemaProblems(dir / name)) {
      ADD_FAILURE() << name << ": " << problem;
    }
  }
  H5Reader t(dir / "ten.h5"), r(dir / "raw.h5");
  EXPECT_DOUBLE_EQ(t.AttrDouble("/", "level_scale").value_or(0), 65535.0 / 1023.0);
  EXPECT_EQ(t.AttrDouble("/", "level_scale_bits"), 10.0);
  EXPECT_EQ(t.AttrString("/", "cine_colour"), "grey");
  EXPECT_EQ(r.AttrDouble("/", "level_scale"), 1.0);  // 8-bit frames: nothing to scale
  EXPECT_EQ(r.AttrString("/", "cine_colour"), "mosaic");
  EXPECT_EQ(r.AttrDouble("/", "cine_cfa"), 3.0);
}

}  // namespace
}  // namespace dimer::tracking
