// The grey frames made from a colour sensor's raw Bayer mosaic (tracking/io/mosaic_grey.h): the
// same luminance whatever the sensor's layout, a lamp's tint balanced away without blur, colour
// left only where the scene has it and filtered there, no edge moved, exact integer filtering.
#include "tracking/io/mosaic_grey.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
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
      const std::array<double, 3> v = rgb(r, c);
      const char f = FilterAt(layout, r, c);
      m.at<T>(r, c) = cv::saturate_cast<T>(std::round(f == 'R' ? v[0] : f == 'G' ? v[1] : v[2]));
    }
  }
  return m;
}

const std::array<std::string, 4> kLayouts = {"RGGB", "BGGR", "GRBG", "GBRG"};

// A scene of one colour: every pixel, the borders included, is (R + 2G + B) / 4 whichever layout
// the sensor has: through the balance on a frame with enough cells, through the filter where the
// frame is too small to balance (the reason the reader need not trust the file's layout code).
TEST(MosaicGrey, EveryLayoutGivesTheSameLuminanceUpToTheBorders) {
  for (const std::string& layout : kLayouts) {
    for (const cv::Size size : {cv::Size(9, 7), cv::Size(41, 31)}) {
      const cv::Mat m8 = Mosaic<uint8_t>(layout, size.height, size.width, CV_8UC1, [](int, int) {
        return std::array<double, 3>{200, 100, 40};
      });
      const MosaicBalance b8 = EstimateMosaicBalance(m8, 255);
      EXPECT_EQ(b8.found(), size.width > 20) << layout;
      const cv::Mat g8 = MosaicToGrey(m8, b8);
      ASSERT_EQ(g8.type(), CV_8UC1);
      EXPECT_EQ(cv::countNonZero(g8 != 110), 0) << layout << " " << size;  // (200 + 200 + 40) / 4

      const cv::Mat m16 =
          Mosaic<uint16_t>(layout, size.height, size.width, CV_16UC1, [](int, int) {
            return std::array<double, 3>{4000, 65000, 14};
          });
      const cv::Mat g16 = MosaicToGrey(m16, EstimateMosaicBalance(m16, 65535));
      ASSERT_EQ(g16.type(), CV_16UC1);
      cv::Mat want(g16.size(), CV_16UC1, cv::Scalar(33504));  // (4000 + 130000 + 14) / 4 = 33503.5
      EXPECT_LE(cv::norm(g16, want, cv::NORM_INF), 1) << layout << " " << size;
    }
  }
}

// A lamp's tint on a grey scene (a bright disc on a dark backdrop, as a sphere's highlight on
// steel, blurred as by a lens and with an 8-bit camera's read noise): the balance finds the tint
// whatever the layout, and nearly every pixel is its own level divided by its phase's ratio,
// unfiltered (no blur): the tint leaves no colour to filter, the noise and the disc's edge
// almost none (the edge's curvature is grey; a few of its pixels may pass the noise limit).
TEST(MosaicGrey, ALampsTintIsBalancedAwayWithoutBlur) {
  const std::array<double, 3> tint = {1.0, 0.8, 0.55};  // R, G, B
  auto scene = [](int r, int c) {
    const double d = std::hypot(r - 40.3, c - 61.7);
    return 20.0 + 220.0 / (1.0 + std::exp((d - 24.0) / 0.8));
  };
  for (const std::string& layout : kLayouts) {
    cv::RNG rng(11);
    const cv::Mat m = Mosaic<uint8_t>(layout, 80, 128, CV_8UC1, [&](int r, int c) {
      const double v = scene(r, c);
      return std::array<double, 3>{v * tint[0] + rng.gaussian(2), v * tint[1] + rng.gaussian(2),
                                   v * tint[2] + rng.gaussian(2)};
    });
    const MosaicBalance b = EstimateMosaicBalance(m, 255);
    ASSERT_TRUE(b.found());
    const double mean_tint = (tint[0] + 2 * tint[1] + tint[2]) / 4;
    for (int p = 0; p < 4; ++p) {
      const char f = layout[size_t(p)];
      const double t = f == 'R' ? tint[0] : f == 'G' ? tint[1] : tint[2];
      EXPECT_NEAR(b.ratio[size_t(p)], t / mean_tint, 0.01) << layout << " phase " << p;
    }
    const cv::Mat g = MosaicToGrey(m, b);
    int own = 0;
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c) {
        const double balanced = m.at<uint8_t>(r, c) / b.ratio[size_t(2 * (r % 2) + c % 2)];
        own += g.at<uint8_t>(r, c) == cv::saturate_cast<uint8_t>(balanced);
      }
    }
    EXPECT_GE(own, int(0.99 * double(g.total()))) << layout;
  }
}

