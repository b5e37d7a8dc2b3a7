// The direct grey-BMP decoder gives exactly cv::imdecode's frame, and declines (leaving the
// file to OpenCV) everything it does not cover.
#include "tracking/io/bmp_decode.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <random>

#include "tests/tracking/io/decoded_image.h"
#include "tracking/io/frame_source.h"

namespace dimer::tracking {
namespace {

std::vector<uint8_t> Encode(const cv::Mat& m) {
  std::vector<uint8_t> b;
  EXPECT_TRUE(cv::imencode(".bmp", m, b));
  return b;
}

TEST(GreyBmp, SameAsOpenCvForEveryRowPadding) {
  for (int w : {37, 38, 39, 40, 1}) {
    const cv::Mat m = Random(w, 11, CV_8UC1, w);
    const auto b = Encode(m);
    cv::Mat out;
    ASSERT_TRUE(DecodeGreyBmp(b.data(), b.size(), &out)) << w;
    EXPECT_TRUE(Same(out, m)) << w;
    EXPECT_TRUE(Same(out, OpenCvGrey(b))) << w;
  }
}

TEST(GreyBmp, TopDownRows) {
  const cv::Mat m = Random(8, 5, CV_8UC1, 3);
  auto b = Encode(m);  // bottom-up; make it top-down by hand
  const uint32_t at = b[10] | b[11] << 8 | b[12] << 16 | b[13] << 24;
  std::vector<uint8_t> flipped(b.begin() + at, b.end());
  for (int r = 0; r < 5; ++r) std::copy_n(b.begin() + at + 8 * (4 - r), 8, flipped.begin() + 8 * r);
  std::copy(flipped.begin(), flipped.end(), b.begin() + at);
  const int32_t h = -5;
  for (int k = 0; k < 4; ++k) b[22 + k] = uint8_t(uint32_t(h) >> (8 * k));
  cv::Mat out;
  ASSERT_TRUE(DecodeGreyBmp(b.data(), b.size(), &out));
  EXPECT_TRUE(Same(out, m));
}

TEST(GreyBmp, DeclinesWhatItDoesNotCover) {
  cv::Mat out;
  const auto colour = Encode(Random(9, 4, CV_8UC3, 4));
  EXPECT_FALSE(DecodeGreyBmp(colour.data(), colour.size(), &out));
  auto palette = Encode(Random(9, 4, CV_8UC1, 5));
  palette[54 + 4 * 7 + 2] = 200;  // entry 7 no longer grey
  EXPECT_FALSE(DecodeGreyBmp(palette.data(), palette.size(), &out));
  auto truncated = Encode(Random(9, 4, CV_8UC1, 6));
  truncated.resize(truncated.size() - 3);
  EXPECT_FALSE(DecodeGreyBmp(truncated.data(), truncated.size(), &out));
  EXPECT_TRUE(out.empty());
  // The frame reader then gives OpenCV's grey conversion of the colour file.
  const std::string path = ::testing::TempDir() + "/colour.bmp";
  cv::imwrite(path, Random(9, 4, CV_8UC3, 4));
  const Frame f = DecodeImageFile(path, 0, "colour.bmp");
  EXPECT_TRUE(f.error.empty());
  EXPECT_TRUE(Same(f.image, OpenCvGrey(colour)));
}

TEST(GreyBmp, DamagedHeadersNeverReadOutside) {  // meaningful in the sanitizer build
  const auto good = Encode(Random(13, 7, CV_8UC1, 7));
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    auto b = good;
    for (int k = 0; k < 3; ++k) b[rng() % 60] = uint8_t(rng());
    if (trial % 2) b.resize(rng() % b.size());
    cv::Mat out;
    if (DecodeGreyBmp(b.data(), b.size(), &out)) {
      EXPECT_FALSE(out.empty());
    }
  }
}

}  // namespace
}  // namespace dimer::tracking
