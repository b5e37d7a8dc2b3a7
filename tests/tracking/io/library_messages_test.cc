// OpenCV's own stderr text (several lines, its call's name and source file) never reaches the
// user raw: a codec call inside CerrToString hands it over, and it becomes part of one line
// naming the file.
#include "tracking/io/library_messages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "tests/common/test_tmpdir.h"
#include "tracking/io/frame_source.h"

namespace dimer::tracking {
namespace library_messages_test {
namespace {

// OpenCV 4.6's text for a TIFF of 5 samples per pixel, as imcount prints it.
const char kImcount[] =
    "imcount_('stack.tif'): can't read header: OpenCV(4.6.0) "
    "./modules/imgcodecs/src/grfmt_tiff.cpp:152: error: (-2:Unspecified error) in function "
    "'int cv::TiffDecoder::normalizeChannelsNumber(int) const'\n"
    "> Unsupported number of channels:\n"
    ">     'channels >= 1 && channels <= 4'\n"
    "> where\n"
    ">     'channels' is 5\n\n";

TEST(OneLineLibraryMessage, OpenCvsTextBecomesWhatFailedAndWhy) {
  EXPECT_EQ(OneLineLibraryMessage(kImcount),
            "OpenCV: can't read header: Unsupported number of channels ('channels' is 5)");
  EXPECT_EQ(OneLineLibraryMessage("OpenCV(4.6.0) ./modules/core/src/matrix.cpp:1: error: "
                                  "(-215:Assertion failed) total() == 0 in function 'f'\n"),
            "OpenCV: total() == 0");
  EXPECT_EQ(OneLineLibraryMessage("libtiff: bad\nsecond line\n"), "libtiff: bad; second line");
  EXPECT_EQ(OneLineLibraryMessage(" \n"), "");
}

TEST(CerrToString, TakesThisThreadsCerrOnly) {
  std::string mine, theirs;
  {
    CerrToString capture(&mine);
    std::cerr << "kept" << std::endl;
    std::thread other([&] {
      CerrToString other_capture(&theirs);
      std::cerr << "other thread";
    });
    other.join();
  }
  EXPECT_EQ(mine, "kept\n");
  EXPECT_EQ(theirs, "other thread");
  ::testing::internal::CaptureStderr();
  std::cerr << "after" << std::flush;
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "after");
}

// An uncompressed 8-bit TIFF of `pages` pages of w x h, page k with samples[k] samples a pixel.
std::vector<uint8_t> Tiff(int w, int h, const std::vector<int>& samples) {
  std::vector<uint8_t> b = {'I', 'I', 42, 0, 8, 0, 0, 0};
  auto put = [&](size_t at, uint32_t v, int n) {
    if (b.size() < at + n) b.resize(at + n);
    for (int k = 0; k < n; ++k) b[at + k] = uint8_t(v >> (8 * k));
  };
  constexpr int kEntries = 9, kIfd = 2 + 12 * kEntries + 4;
  size_t at = 8;
  for (size_t p = 0; p < samples.size(); ++p) {
    const int spp = samples[p];
    const size_t bps = at + kIfd, data = bps + 2 * 8, end = data + size_t(w * h * spp);
    const uint32_t next = p + 1 < samples.size() ? uint32_t(end + end % 2) : 0;
    // BitsPerSample: in the entry itself for up to 2 samples, else at `bps`.
    const uint32_t bits = spp <= 2 ? 8u | 8u << 16 : uint32_t(bps);
    const uint32_t e[kEntries][4] = {{256, 3, 1, uint32_t(w)},
                                     {257, 3, 1, uint32_t(h)},
                                     {258, 3, uint32_t(spp), bits},
                                     {259, 3, 1, 1},
                                     {262, 3, 1, 1},
                                     {273, 4, 1, uint32_t(data)},
                                     {277, 3, 1, uint32_t(spp)},
                                     {278, 3, 1, uint32_t(h)},
                                     {279, 4, 1, uint32_t(w * h * spp)}};
    put(at, kEntries, 2);
    for (int i = 0; i < kEntries; ++i) {
      put(at + 2 + 12 * i, e[i][0], 2);
      put(at + 4 + 12 * i, e[i][1], 2);
      put(at + 6 + 12 * i, e[i][2], 4);
      put(at + 10 + 12 * i, e[i][3], 4);
    }
    put(at + 2 + 12 * kEntries, next, 4);
    for (int s = 0; s < 8; ++s) put(bps + 2 * s, 8, 2);
    for (size_t i = data; i < end; ++i) put(i, uint32_t(i * 7 % 251), 1);
    at = next;
  }
  return b;
}

void Save(const std::string& path, const std::vector<uint8_t>& b, size_t n) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()),
                                              std::streamsize(n));
}