// A coloured patch in a grey scene: its cells (and only they, with the cells its border
// crosses) are filtered; the grey ones keep their own level.
TEST(MosaicGrey, OnlyCellsThatStayColouredAreFiltered) {
  auto rgb = [](int r, int c) {
    const bool patch = r >= 10 && r < 20 && c >= 12 && c < 24;
    return patch ? std::array<double, 3>{180, 60, 30} : std::array<double, 3>{100, 100, 100};
  };
  const cv::Mat m = Mosaic<uint8_t>("RGGB", 32, 40, CV_8UC1, rgb);
  const MosaicBalance b = EstimateMosaicBalance(m, 255);
  ASSERT_TRUE(b.found());
  for (double r : b.ratio) EXPECT_DOUBLE_EQ(r, 1.0);  // most cells are grey
  const cv::Mat g = MosaicToGrey(m, b), f = MosaicFilterToGrey(m);
  int grey_kept = 0, grey_total = 0, patch_filtered = 0, patch_total = 0;
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const bool in_patch = r >= 10 && r < 20 && c >= 12 && c < 24;
      const bool near_patch = r >= 8 && r < 22 && c >= 10 && c < 26;
      if (in_patch) {
        ++patch_total;
        patch_filtered += g.at<uint8_t>(r, c) == f.at<uint8_t>(r, c);
      } else if (!near_patch) {
        ++grey_total;
        grey_kept += g.at<uint8_t>(r, c) == 100;
      }
    }
  }
  EXPECT_EQ(grey_kept, grey_total);
  EXPECT_EQ(patch_filtered, patch_total);
}

// A grey scene's brightness ramp comes back unchanged, the borders included: a linear gradient
// puts nothing in a cell's checkerboard component, so nothing is filtered and no edge moves.
TEST(MosaicGrey, AGreyScenesRampComesBackWhereItWas) {
  for (const std::string& layout : kLayouts) {
    auto ramp = [](int r, int c) {
      const double v = 1000 + 37 * c - 23 * r;
      return std::array<double, 3>{v, v, v};
    };
    const cv::Mat m = Mosaic<uint16_t>(layout, 12, 15, CV_16UC1, ramp);
    const cv::Mat g = MosaicToGrey(m, MosaicBalance{});
    int wrong = 0;
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c) wrong += g.at<uint16_t>(r, c) != ramp(r, c)[0];
    }
    EXPECT_EQ(wrong, 0) << layout;
  }
}

// The filter against sums in integers (mirrored borders, the nearest level, ties to even as
// OpenCV rounds): exact in float, so every machine gives the same grey frame.
TEST(MosaicGrey, TheFilterEqualsTheIntegerSumRounded) {
  cv::RNG rng(7);
  cv::Mat m(9, 13, CV_16UC1);
  rng.fill(m, cv::RNG::UNIFORM, 0, 65536);
  const cv::Mat g = MosaicFilterToGrey(m);
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
  EXPECT_THROW(MosaicToGrey(cv::Mat(4, 4, CV_8UC3), MosaicBalance{}), std::invalid_argument);
  EXPECT_THROW(MosaicFilterToGrey(cv::Mat(4, 4, CV_32FC1)), std::invalid_argument);
  EXPECT_THROW(EstimateMosaicBalance(cv::Mat(4, 4, CV_32FC1), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace dimer::tracking
