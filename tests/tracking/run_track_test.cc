#include "tracking/io/frame_source.h"
#include "tracking/run_track.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/h5_file.h"
#include "common/interrupt.h"
#include "common/trajectory_io.h"
#include "tests/common/test_tmpdir.h"
#include "tests/tracking/synthetic.h"
#include "render/render.h"
#include "tracking/io/cine_writer.h"

namespace dimer::tracking {
namespace {

// Renders `n` drift frames into dir/frames (PNG unless `format` says tiff).
RenderArgs RenderDrift(const dimer::testing::TempDir& dir, size_t n, Lighting l,
                       FrameFormat format = FrameFormat::kPng, int bit_depth = 8) {
  testing::WriteSimFile(dir / "sim.h5", testing::DriftTrajectory(n, 2000.0), 2000.0);
  RenderArgs a;
  a.input = dir / "sim.h5";
  a.output = dir / "frames";
  a.quiet = true;
  a.format = format;
  a.image.lighting = l;
  a.image.bit_depth = bit_depth;
  RunRender(a);
  return a;
}

TrackArgs Track(const dimer::testing::TempDir& dir) {
  TrackArgs t;
  t.input = dir / "frames";
  t.output = dir / "track.h5";
  t.quiet = true;
  t.m_per_px = 2e-4;
  t.sequence.chunk_frames = 8;
  return t;
}

// Truth pixel centres per frame from truth.csv.
std::vector<std::array<double, 5>> ReadTruth(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::array<double, 5>> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'f') continue;
    std::array<double, 5> r;
    int frame;
    char file[64];
    double t;
    std::sscanf(line.c_str(), "%d,%63[^,],%lf,%lf,%lf,%lf,%lf,%lf", &frame, file, &t, &r[0], &r[1],
                &r[2], &r[3], &r[4]);
    rows.push_back(r);
  }
  return rows;
}

TEST(RunTrack, RenderThenTrackMatchesTheTruthAndWritesTheFormat) {
  dimer::testing::TempDir dir;
  const RenderArgs r = RenderDrift(dir, 20, Lighting::kBacklit);
  TrackArgs t = Track(dir);
  RunTrack(t);
  H5Reader h(t.output);
  EXPECT_EQ(FileKind(h), "track");
  const Trajectory traj = ReadTrajectory(h);
  ASSERT_EQ(traj.size(), 20u);
  Dims dims;
  const auto left = h.ReadDoubles("/pixels/left", &dims);
  EXPECT_EQ(dims, (Dims{20, 2}));
  const auto right = h.ReadDoubles("/pixels/right");
  const auto plate = h.ReadDoubles("/pixels/plate_row");
  const auto found = h.ReadUint8("/found", &dims);
  EXPECT_EQ(dims, (Dims{20, 2}));
  EXPECT_EQ(h.ReadStrings("/frame_files")[3], "frame_000003.png");
  EXPECT_EQ(h.ReadInt64("/frame_index")[3], 3);
  // auto on our renderer's uniform silhouettes: discfit, whose noise the trial shows lower.
  EXPECT_EQ(h.AttrString("/", "method"), "discfit");
  EXPECT_EQ(h.AttrDouble("/", "fps"), 2000.0);
  const auto truth = ReadTruth(r.output + "/truth.csv");
  const double row0 = *h.AttrDouble("/", "row0");
  for (size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(found[2 * i] + found[2 * i + 1], 2);
    // sigma = 2, 47 px spheres, motion blur: 0.03 px is ~4x the measured scatter.
    EXPECT_NEAR(left[2 * i], truth[i][0], 0.03);
    EXPECT_NEAR(left[2 * i + 1], truth[i][1], 0.03);
    EXPECT_NEAR(right[2 * i], truth[i][2], 0.03);
    EXPECT_NEAR(right[2 * i + 1], truth[i][3], 0.03);
    EXPECT_NEAR(plate[i], truth[i][4], 0.03);
    // Metric = (col * m_per_px, (row0 - row) * m_per_px).
    EXPECT_NEAR(traj.tip_left[i].x(), left[2 * i] * 2e-4, 1e-12);
    EXPECT_NEAR(traj.tip_left[i].y(), (row0 - left[2 * i + 1]) * 2e-4, 1e-12);
    EXPECT_NEAR(traj.t[i], i / 2000.0, 1e-15);
  }
  EXPECT_THROW(RunTrack(t), InputError);  // refuses to overwrite without --force
}

