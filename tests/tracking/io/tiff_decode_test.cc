// The direct plain-TIFF decoder gives exactly cv::imdecode's frame, and declines (leaving the
// file to OpenCV) everything it does not cover.
#include "tracking/io/tiff_decode.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <random>

#include "tests/tracking/io/decoded_image.h"
#include "tracking/io/frame_source.h"

// GCC says AddressSanitizer with __SANITIZE_ADDRESS__, clang with __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define DIMERLAB_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DIMERLAB_TEST_UNDER_ASAN 1
#endif
#endif
#ifndef DIMERLAB_TEST_UNDER_ASAN
#define DIMERLAB_TEST_UNDER_ASAN 0
#endif

namespace dimer::tracking {
namespace {

std::vector<uint8_t> Encode(const cv::Mat& m, int compression) {
  std::vector<uint8_t> b;
  EXPECT_TRUE(cv::imencode(".tif", m, b, {cv::IMWRITE_TIFF_COMPRESSION, compression}));
  return b;
}

TEST(PlainTiff, SameAsOpenCvFor8And16BitAndManyStrips) {
  // 512x256 8-bit: OpenCV writes several strips; 37 wide: odd rows; 16-bit: two bytes a sample.
  for (const cv::Mat& m : {Random(512, 256, CV_8UC1, 1), Random(37, 11, CV_8UC1, 2),
                           Random(64, 300, CV_16UC1, 3), Random(5, 3, CV_16UC1, 4)}) {
    const auto b = Encode(m, 1);
    cv::Mat out;
    ASSERT_TRUE(DecodePlainTiff(b.data(), b.size(), &out)) << m.size();
    EXPECT_TRUE(Same(out, m)) << m.size();
    EXPECT_TRUE(Same(out, OpenCvGrey(b))) << m.size();
  }
}

TEST(PlainTiff, DeclinesCompressedColourAndDamaged) {
  cv::Mat out;
  const auto lzw = Encode(Random(40, 20, CV_8UC1, 5), 5);
  EXPECT_FALSE(DecodePlainTiff(lzw.data(), lzw.size(), &out));
  const auto colour = Encode(Random(40, 20, CV_8UC3, 6), 1);
  EXPECT_FALSE(DecodePlainTiff(colour.data(), colour.size(), &out));
  auto truncated = Encode(Random(40, 20, CV_8UC1, 7), 1);
  truncated.resize(truncated.size() / 2);
  EXPECT_FALSE(DecodePlainTiff(truncated.data(), truncated.size(), &out));
  EXPECT_TRUE(out.empty());
  // The frame reader then decodes the LZW file through OpenCV, same pixels.
  const std::string path = ::testing::TempDir() + "/lzw.tif";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(lzw.data()), lzw.size());
  const Frame f = DecodeImageFile(path, 0, "lzw.tif");
  EXPECT_TRUE(f.error.empty());
  EXPECT_TRUE(Same(f.image, OpenCvGrey(lzw)));
}

TEST(PlainTiff, PageCountHint) {
  const std::string one = ::testing::TempDir() + "/one.tif", two = ::testing::TempDir() + "/two.tif";
  cv::imwrite(one, Random(8, 4, CV_8UC1, 8));
  cv::imwritemulti(two, std::vector<cv::Mat>{Random(8, 4, CV_8UC1, 9), Random(8, 4, CV_8UC1, 10)});
  EXPECT_TRUE(TiffHasOnePage(one));
  EXPECT_FALSE(TiffHasOnePage(two));
  EXPECT_FALSE(TiffHasOnePage(::testing::TempDir() + "/missing.tif"));
}

TEST(PlainTiff, DamagedHeadersNeverReadOutside) {  // meaningful in the sanitizer build
  const auto good = Encode(Random(13, 7, CV_8UC1, 11), 1);
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 3000; ++trial) {
    auto b = good;
    for (int k = 0; k < 3; ++k) b[rng() % b.size()] = uint8_t(rng());
    if (trial % 2) b.resize(rng() % b.size());
    cv::Mat out;
    if (DecodePlainTiff(b.data(), b.size(), &out)) {
      EXPECT_FALSE(out.empty());
    }
  }
}

// Exits 0 when `b` is declined, 1 when decoded; an allocation above 1 GiB aborts.
[[noreturn]] void DecodeWithin1GiB(const std::vector<uint8_t>& b) {
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = rlim_t(1) << 30;
  setrlimit(RLIMIT_AS, &limit);
  cv::Mat out;
  std::exit(DecodePlainTiff(b.data(), b.size(), &out) ? 1 : 0);
}

// The fuzz target's find: a 178-byte file whose header says 63,492 x 65,020 16-bit pixels made
// the decoder allocate 8 GB before finding the strips outside the file. Under a 1 GiB address
// space limit the allocation would throw; the header is declined before it.
TEST(PlainTiff, AForgedSizeIsDeclinedBeforeTheImageIsAllocated) {
  std::vector<uint8_t> b = Encode(Random(4, 3, CV_16UC1, 12), 1);
  auto set_single = [&](uint16_t tag, uint32_t v) {
    const uint32_t ifd = uint32_t(b[4] | b[5] << 8 | b[6] << 16 | uint32_t(b[7]) << 24);
    const int n = b[ifd] | b[ifd + 1] << 8;
    for (int e = 0; e < n; ++e) {
      uint8_t* p = b.data() + ifd + 2 + 12 * e;
      if ((p[0] | p[1] << 8) != tag) continue;
      p[2] = 4;  // LONG
      p[3] = 0;
      for (int k = 0; k < 4; ++k) p[8 + k] = uint8_t(v >> (8 * k));
      return true;
    }
    return false;
  };
  ASSERT_TRUE(set_single(256, 63492));  // ImageWidth
  ASSERT_TRUE(set_single(257, 65020));  // ImageLength
  ASSERT_TRUE(set_single(278, 65020));  // RowsPerStrip: one strip, as the table has
#if DIMERLAB_TEST_UNDER_ASAN
  // AddressSanitizer reserves terabytes of address space for its shadow, so no address-space
  // limit can hold a child; there the fuzz target's malloc limit (libFuzzer's 2 GB) guards it.
  GTEST_SKIP() << "an address-space limit cannot be set under AddressSanitizer";
#endif
  EXPECT_EXIT(DecodeWithin1GiB(b), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace dimer::tracking
