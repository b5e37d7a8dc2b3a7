// The direct plain-TIFF decoder gives exactly cv::imdecode's frame, and declines (leaving the
// file to OpenCV) everything it does not cover.
#include "tracking/io/tiff_decode.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <random>

#include "tests/tracking/io/decoded_image.h"
#include "tracking/io/frame_source.h"

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

}  // namespace
}  // namespace dimer::tracking