TEST(RunTrack, BadFramesAreReportedSkippedAndTheRunContinues) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 12, Lighting::kDisc);
  const std::string f = dir / "frames";
  std::ofstream(f + "/frame_000003.png", std::ios::trunc).close();  // empty
  std::ofstream(f + "/frame_000004.png", std::ios::trunc) << "not an image at all";
  {  // truncated: the first half of a real PNG
    std::ifstream in(f + "/frame_000005.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(f + "/frame_000005.png", std::ios::binary | std::ios::trunc)
        << bytes.substr(0, bytes.size() / 2);
  }
  cv::imwrite(f + "/frame_000006.png", cv::Mat(100, 100, CV_8U, cv::Scalar(7)));  // wrong size
  {  // corrupt: valid header, garbage body
    std::ifstream in(f + "/frame_000007.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t i = 64; i < bytes.size(); i += 7) bytes[i] = char(bytes[i] ^ 0x5a);
    std::ofstream(f + "/frame_000007.png", std::ios::binary | std::ios::trunc) << bytes;
  }
  TrackArgs t = Track(dir);
  RunTrack(t);
  H5Reader h(t.output);
  const auto files = h.ReadStrings("/skipped/files");
  const auto reasons = h.ReadStrings("/skipped/reasons");
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files[0], "frame_000003.png");
  EXPECT_NE(reasons[0].find("empty"), std::string::npos);
  EXPECT_NE(reasons[1].find("not a decodable image"), std::string::npos);
  EXPECT_NE(reasons[2].find("not a decodable image"), std::string::npos);
  EXPECT_NE(reasons[3].find("size 100x100"), std::string::npos);
  EXPECT_NE(reasons[4].find("not a decodable image"), std::string::npos);
  const auto index = h.ReadInt64("/frame_index");
  EXPECT_EQ(index, (std::vector<int64_t>{0, 1, 2, 8, 9, 10, 11}));
}

// `--plate-m-per-px`: the plate edge seen nearer the camera than the dimer (a front edge) moves
// more px per metre; its motion is scaled to the dimer plane's by the ratio of the two scales,
// about the edge's median row, and nothing else moves (the spheres, row0).
TEST(RunTrack, PlateScaleMovesOnlyThePlateRowsAboutTheirMedian) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 24, Lighting::kBacklit);
  TrackArgs t = Track(dir);
  RunTrack(t);
  TrackArgs scaled = t;
  scaled.output = dir / "scaled.h5";
  scaled.plate_m_per_px = 0.5 * *t.m_per_px;
  RunTrack(scaled);
  H5Reader a(t.output), b(scaled.output);
  const auto plate = a.ReadDoubles("/pixels/plate_row");
  const auto plate_scaled = b.ReadDoubles("/pixels/plate_row");
  ASSERT_EQ(plate.size(), 24u);
  ASSERT_EQ(plate_scaled.size(), 24u);
  std::vector<double> sorted = plate;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[12];
  EXPECT_GT(sorted.back() - sorted.front(), 1.0) << "the plate must move for this test";
  for (size_t i = 0; i < plate.size(); ++i) {
    EXPECT_NEAR(plate_scaled[i], median + 0.5 * (plate[i] - median), 1e-9) << "frame " << i;
  }
  EXPECT_EQ(a.ReadDoubles("/pixels/left"), b.ReadDoubles("/pixels/left"));
  EXPECT_EQ(a.ReadDoubles("/pixels/right"), b.ReadDoubles("/pixels/right"));
  EXPECT_EQ(*a.AttrDouble("/", "row0"), *b.AttrDouble("/", "row0"));
  EXPECT_EQ(*b.AttrDouble("/", "plate_motion_scale"), 0.5);
  EXPECT_EQ(*b.AttrDouble("/", "plate_m_per_px"), 1e-4);
  EXPECT_EQ(*b.AttrDouble("/", "plate_shift_edge_ref"), median);
  EXPECT_EQ(b.AttrString("/", "plate_motion_scale_source"), "--plate-m-per-px");
  EXPECT_EQ(a.AttrString("/", "plate_motion_scale_source"), "none");
  EXPECT_EQ(*a.AttrDouble("/", "plate_motion_scale"), 1.0);
  // The ratio needs the dimer plane's scale before tracking: from --diameter it comes after.
  scaled.m_per_px.reset();
  scaled.force = true;
  try {
    RunTrack(scaled);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--plate-m-per-px needs --m-per-px"), std::string::npos)
        << e.what();
  }
}