bool OneLine(const std::string& s) {
  return !s.empty() && s.find('\n') == s.size() - 1;
}

TEST(LibraryMessages, BadTiffsGiveOneLineNamingTheFile) {
  dimer::testing::TempDir dir;
  // A stack whose last page has 5 samples a pixel: OpenCV cannot count its pages.
  const std::vector<uint8_t> stack = Tiff(8, 4, {1, 1, 5});
  Save(dir / "stack.tif", stack, stack.size());
  ::testing::internal::CaptureStderr();
  auto src = OpenFrameSource(dir / "stack.tif");
  std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "");  // the library prints nothing: the source says it (FrameSource::warnings)
  ASSERT_EQ(src->warnings().size(), 1u);
  EXPECT_TRUE(OneLine(src->warnings()[0] + "\n")) << src->warnings()[0];
  EXPECT_EQ(src->warnings()[0], dir / "stack.tif" +
                                    ": cannot count its pages (OpenCV: Unsupported number of "
                                    "channels ('channels' is 5)); read as one image");
  // A truncated stack, a 2-channel and a 5-channel image: each frame's reason is one line.
  std::filesystem::create_directories(dir / "frames");
  const std::vector<uint8_t> three = Tiff(8, 4, {1, 1, 1});
  Save(dir / "frames/a_truncated.tif", three, three.size() - 40);
  const std::vector<uint8_t> two = Tiff(8, 4, {2});
  Save(dir / "frames/b_two.tif", two, two.size());
  const std::vector<uint8_t> five = Tiff(8, 4, {5});
  Save(dir / "frames/c_five.tif", five, five.size());
  ::testing::internal::CaptureStderr();
  auto folder = OpenFrameSource(dir / "frames");
  std::vector<Frame> frames;
  for (size_t i = 0; i < folder->size(); ++i) frames.push_back(folder->Read(i));
  err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "");  // nothing raw: said in the frames' reasons
  for (const Frame& f : frames) {
    EXPECT_EQ(f.error.find('\n'), std::string::npos) << f.name << ": " << f.error;
  }
  ASSERT_EQ(frames.size(), 5u);  // the truncated stack's 3 pages, then the two images
  EXPECT_EQ(frames[2].name, "a_truncated.tif#2");
  EXPECT_EQ(frames[2].error.rfind("not a decodable image: OpenCV: can't read data: ", 0), 0u)
      << frames[2].error;
  const Frame& last = frames.back();
  EXPECT_EQ(last.name, "c_five.tif");
  EXPECT_EQ(last.error, "not a decodable image: OpenCV: can't read header: Unsupported number of "
                        "channels ('channels' is 5)");
  // The 2-channel image (grey and alpha) is read as grey, without a word from OpenCV.
  EXPECT_EQ(frames[frames.size() - 2].name, "b_two.tif");
  EXPECT_EQ(frames[frames.size() - 2].error, "");
  EXPECT_EQ(frames[frames.size() - 2].image.channels(), 1);
}

}  // namespace
}  // namespace library_messages_test
}  // namespace dimer::tracking
