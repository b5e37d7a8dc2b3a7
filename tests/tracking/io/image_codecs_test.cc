// OpenCV's codecs through libdimer_codecs.so (tracking/io/image_codecs.h) give exactly what the
// same OpenCV calls give linked directly; the BMP path never loads the library; and a library
// that cannot be loaded is one line naming the file.
#include "tracking/io/image_codecs.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/common/test_tmpdir.h"
#include "tracking/io/frame_source.h"

namespace dimer::tracking {
namespace image_codecs_test {
namespace {

constexpr int kGreyAnyDepth = cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE;

cv::Mat Random(int rows, int cols, int type, uint64_t seed) {
  cv::Mat m(rows, cols, type);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  return m;
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ImageCodecs, PngAndJpegFolderReadsAsDirectOpenCv) {
  dimer::testing::TempDir dir;
  const std::string f = dir / "frames";
  std::filesystem::create_directories(f);
  // 8- and 16-bit grey, colour (converted to grey by the decoder), and a lossy JPEG.
  ASSERT_TRUE(cv::imwrite(f + "/a_1.png", Random(24, 40, CV_8UC1, 1)));
  ASSERT_TRUE(cv::imwrite(f + "/a_2.png", Random(24, 40, CV_16UC1, 2)));
  ASSERT_TRUE(cv::imwrite(f + "/a_3.png", Random(24, 40, CV_8UC3, 3)));
  ASSERT_TRUE(cv::imwrite(f + "/a_4.jpg", Random(24, 40, CV_8UC3, 4)));
  const auto source = OpenFrameSource(f);
  ASSERT_EQ(source->size(), 4u);
  const char* names[] = {"a_1.png", "a_2.png", "a_3.png", "a_4.jpg"};
  for (size_t i = 0; i < 4; ++i) {
    const Frame frame = source->Read(i);
    EXPECT_EQ(frame.name, names[i]);
    EXPECT_EQ(frame.error, "") << names[i];
    const cv::Mat direct = cv::imread(f + "/" + names[i], kGreyAnyDepth);
    ASSERT_FALSE(direct.empty());
    EXPECT_TRUE(Same(frame.image, direct)) << names[i];
  }
  // The bare call too, on the bytes.
  const std::string png = Bytes(f + "/a_2.png");
  const std::vector<uchar> bytes(png.begin(), png.end());
  EXPECT_TRUE(Same(codecs::Decode(bytes, kGreyAnyDepth), cv::imdecode(bytes, kGreyAnyDepth)));
}

TEST(ImageCodecs, MultiPageTiffPagesAsDirectOpenCv) {
  dimer::testing::TempDir dir;
  const std::string path = dir / "stack.tif";
  const std::vector<cv::Mat> pages = {Random(8, 6, CV_16UC1, 5), Random(8, 6, CV_16UC1, 6),
                                      Random(8, 6, CV_16UC1, 7)};
  ASSERT_TRUE(cv::imwritemulti(path, pages));
  EXPECT_EQ(codecs::CountPages(path, kGreyAnyDepth), cv::imcount(path, kGreyAnyDepth));
  EXPECT_EQ(codecs::CountPages(path, kGreyAnyDepth), 3u);
  for (int p = 0; p < 3; ++p) {
    std::vector<cv::Mat> ours, direct;
    EXPECT_TRUE(codecs::ReadPages(path, &ours, p, 1, kGreyAnyDepth));
    ASSERT_TRUE(cv::imreadmulti(path, direct, p, 1, kGreyAnyDepth));
    ASSERT_EQ(ours.size(), 1u);
    EXPECT_TRUE(Same(ours[0], direct[0])) << p;
    EXPECT_TRUE(Same(ours[0], pages[p])) << p;
  }
}

TEST(ImageCodecs, VideoReadsAsDirectOpenCv) {
  dimer::testing::TempDir dir;
  const std::string video = dir / "clip.avi";
  {
    // Motion JPEG in AVI: OpenCV's built-in writer, no external codec needed.
    cv::VideoWriter w(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25.0, cv::Size(48, 32));
    if (!w.isOpened()) GTEST_SKIP() << "no MJPG/AVI writer in this OpenCV build";
    for (int i = 0; i < 5; ++i) w.write(Random(32, 48, CV_8UC3, 10 + i));
  }
  cv::VideoCapture direct(video);
  ASSERT_TRUE(direct.isOpened());
  codecs::VideoReader reader;
  ASSERT_TRUE(reader.Open(video));
  EXPECT_EQ(reader.FrameCount(), direct.get(cv::CAP_PROP_FRAME_COUNT));
  EXPECT_EQ(reader.FrameCount(), 5);
  EXPECT_EQ(reader.Fps(), direct.get(cv::CAP_PROP_FPS));
  // Through the frame source, as `track` reads it: colour decoded, then made grey.
  const auto source = OpenFrameSource(video);
  EXPECT_EQ(source->size(), 5u);
  Frame frame;
  int n = 0;
  cv::Mat bgr, grey, ours;
  while (direct.read(bgr)) {
    ASSERT_TRUE(reader.Read(&ours)) << n;
    EXPECT_TRUE(Same(ours, bgr)) << n;
    ASSERT_TRUE(source->Next(&frame)) << n;
    EXPECT_EQ(frame.error, "");
    EXPECT_EQ(frame.name, "clip.avi#" + std::to_string(n));
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    EXPECT_TRUE(Same(frame.image, grey)) << n;
    ++n;
  }
  EXPECT_EQ(n, 5);
  EXPECT_FALSE(reader.Read(&ours));
  EXPECT_FALSE(source->Next(&frame));
}

TEST(ImageCodecs, WritesTheSameFilesAsDirectOpenCv) {
  dimer::testing::TempDir dir;
  const cv::Mat img = Random(20, 30, CV_16UC1, 20);
  ASSERT_TRUE(codecs::Write(dir / "ours.png", img));
  ASSERT_TRUE(cv::imwrite(dir / "direct.png", img));
  EXPECT_EQ(Bytes(dir / "ours.png"), Bytes(dir / "direct.png"));
  EXPECT_FALSE(codecs::Write(dir / "no_such_folder/x.png", img));
  // The overlay's video.
  codecs::VideoWriter ours;
  cv::VideoWriter direct;
  ASSERT_TRUE(ours.Open(dir / "ours.avi", "MJPG", 10.0, cv::Size(30, 20)));
  ASSERT_TRUE(direct.open(dir / "direct.avi", cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0,
                          cv::Size(30, 20)));
  EXPECT_TRUE(ours.IsOpened());
  for (int i = 0; i < 3; ++i) {
    const cv::Mat frame = Random(20, 30, CV_8UC3, 30 + i);
    ours.Write(frame);
    direct.write(frame);
  }
  ours.Release();
  direct.release();
  EXPECT_FALSE(ours.IsOpened());
  const std::string bytes = Bytes(dir / "ours.avi");
  EXPECT_GT(bytes.size(), 1000u);
  EXPECT_EQ(bytes, Bytes(dir / "direct.avi"));
}

// The cases below need a process whose loader has not run yet: each runs in a child started
// afresh (death test style "threadsafe" re-executes the test binary up to the EXPECT_EXIT, so the
// child has its own TempDir, which it removes itself), which reports by exit code.
class ImageCodecsLoading : public ::testing::Test {
 protected:
  void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

bool Mapped(const std::string& file) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    if (line.find(file) != std::string::npos) return true;
  }
  return false;
}

// The start-time point of the library: the common inputs never load it.
TEST_F(ImageCodecsLoading, GreyBmpDoesNotLoadTheLibraryAndPngDoes) {
  dimer::testing::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir / "grey.bmp", Random(16, 12, CV_8UC1, 40)));
  ASSERT_TRUE(cv::imwrite(dir / "grey.png", Random(16, 12, CV_8UC1, 41)));
  EXPECT_EXIT(
      {
        const bool before = Mapped("libdimer_codecs.so");
        const Frame bmp = DecodeImageFile(dir / "grey.bmp", 0, "grey.bmp");
        const bool after_bmp = Mapped("libdimer_codecs.so");
        const Frame png = DecodeImageFile(dir / "grey.png", 0, "grey.png");
        const bool after_png = Mapped("libdimer_codecs.so");
        std::fprintf(stderr, "before %d, after bmp %d (%s), after png %d (%s)\n", before,
                     after_bmp, bmp.error.c_str(), after_png, png.error.c_str());
        const bool ok = !before && !after_bmp && after_png && bmp.error.empty() &&
                        png.error.empty();
        std::filesystem::remove_all(dir.path());
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "before 0, after bmp 0 \\(\\), after png 1 \\(\\)");
}

// What the child prints: the error's message, then "lines N" (how many lines it has).
void ReportError(const std::exception& e, const dimer::testing::TempDir& dir) {
  std::filesystem::remove_all(dir.path());
  const std::string what = e.what();
  std::fprintf(stderr, "message: %s\nlines %d\n", what.c_str(),
               1 + int(std::count(what.begin(), what.end(), '\n')));
  std::exit(3);
}

TEST_F(ImageCodecsLoading, MissingLibraryIsOneLineNamingTheFile) {
  dimer::testing::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir / "grey.png", Random(16, 12, CV_8UC1, 42)));
  const std::string missing = "/nonexistent/dimerlab/libdimer_codecs.so";
  EXPECT_EXIT(
      {
        setenv("DIMERLAB_CODECS", missing.c_str(), 1);
        if (codecs::LibraryPath() != missing) std::exit(1);
        try {
          // A PNG frame is not "unreadable": the installation is incomplete, which is an error
          // of the command, not a frame to skip.
          DecodeImageFile(dir / "grey.png", 0, "grey.png");
        } catch (const CodecsUnavailable& e) {
          ReportError(e, dir);
        }
        std::filesystem::remove_all(dir.path());
        std::exit(2);
      },
      ::testing::ExitedWithCode(3),
      "message: cannot load " + missing +
          ", OpenCV's image and video codecs \\(needed for PNG, JPEG, compressed TIFF, video, "
          "and writing images\\): cannot open shared object file: No such file or directory\n"
          "lines 1\n");
}

TEST_F(ImageCodecsLoading, NotALibraryIsOneLineNamingTheFile) {
  dimer::testing::TempDir dir;
  const std::string fake = dir / "libdimer_codecs.so";
  std::ofstream(fake) << "not a shared library\n";
  EXPECT_EXIT(
      {
        setenv("DIMERLAB_CODECS", fake.c_str(), 1);
        try {
          codecs::Require();
        } catch (const CodecsUnavailable& e) {
          ReportError(e, dir);
        }
        std::filesystem::remove_all(dir.path());
        std::exit(2);
      },
      ::testing::ExitedWithCode(3),
      "message: cannot load /.*/libdimer_codecs.so, OpenCV's .*\\): .*\nlines 1\n");
}

}  // namespace
}  // namespace image_codecs_test
}  // namespace dimer::tracking