// --ar (tracking/dimer_length_scale.h): the scale from the dimer's length, recorded as such,
// with the passes that chose the radius; given beside --m-per-px it only checks; an aspect ratio
// below two spheres touching is refused. The POV-Ray films where the spheres' size fails are in
// povray_footage_test.cc (PovrayDimerLength).
TEST(RunTrack, TheDimersLengthGivesTheScale) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 24, Lighting::kReflect);
  TrackArgs t = Track(dir);
  t.m_per_px.reset();
  t.ar = testing::kAspectRatio;
  RunTrack(t);
  H5Reader h(t.output);
  const double scale = *h.AttrDouble("/", "m_per_px");
  EXPECT_NEAR(scale / 2e-4, 1.0, 0.003) << "m/px from the length, against the renderer's";
  EXPECT_EQ(*h.AttrDouble("/", "m_per_px_given"), 2.0);
  EXPECT_EQ(*h.AttrDouble("/", "ar"), testing::kAspectRatio);
  const double length = *h.AttrDouble("/", "ar_length_px");
  // The scale is the length's, exactly: (A_r - 1) d / length.
  EXPECT_DOUBLE_EQ(scale, (testing::kAspectRatio - 1.0) * 9.5e-3 / length);
  EXPECT_GE(*h.AttrDouble("/", "ar_length_frames"), 20.0);
  EXPECT_GE(*h.AttrDouble("/", "ar_passes"), 2.0);
  EXPECT_EQ(*h.AttrDouble("/", "ar_converged"), 1.0);
  EXPECT_NEAR(*h.AttrDouble("/", "ar_radius_px"), 23.75, 0.06);
  // Beside --m-per-px the given scale stands; the length is still measured (the check).
  TrackArgs both = t;
  both.output = dir / "both.h5";
  both.m_per_px = 2e-4;
  both.ar = 5.0;  // wrong: a warning, not an error
  RunTrack(both);
  H5Reader b(both.output);
  EXPECT_EQ(*b.AttrDouble("/", "m_per_px"), 2e-4);
  EXPECT_EQ(*b.AttrDouble("/", "m_per_px_given"), 1.0);
  EXPECT_EQ(*b.AttrDouble("/", "ar_passes"), 0.0);
  EXPECT_NEAR(*b.AttrDouble("/", "ar_length_px"), length, 0.05);
  // Too few frames for a length: said at once, without guessing radii.
  TrackArgs few = t;
  few.output = dir / "few.h5";
  few.frames = "0:7";
  try {
    RunTrack(few);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("7 readable frames, and a length needs 10"),
              std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(few.output));
  // Spheres cannot overlap.
  TrackArgs overlap = t;
  overlap.output = dir / "overlap.h5";
  overlap.ar = 1.5;
  try {
    RunTrack(overlap);
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--ar must be >= 2"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(overlap.output));
}

