// The frames' own time stamps of a .cine (the TIME_ONLY tagged block): read back as written,
// and a block that cannot be right (another count, times that do not increase) ignored.
#include "tracking/io/cine_time_stamps.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <vector>

#include "tests/common/test_tmpdir.h"
#include "tracking/io/cine_layout.h"
#include "tracking/io/cine_source.h"
#include "tracking/io/cine_writer.h"

namespace dimer::tracking {
namespace {

// A TIME_ONLY block of `stamps` (TIME64: fraction, then seconds).
std::vector<uint8_t> Block(const std::vector<uint64_t>& stamps, uint16_t type = 1002) {
  std::vector<uint8_t> b(8 + 8 * stamps.size());
  const uint32_t size = uint32_t(b.size());
  std::memcpy(b.data(), &size, 4);
  std::memcpy(b.data() + 4, &type, 2);
  for (size_t i = 0; i < stamps.size(); ++i) {
    const uint32_t frac = uint32_t(stamps[i]), sec = uint32_t(stamps[i] >> 32);
    std::memcpy(b.data() + 8 + 8 * i, &frac, 4);
    std::memcpy(b.data() + 12 + 8 * i, &sec, 4);
  }
  return b;
}

TEST(CineFrameTimes, ReadsTheTimeOnlyBlockAfterOtherBlocks) {
  const uint64_t s = uint64_t(1551223045) << 32;
  std::vector<uint8_t> blocks = Block({7, 8}, 1003);  // EXPOSURE_ONLY-sized: skipped
  const std::vector<uint8_t> times = Block({s, s + (uint64_t(1) << 31), s + (uint64_t(1) << 32)});
  blocks.insert(blocks.end(), times.begin(), times.end());
  const std::vector<double> t = CineFrameTimes(blocks.data(), blocks.size(), 3);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0], 0.0);
  EXPECT_EQ(t[1], 0.5);
  EXPECT_EQ(t[2], 1.0);
  EXPECT_EQ(FrameRateOfTimes(t), 2.0);
}

TEST(CineFrameTimes, ABlockThatCannotBeRightIsIgnored) {
  const std::vector<uint8_t> two = Block({10, 20});
  EXPECT_TRUE(CineFrameTimes(two.data(), two.size(), 3).empty());  // another count
  const std::vector<uint8_t> back = Block({10, 20, 20});
  EXPECT_TRUE(CineFrameTimes(back.data(), back.size(), 3).empty());  // not increasing
  std::vector<uint8_t> range = Block({1}, 1004);  // RANGE_DATA ends the list
  const std::vector<uint8_t> after = Block({10, 20});
  range.insert(range.end(), after.begin(), after.end());
  EXPECT_TRUE(CineFrameTimes(range.data(), range.size(), 2).empty());
  std::vector<uint8_t> huge = Block({10, 20});
  const uint32_t lie = 0xFFFFFFF0u;  // a size past the end
  std::memcpy(huge.data(), &lie, 4);
  EXPECT_TRUE(CineFrameTimes(huge.data(), huge.size(), 2).empty());
  EXPECT_EQ(FrameRateOfTimes({}), 0.0);
}

TEST(CineFrameTimes, TheWritersBlockReachesTheSourceAndTheHeaderKeepsItsRate) {
  dimer::testing::TempDir dir;
  CineWriteOptions o;
  o.frame_rate = 90000;
  o.time_stamp_rate = 9000;
  o.trigger_seconds = 1551223045;
  std::vector<cv::Mat> frames(5, cv::Mat(8, 16, CV_8U, cv::Scalar(9)));
  WriteCine(dir / "decimated.cine", frames, o);
  auto src = OpenCine(dir / "decimated.cine");
  ASSERT_EQ(src->size(), 5u);
  EXPECT_EQ(src->Read(4).error, "");
  const RecordingInfo info = src->recording();
  EXPECT_EQ(info.fps, 90000.0);
  ASSERT_EQ(info.frame_times.size(), 5u);
  EXPECT_NEAR(info.frame_times[4], 4.0 / 9000, 1e-9);
  EXPECT_NEAR(FrameRateOfTimes(info.frame_times), 9000.0, 0.01);  // stamps in 2^-32 s
  WriteCine(dir / "plain.cine", frames, {});
  EXPECT_TRUE(OpenCine(dir / "plain.cine")->recording().frame_times.empty());
}

}  // namespace
}  // namespace dimer::tracking
