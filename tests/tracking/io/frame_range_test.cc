// --frames A:B: parsing, and the one wrapper over a folder, a .cine and a sequential source.
#include "tracking/io/frame_source.h"
#include "tracking/io/frame_range.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"
#include "tracking/io/cine_writer.h"

namespace dimer::tracking {
namespace {

using dimer::testing::TempDir;

TEST(FrameRange, Parses) {
  const FrameRange a = ParseFrameRange("2:5");
  EXPECT_EQ(a.first, 2u);
  EXPECT_EQ(a.end.value(), 5u);
  const FrameRange b = ParseFrameRange("3:");
  EXPECT_EQ(b.first, 3u);
  EXPECT_FALSE(b.end);
  const FrameRange c = ParseFrameRange(":4");
  EXPECT_EQ(c.first, 0u);
  EXPECT_EQ(c.end.value(), 4u);
  EXPECT_TRUE(ParseFrameRange("").all());
  EXPECT_EQ(a.ToString(), "2:5");
  EXPECT_EQ(b.ToString(), "3:");
  EXPECT_EQ(c.ToString(), ":4");
}

TEST(FrameRange, BadTextIsAUsageErrorNamingTheOption) {
  for (const char* bad : {"5:5", "5:3", "a:b", "-1:3", "1:2:3", ":", "3", "1 :4", "0x1:4",
                          "99999999999999999999:"}) {
    try {
      ParseFrameRange(bad);
      ADD_FAILURE() << bad;
    } catch (const UsageError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string("--frames '") + bad + "'", 0), 0u)
          << e.what();
    }
  }
}

cv::Mat Plain(int value) { return cv::Mat(6, 8, CV_8UC1, cv::Scalar(value)); }

void ExpectFrames(FrameSource& s, const std::vector<size_t>& indices) {
  ASSERT_EQ(s.size(), indices.size());
  for (size_t i = 0; i < indices.size(); ++i) {
    if (s.random_access()) {
      const Frame f = s.Read(i);
      EXPECT_EQ(f.index, indices[i]);  // the original index
      EXPECT_EQ(f.image.at<uint8_t>(0, 0), 10 + indices[i]);
    }
  }
  Frame f;
  std::vector<size_t> seen;
  while (s.Next(&f)) {
    seen.push_back(f.index);
    EXPECT_EQ(f.image.at<uint8_t>(0, 0), 10 + f.index);
  }
  EXPECT_EQ(seen, indices);
}

TEST(FrameRange, OnAFolder) {
  TempDir dir;
  for (int i = 0; i < 12; ++i) cv::imwrite(dir / ("f_" + std::to_string(i) + ".png"), Plain(10 + i));
  auto s = SelectFrames(OpenFrameSource(dir.path().string()), ParseFrameRange("2:5"), "in");
  ExpectFrames(*s, {2, 3, 4});
  EXPECT_EQ(s->Read(0).name, "f_2.png");  // natural order: f_2 is the third file, not f_10
  auto tail = SelectFrames(OpenFrameSource(dir.path().string()), ParseFrameRange("10:"), "in");
  ExpectFrames(*tail, {10, 11});
  auto cut = SelectFrames(OpenFrameSource(dir.path().string()), ParseFrameRange("9:100"), "in");
  ExpectFrames(*cut, {9, 10, 11});  // an end past the last frame is cut to it
}

TEST(FrameRange, OnACine) {
  TempDir dir;
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 7; ++i) frames.push_back(Plain(10 + i));
  WriteCine(dir / "x.cine", frames, {});
  auto s = SelectFrames(OpenFrameSource(dir / "x.cine"), ParseFrameRange(":3"), "x.cine");
  ExpectFrames(*s, {0, 1, 2});
  auto t = SelectFrames(OpenFrameSource(dir / "x.cine"), ParseFrameRange("4:"), "x.cine");
  ExpectFrames(*t, {4, 5, 6});
  EXPECT_EQ(t->recording().fps, 2000.0);  // the header passes through
}

// A source that can only be read forward, like a video.
class Sequential : public MemorySource {
 public:
  using MemorySource::MemorySource;
  bool random_access() const override { return false; }
};

TEST(FrameRange, OnASequentialSource) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 9; ++i) frames.push_back(Plain(10 + i));
  auto s = SelectFrames(std::make_unique<Sequential>(frames), ParseFrameRange("3:6"), "video");
  EXPECT_FALSE(s->random_access());
  ExpectFrames(*s, {3, 4, 5});
}

TEST(FrameRange, StartPastTheEndIsAnInputErrorNamingTheInput) {
  std::vector<cv::Mat> frames(5, Plain(10));
  try {
    SelectFrames(std::make_unique<MemorySource>(frames), ParseFrameRange("5:8"), "run.cine");
    FAIL();
  } catch (const UsageError&) {
    FAIL() << "not a usage error: the range is valid, the input is shorter";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "run.cine: --frames 5:8 starts at frame 5 but there are only 5 frames (0..4)");
  }
}

}  // namespace
}  // namespace dimer::tracking