TEST(RunTrack, UnusableInputsAreOneLineErrors) {
  dimer::testing::TempDir dir;
  TrackArgs t = Track(dir);
  t.input = dir / "nowhere";
  EXPECT_THROW(RunTrack(t), InputError);
  std::filesystem::create_directories(dir / "empty");
  t.input = dir / "empty";
  try {
    RunTrack(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no image files"), std::string::npos);
  }
  t.fps = -1;
  t.m_per_px = -2e-4;
  try {
    RunTrack(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--m-per-px"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("--fps"), std::string::npos);
  }
  // Names the options take are typed where the command line is read; a wrong one names it.
  try {
    ParseMethod("magic", "--method");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--method 'magic': expected auto, centroid, discfit or template");
  }
  EXPECT_THROW(ParsePolarity("grey"), InputError);
  EXPECT_EQ(ParsePolarity("dark"), Polarity::kDark);
}

// --lens: the calibration is read before any work (a bad file is a one-line error naming it,
// and no output is left), and the track file says which lens the frames were undistorted with.
TEST(RunTrack, TheLensCalibrationIsCheckedFirstAndRecorded) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 12, Lighting::kBacklit);
  TrackArgs t = Track(dir);
  t.lens = dir / "missing.yml";
  try {
    RunTrack(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir / "missing.yml"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(t.output));
  // An image size that is not one (it became INT_MAX and skipped the size check): refused in one
  // line naming the file and the field, before any work.
  std::ofstream(dir / "bad_width.yml")
      << "%YAML:1.0\n---\nimage_width: abc\nimage_height: 256\n"
         "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
         "   data: [ 2000., 0., 255.5, 0., 2000., 127.5, 0., 0., 1. ]\n"
         "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
         "   data: [ 0.1, 0., 0., 0., 0. ]\n";
  t.lens = dir / "bad_width.yml";
  try {
    RunTrack(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              dir / "bad_width.yml" + ": image_width is 'abc', not an integer in 1..65536");
  }
  EXPECT_FALSE(std::filesystem::exists(t.output));
  // Our renderer's frames are 512 x 256; a lens of 0.2 % at the corner, centred on the frame.
  std::ofstream(dir / "lens.yml")
      << "%YAML:1.0\n---\nimage_width: 512\nimage_height: 256\n"
         "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
         "   data: [ 2000., 0., 255.5, 0., 2000., 127.5, 0., 0., 1. ]\n"
         "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
         "   data: [ 0.1, 0., 0., 0., 0. ]\n";
  t.lens = dir / "lens.yml";
  RunTrack(t);
  H5Reader h(t.output);
  EXPECT_EQ(h.AttrString("/", "lens"), dir / "lens.yml");
  EXPECT_GT(*h.AttrDouble("/", "lens_max_shift_px"), 0.1);
  const auto k = h.ReadDoubles("/lens/camera_matrix");
  ASSERT_EQ(k.size(), 9u);
  EXPECT_EQ(k[0], 2000.0);
  EXPECT_EQ(k[2], 255.5);
  const auto d = h.ReadDoubles("/lens/distortion");
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d[0], 0.1);
  // Made for other frames: said, with both sizes.
  std::ofstream(dir / "other.yml")
      << "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
         "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
         "   data: [ 2000., 0., 319.5, 0., 2000., 239.5, 0., 0., 1. ]\n"
         "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
         "   data: [ 0.1, 0., 0., 0., 0. ]\n";
  t.lens = dir / "other.yml";
  t.force = true;
  try {
    RunTrack(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("calibrated for 640x480 images, the frames are 512x256"),
              std::string::npos)
        << e.what();
  }
}

