// Two real Phantom films (pims' test data, tests/data/cine/README.md): the reader against
// pims' decode of the same files, and the frames' own time stamps against the rates they give.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <string>

#include "tracking/io/cine_source.h"
#include "tracking/io/cine_time_stamps.h"

namespace dimer::tracking {
namespace {

const std::string kData = DIMERLAB_TEST_DATA "/cine/";

struct Reference {
  const char* file;
  size_t frames;
  int width, height, real_bpp;
  double header_fps, stamped_fps;
  bool flip_v;
  double min0, max0, sum0, min_all, max_all;
};

// The README's reference values (pims' reader, uint16 levels as stored).
const Reference kFilms[] = {
    {"cine_781.cine", 15, 256, 256, 12, 90000, 9003, true, 75, 3028, 176860542, 55, 3035},
    {"cine_legacy.cine", 97, 128, 128, 14, 35087, 35098, false, 0, 6081, 4484258, 0, 6382},
};

class RealCine : public ::testing::TestWithParam<Reference> {};

TEST_P(RealCine, FramesLevelsAndRatesAreThoseOfPimsDecode) {
  const Reference& ref = GetParam();
  auto src = OpenCine(kData + ref.file);
  ASSERT_EQ(src->size(), ref.frames);
  const RecordingInfo info = src->recording();
  EXPECT_EQ(info.real_bpp, ref.real_bpp);
  EXPECT_EQ(info.fps, ref.header_fps);
  EXPECT_EQ(info.flip_v, ref.flip_v);
  double lo = 1e9, hi = -1;
  for (size_t i = 0; i < ref.frames; ++i) {
    const Frame f = src->Read(i);
    ASSERT_EQ(f.error, "") << i;
    ASSERT_EQ(f.image.type(), CV_16U);
    ASSERT_EQ(f.image.size(), cv::Size(ref.width, ref.height));
    double mn, mx;
    cv::minMaxLoc(f.image, &mn, &mx);
    if (i == 0) {
      EXPECT_EQ(mn, ref.min0);
      EXPECT_EQ(mx, ref.max0);
      EXPECT_EQ(cv::sum(f.image)[0], ref.sum0);
    }
    lo = std::min(lo, mn);
    hi = std::max(hi, mx);
  }
  EXPECT_EQ(lo, ref.min_all);
  EXPECT_EQ(hi, ref.max_all);
  ASSERT_EQ(info.frame_times.size(), ref.frames);
  EXPECT_NEAR(FrameRateOfTimes(info.frame_times), ref.stamped_fps, 1e-3 * ref.stamped_fps);
}

INSTANTIATE_TEST_SUITE_P(PimsTestData, RealCine, ::testing::ValuesIn(kFilms),
                         [](const auto& p) {
                           std::string n = p.param.file;
                           n = n.substr(0, n.find('.'));
                           n.erase(std::remove(n.begin(), n.end(), '_'), n.end());
                           return n;
                         });

}  // namespace
}  // namespace dimer::tracking
