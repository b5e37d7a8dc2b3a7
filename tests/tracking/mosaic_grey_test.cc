// The grey frames made from a colour sensor's raw Bayer mosaic (tracking/mosaic_grey.h): the
// same luminance whatever the sensor's layout, no edge moved, exact integer results.
#include "tracking/mosaic_grey.h"

#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <string>

namespace dimer::tracking {
namespace {

// The colour filter at (row, col) for a layout named by its top-left 2x2 cell, e.g. "RGGB".
char FilterAt(const std::string& layout, int row, int col) {
  return layout[size_t(2 * (row % 2) + col % 2)];
}

// What a sensor with `layout` records of a scene whose colour at each pixel is `rgb(row, col)`.
template <typename T, typename F>
cv::Mat Mosaic(const std::string& layout, int rows, int cols, int type, F rgb) {
  cv::Mat m(rows, cols, type);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const std::array<int, 3> v = rgb(r, c);
      const char f = FilterAt(layout, r, c);
      m.at<T>(r, c) = T(f == 'R' ? v[0] : f == 'G' ? v[1] : v[2]);
    }
  }
  return m;
}

const std::array<std::string, 4> kLayouts = {"RGGB", "BGGR", "GRBG", "GBRG"};

// A scene of one colour: every pixel, the borders included, is (R + 2G + B) / 4, whichever
// layout the sensor has (the reason the reader need not trust the file's layout code).
TEST(MosaicGrey, EveryLayoutGivesTheSameLuminanceUpToTheBorders) {
  for (const std::string& layout : kLayouts) {
    const cv::Mat m8 = Mosaic<uint8_t>(layout, 7, 9, CV_8UC1, [](int, int) {
      return std::array<int, 3>{200, 100, 40};
    });
    const cv::Mat g8 = MosaicToGrey(m8);
    ASSERT_EQ(g8.type(), CV_8UC1);
    EXPECT_EQ(cv::countNonZero(g8 != 110), 0) << layout;  // (200 + 200 + 40) / 4

    const cv::Mat m16 = Mosaic<uint16_t>(layout, 6, 11, CV_16UC1, [](int, int) {
      return std::array<int, 3>{4000, 65535, 14};
    });
    const cv::Mat g16 = MosaicToGrey(m16);
    ASSERT_EQ(g16.type(), CV_16UC1);
    cv::Mat want(g16.size(), CV_16UC1, cv::Scalar(33771));  // (4000 + 131070 + 14) / 4
    EXPECT_EQ(cv::norm(g16, want, cv::NORM_INF), 0) << layout;
  }
}

// A grey scene (the filters see the same level) with a brightness ramp comes back unchanged
// inside the border: the filter is symmetric about each pixel and moves no edge.
TEST(MosaicGrey, AGreyScenesRampComesBackWhereItWas) {
  for (const std::string& layout : kLayouts) {
    auto ramp = [](int r, int c) {
      const int v = 1000 + 37 * c - 23 * r;
      return std::array<int, 3>{v, v, v};
    };
    const cv::Mat m = Mosaic<uint16_t>(layout, 12, 15, CV_16UC1, ramp);
    const cv::Mat g = MosaicToGrey(m);
    int wrong = 0;
    for (int r = 1; r + 1 < g.rows; ++r) {
      for (int c = 1; c + 1 < g.cols; ++c) wrong += g.at<uint16_t>(r, c) != ramp(r, c)[0];
    }
    EXPECT_EQ(wrong, 0) << layout;
  }
}

// Against sums in integers (mirrored borders, the nearest level, ties to even as OpenCV rounds):
// the float filter is exact, so every machine gives the same grey frame.
TEST(MosaicGrey, EqualsTheIntegerSumRounded) {
  cv::RNG rng(7);
  cv::Mat m(9, 13, CV_16UC1);
  rng.fill(m, cv::RNG::UNIFORM, 0, 65536);
  const cv::Mat g = MosaicToGrey(m);
  auto at = [&](int r, int c) {  // BORDER_REFLECT_101
    r = r < 0 ? -r : r >= m.rows ? 2 * m.rows - 2 - r : r;
    c = c < 0 ? -c : c >= m.cols ? 2 * m.cols - 2 - c : c;
    return int64_t(m.at<uint16_t>(r, c));
  };
  const int w[3] = {1, 2, 1};
  int wrong = 0;
  for (int r = 0; r < m.rows; ++r) {
    for (int c = 0; c < m.cols; ++c) {
      int64_t s = 0;
      for (int i = -1; i <= 1; ++i) {
        for (int j = -1; j <= 1; ++j) s += w[i + 1] * w[j + 1] * at(r + i, c + j);
      }
      int64_t q = s / 16;
      const int64_t rem = s % 16;
      if (rem > 8 || (rem == 8 && q % 2 == 1)) ++q;
      wrong += int64_t(g.at<uint16_t>(r, c)) != q;
    }
  }
  EXPECT_EQ(wrong, 0);
}

TEST(MosaicGrey, RefusesColourAndFloatFrames) {
  EXPECT_THROW(MosaicToGrey(cv::Mat(4, 4, CV_8UC3)), std::invalid_argument);
  EXPECT_THROW(MosaicToGrey(cv::Mat(4, 4, CV_32FC1)), std::invalid_argument);
}

}  // namespace
}  // namespace dimer::tracking