TEST(RunTrack, SixteenBitTiffFramesAndMultiPageTiff) {
  dimer::testing::TempDir dir;
  const RenderArgs r = RenderDrift(dir, 6, Lighting::kBacklit, FrameFormat::kTiff, 16);
  TrackArgs t = Track(dir);
  RunTrack(t);
  H5Reader h(t.output);
  const auto found = h.ReadUint8("/found");
  EXPECT_EQ(std::count(found.begin(), found.end(), 1), 12);
  // The same frames as one multi-page TIFF.
  std::vector<cv::Mat> pages;
  for (int i = 0; i < 6; ++i) {
    char name[40];
    std::snprintf(name, sizeof name, "/frame_%06d.tif", i);
    pages.push_back(cv::imread(r.output + name, cv::IMREAD_ANYDEPTH));
  }
  ASSERT_TRUE(cv::imwritemulti(dir / "stack.tif", pages));
  t.input = dir / "stack.tif";
  t.output = dir / "stack.h5";
  RunTrack(t);
  H5Reader hs(t.output);
  EXPECT_EQ(hs.ReadStrings("/frame_files")[2], "stack.tif#2");
  EXPECT_EQ(hs.ReadDoubles("/pixels/left"), h.ReadDoubles("/pixels/left"));
}

TEST(TrackSequence, DeterministicAcrossThreadCountsAndPartialOnInterrupt) {
  RenderPlan plan;
  plan.map = {2e-4, 200, 300};
  plan.radius_px = 23.75;
  plan.rod_half_width_px = 3.75;
  const Trajectory traj = testing::DriftTrajectory(40, 2000.0);
  RenderOptions o;
  std::vector<cv::Mat> frames;
  for (size_t i = 0; i < traj.size(); ++i) frames.push_back(RenderFrame({plan.SceneAt(traj, traj.t[i])}, o, i));
  MemorySource source(frames);
  SequenceOptions opts;
  opts.chunk_frames = 7;
  opts.threads = 1;
  const SequenceResult one = TrackSequence(source, opts);
  opts.threads = 2;
  const SequenceResult two = TrackSequence(source, opts);
  ASSERT_EQ(one.frames.size(), 40u);
  ASSERT_EQ(two.frames.size(), 40u);
  for (size_t i = 0; i < 40; ++i) {
    EXPECT_EQ(one.frames[i].centre[0], two.frames[i].centre[0]);  // bit-identical
    EXPECT_EQ(one.frames[i].centre[1], two.frames[i].centre[1]);
  }
  // Ctrl-C after the first chunk: a complete prefix, flagged incomplete.
  const SequenceResult cut = TrackSequence(source, opts, [](size_t) { SetInterruptRequested(true); });
  SetInterruptRequested(false);
  EXPECT_FALSE(cut.complete);
  EXPECT_LT(cut.frames.size(), 40u);
  for (size_t i = 0; i < cut.frames.size(); ++i) EXPECT_EQ(cut.frames[i].index, i);
}

}  // namespace
}  // namespace dimer::tracking

namespace dimer::tracking {
namespace {

// Copies every PNG frame of `from` into `to` re-encoded as `ext` (".bmp", ".jpg").
void Reencode(const std::string& from, const std::string& to, const std::string& ext) {
  std::filesystem::create_directories(to);
  for (const auto& e : std::filesystem::directory_iterator(from)) {
    if (e.path().extension() != ".png") continue;
    const cv::Mat img = cv::imread(e.path().string(), cv::IMREAD_UNCHANGED);
    ASSERT_TRUE(cv::imwrite(to + "/" + e.path().stem().string() + ext, img));
  }
}

std::vector<double> Pixels(const std::string& track, const char* which) {
  return H5Reader(track).ReadDoubles(which);
}

TEST(RunTrack, BmpFramesGiveTheSameTrackAsPngAndJpegClose) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 10, Lighting::kBacklit);
  TrackArgs t = Track(dir);
  RunTrack(t);
  const auto png_left = Pixels(t.output, "/pixels/left");
  const auto png_right = Pixels(t.output, "/pixels/right");
  // BMP is lossless: bit-identical pixels, bit-identical track.
  Reencode(dir / "frames", dir / "bmp", ".bmp");
  t.input = dir / "bmp";
  t.output = dir / "bmp.h5";
  RunTrack(t);
  EXPECT_EQ(Pixels(t.output, "/pixels/left"), png_left);
  EXPECT_EQ(H5Reader(t.output).ReadStrings("/frame_files")[2], "frame_000002.bmp");
  // JPEG (OpenCV's default quality 95) is lossy: ringing of a few grey levels at the edges,
  // spread over ~150 edge pixels, moves a centre by far less than the 0.05 px reflect target;
  // bound 0.05 px against the PNG track.
  Reencode(dir / "frames", dir / "jpg", ".jpg");
  t.input = dir / "jpg";
  t.output = dir / "jpg.h5";
  RunTrack(t);
  const auto jl = Pixels(t.output, "/pixels/left"), jr = Pixels(t.output, "/pixels/right");
  ASSERT_EQ(jl.size(), png_left.size());
  double worst = 0;
  for (size_t i = 0; i < jl.size(); ++i) {
    worst = std::max({worst, std::abs(jl[i] - png_left[i]), std::abs(jr[i] - png_right[i])});
  }
  std::printf("[ stats    ] JPEG vs PNG: max centre difference %.4f px\n", worst);
  EXPECT_LE(worst, 0.05);
}

TEST(RunTrack, VideoFileIsTrackedInOrder) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 12, Lighting::kBacklit);
  TrackArgs t = Track(dir);
  RunTrack(t);
  const auto png_left = Pixels(t.output, "/pixels/left");
  // Motion JPEG in AVI: OpenCV's built-in writer, so no external codec is needed.
  const std::string video = dir / "clip.avi";
  {
    cv::VideoWriter writer(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25.0,
                           cv::Size(512, 256), false);
    if (!writer.isOpened()) GTEST_SKIP() << "no MJPG/AVI writer in this OpenCV build";
    for (int i = 0; i < 12; ++i) {
      char name[40];
      std::snprintf(name, sizeof name, "/frame_%06d.png", i);
      writer.write(cv::imread(std::string(dir / "frames") + name, cv::IMREAD_GRAYSCALE));
    }
  }
  t.input = video;
  t.output = dir / "video.h5";
  RunTrack(t);
  H5Reader h(t.output);
  EXPECT_EQ(h.ReadInt64("/frame_index"),
            (std::vector<int64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
  EXPECT_EQ(h.ReadStrings("/frame_files")[3], "clip.avi#3");
  // The codec, as the container declares it, and that it is lossy (track warns on stderr too);
  // a folder of frames has no codec.
  EXPECT_EQ(h.AttrString("/", "video_codec").value_or(""), "MJPG");
  EXPECT_EQ(h.AttrDouble("/", "video_codec_lossless").value_or(-1), 0);
  EXPECT_FALSE(H5Reader(dir / "track.h5").AttrString("/", "video_codec").has_value());
  const auto left = h.ReadDoubles("/pixels/left");
  ASSERT_EQ(left.size(), png_left.size());
  // MJPEG is lossy like JPEG (same bound and reason as above).
  for (size_t i = 0; i < left.size(); ++i) EXPECT_NEAR(left[i], png_left[i], 0.05) << i;
}

// A .cine's own per-frame time stamps give t and fps (a film saved with a decimation: the
// header's recording rate is 4 times theirs, and a one-line warning says so); a header rate of
// 0 without time stamps is an error unless --fps is given.
TEST(RunTrack, ACinesTimeStampsGiveTheFrameTimes) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 12, Lighting::kBacklit, FrameFormat::kCine);
  std::vector<cv::Mat> frames;
  {
    auto rendered = OpenFrameSource(dir / "frames/frames.cine");
    for (size_t i = 0; i < rendered->size(); ++i) frames.push_back(rendered->Read(i).image);
  }
  ASSERT_EQ(frames.size(), 12u);
  CineWriteOptions o;
  o.frame_rate = 2000;
  o.time_stamp_rate = 500;
  WriteCine(dir / "decimated.cine", frames, o);
  TrackArgs t = Track(dir);
  t.input = dir / "decimated.cine";
  std::vector<Diagnostic> said;
  t.on_diagnostic = [&](const Diagnostic& d) { said.push_back(d); };
  RunTrack(t);
  {
    H5Reader h(t.output);
    EXPECT_NEAR(*h.AttrDouble("/", "fps"), 500.0, 1e-4);  // stamps in 2^-32 s
    EXPECT_EQ(*h.AttrString("/", "fps_source"), "time_stamps");
    EXPECT_EQ(*h.AttrDouble("/", "cine_header_fps"), 2000.0);
    EXPECT_EQ(*h.AttrDouble("/", "cine_flip_v"), 0.0);
    const Trajectory traj = ReadTrajectory(h);
    ASSERT_EQ(traj.size(), 12u);
    for (size_t i = 0; i < 12; ++i) EXPECT_NEAR(traj.t[i], double(i) / 500, 1e-9) << i;
  }
  size_t fps_warnings = 0;
  for (const Diagnostic& d : said) {
    if (d.code != "fps") continue;
    ++fps_warnings;
    EXPECT_EQ(d.message.find('\n'), std::string::npos);
    EXPECT_NE(d.message.find("time stamps give 500 frames/s, the header says 2000"),
              std::string::npos) << d.message;
  }
  EXPECT_EQ(fps_warnings, 1u);

  o.frame_rate = 0;
  o.time_stamp_rate = 0;
  WriteCine(dir / "no_rate.cine", frames, o);
  t.input = dir / "no_rate.cine";
  t.output = dir / "no_rate.h5";
  try {
    RunTrack(t);
    FAIL() << "a header rate of 0 was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir / "no_rate.cine" + ": the .cine header's frame rate is 0 "
              "and the file has no time stamps; give the rate with --fps");
  }
  EXPECT_FALSE(std::filesystem::exists(t.output));
  t.fps = 1000;
  RunTrack(t);
  H5Reader h(t.output);
  EXPECT_EQ(*h.AttrString("/", "fps_source"), "option");
}

TEST(LosslessVideoCodec, KeepsEveryPixelOnlyForTheLosslessCodecs) {
  for (const char* c : {"FFV1", "ffv1", "HFYU", "Y800", "ULY0", "LAGS", "PNG "}) {
    EXPECT_TRUE(LosslessVideoCodec(c)) << c;
  }
  for (const char* c : {"h264", "avc1", "hevc", "MJPG", "mp4v", "XVID", "VP90", "", "????"}) {
    EXPECT_FALSE(LosslessVideoCodec(c)) << c;
  }
}

TEST(RunTrack, CtrlCLeavesAValidPartialFileAndNoTemporary) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 40, Lighting::kBacklit);
  TrackArgs t = Track(dir);  // chunks of 8 frames
  t.sequence.threads = 2;
  t.on_progress = [](size_t) { SetInterruptRequested(true); };  // Ctrl-C after the first chunk
  EXPECT_THROW(RunTrack(t), Interrupted);
  SetInterruptRequested(false);
  H5Reader h(t.output);  // under its final name
  EXPECT_EQ(h.AttrDouble("/", "complete"), std::optional<double>(0.0));
  const auto index = h.ReadInt64("/frame_index");
  ASSERT_FALSE(index.empty());
  EXPECT_LT(index.size(), 40u);
  for (size_t i = 0; i < index.size(); ++i) EXPECT_EQ(index[i], int64_t(i));  // a prefix
  EXPECT_EQ(ReadTrajectory(h).size(), index.size());
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
}

}  // namespace
}  // namespace dimer::tracking

namespace dimer::tracking {
namespace {

// Bitwise CRC-32 (the PNG/zlib polynomial): the test's own, to forge a chunk's CRC.
uint32_t Crc32(const std::string& bytes) {
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

// Decoder libraries print their own complaints on stderr (libpng: "libpng error: ..."). A PNG
// whose compressed data is garbage but whose CRCs are right passes the structure check and
// reaches libpng; during `track` its message is captured and becomes a dimerlab warning: every
// line on stderr is dimerlab's own.
TEST(RunTrack, LibraryMessagesBecomeDimerlabWarnings) {
  dimer::testing::TempDir dir;
  RenderDrift(dir, 6, Lighting::kBacklit);
  {
    const std::string path = dir / "frames/frame_000002.png";
    std::ifstream in(path, std::ios::binary);
    std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t idat = png.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    const uint32_t length = (uint32_t(uint8_t(png[idat - 4])) << 24) |
                            (uint32_t(uint8_t(png[idat - 3])) << 16) |
                            (uint32_t(uint8_t(png[idat - 2])) << 8) | uint8_t(png[idat - 1]);
    for (size_t i = idat + 4 + 2; i < idat + 4 + length; i += 3) png[i] = char(png[i] ^ 0x6b);
    const uint32_t crc = Crc32(png.substr(idat, 4 + length));
    for (int k = 0; k < 4; ++k) png[idat + 4 + length + k] = char(crc >> (24 - 8 * k));
    std::ofstream(path, std::ios::binary | std::ios::trunc) << png;
  }
  TrackArgs t = Track(dir);
  std::string err;  // the lines `dimerlab track` prints
  t.on_diagnostic = [&](const Diagnostic& d) { err += FormatDiagnostic(d) + "\n"; };
  ::testing::internal::CaptureStderr();
  RunTrack(t);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");  // nothing raw reaches stderr
  std::istringstream lines(err);
  int library_lines = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    EXPECT_EQ(line.rfind("dimerlab track: ", 0), 0u) << "not ours: " << line;
    library_lines += line.find("decoder message: libpng") != std::string::npos;
  }
  EXPECT_GE(library_lines, 1) << "stderr was:\n" << err;  // libpng spoke, through us
  EXPECT_NE(err.find("frame_000002.png: not a decodable image"), std::string::npos) << err;
}

// A film that shows the dimer but no plate (the plate below the frame): tracked, and said, since
// heights then count from the frame's bottom row.
TEST(RunTrack, APlateFoundInNoFrameIsSaid) {
  dimer::testing::TempDir dir;
  std::filesystem::create_directories(dir.path() / "frames");
  RenderOptions o;
  o.lighting = Lighting::kDisc;
  for (int i = 0; i < 12; ++i) {
    SceneGeometry s = testing::TiltedDimer(150 + 0.4 * i, 200, 23.75, 0.0, 3.75);
    s.plate_row = 400;  // below the 256 rows of the frame
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    ASSERT_TRUE(cv::imwrite(dir / ("frames/" + std::string(name)), RenderFrame({s}, o, uint64_t(i))));
  }
  TrackArgs t = Track(dir);
  t.method = Method::kCentroid;
  std::vector<Diagnostic> said;
  t.on_diagnostic = [&](const Diagnostic& d) { said.push_back(d); };
  RunTrack(t);
  size_t no_plate = 0;
  for (const Diagnostic& d : said) {
    if (d.code != "no_plate") continue;
    ++no_plate;
    EXPECT_NE(d.message.find("no plate edge found in any of the 12 frames"), std::string::npos)
        << d.message;
    EXPECT_TRUE(d.shown_when_quiet);
  }
  EXPECT_EQ(no_plate, 1u);
}

}  // namespace
}  // namespace dimer::tracking
