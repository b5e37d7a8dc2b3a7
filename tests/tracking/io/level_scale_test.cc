// 16-bit frames of a camera with fewer bits scaled to the 16-bit range (tracking/io/level_scale.h):
// from the .cine header's RealBPP, from --bits, or not at all (with a warning when the levels
// would fit a 10- or 12-bit camera's); levels beyond the bits given are an error.
#include "tracking/io/frame_source.h"
#include "tracking/io/level_scale.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"
#include "tracking/io/cine_writer.h"

namespace dimer::tracking {
namespace {

using dimer::testing::TempDir;

std::vector<cv::Mat> Frames(int type, int top, int n = 3) {
  std::vector<cv::Mat> f;
  for (int i = 0; i < n; ++i) {
    cv::Mat m(8, 12, type, cv::Scalar(10 + i));
    if (type == CV_16UC1) m.at<uint16_t>(2, 3) = uint16_t(top);  // the frame's brightest level
    f.push_back(m);
  }
  return f;
}

TEST(LevelScale, ATenBitCinesLevelsAreScaledToSixteenBits) {
  TempDir dir;
  CineWriteOptions o;
  o.pixels = CinePixels::k10BitPacked;
  WriteCine(dir / "ten.cine", Frames(CV_16UC1, 1023), o);
  auto src = OpenFrameSource(dir / "ten.cine");
  const LevelScale s = ChooseLevelScale(*src);
  EXPECT_DOUBLE_EQ(s.factor, 65535.0 / 1023.0);
  EXPECT_EQ(s.bits, 10);
  EXPECT_FALSE(s.warn);
  const auto scaled = ScaledLevels(*src, s.factor);
  const Frame f = scaled->Read(1);
  ASSERT_TRUE(f.error.empty());
  EXPECT_EQ(f.image.at<uint16_t>(2, 3), 65535);  // the camera's top is the container's
  EXPECT_EQ(f.image.at<uint16_t>(0, 0), 705);    // 11 x 64.06, rounded
  EXPECT_EQ(f.name, src->Read(1).name);
  EXPECT_EQ(ChooseLevelScale(*src, 16).factor, 1.0);  // --bits 16: as stored
}

TEST(LevelScale, AHeaderBelowTheLevelsIsNotTrusted) {
  TempDir dir;
  CineWriteOptions o;
  o.pixels = CinePixels::k16Bit;
  o.real_bpp = 12;
  WriteCine(dir / "scaled.cine", Frames(CV_16UC1, 60000), o);  // software already scaled them
  auto src = OpenFrameSource(dir / "scaled.cine");
  const LevelScale s = ChooseLevelScale(*src);
  EXPECT_EQ(s.factor, 1.0);
  EXPECT_NE(s.reason.find("above the 12-bit range"), std::string::npos) << s.reason;
}

// A .cine whose header says 16 bits is tracked as stored, however dark (no guess).
TEST(LevelScale, AHeaderSayingSixteenBitsIsBelieved) {
  TempDir dir;
  CineWriteOptions o;
  o.pixels = CinePixels::k16Bit;  // RealBPP 16
  WriteCine(dir / "dark.cine", Frames(CV_16UC1, 4000), o);
  auto src = OpenFrameSource(dir / "dark.cine");
  const LevelScale s = ChooseLevelScale(*src);
  EXPECT_EQ(s.factor, 1.0);
  EXPECT_FALSE(s.warn);
}

TEST(LevelScale, WithoutAHeaderTheBitsAreTheUsersOrGuessedWithAWarning) {
  MemorySource low(Frames(CV_16UC1, 4000));
  const LevelScale guess = ChooseLevelScale(low);
  EXPECT_DOUBLE_EQ(guess.factor, 65535.0 / 4095.0);
  EXPECT_EQ(guess.bits, 12);
  EXPECT_TRUE(guess.warn);
  EXPECT_NE(guess.reason.find("--bits"), std::string::npos) << guess.reason;
  MemorySource ten(Frames(CV_16UC1, 1000));
  EXPECT_EQ(ChooseLevelScale(ten).bits, 10);
  EXPECT_EQ(ChooseLevelScale(low, 16).factor, 1.0);  // --bits 16: as stored
  const LevelScale given = ChooseLevelScale(low, 12);
  EXPECT_DOUBLE_EQ(given.factor, 65535.0 / 4095.0);
  EXPECT_FALSE(given.warn);
  EXPECT_THROW(ChooseLevelScale(low, 10), InputError);  // 4000 does not fit 10 bits

  // Any bits short of 16, the fewest that hold the levels (8 at least): 8-bit levels x 64 (a
  // film filling a quarter of the range) as 14 bits, 8-bit levels stored unscaled as 8.
  MemorySource quarter(Frames(CV_16UC1, 255 * 64));
  EXPECT_EQ(ChooseLevelScale(quarter).bits, 14);
  EXPECT_DOUBLE_EQ(ChooseLevelScale(quarter).factor, 65535.0 / 16383.0);
  EXPECT_TRUE(ChooseLevelScale(quarter).warn);
  MemorySource unscaled(Frames(CV_16UC1, 200));
  EXPECT_EQ(ChooseLevelScale(unscaled).bits, 8);
  MemorySource full(Frames(CV_16UC1, 50000));
  EXPECT_FALSE(ChooseLevelScale(full).warn);
  MemorySource eight(Frames(CV_8UC1, 0));
  EXPECT_EQ(ChooseLevelScale(eight, 12).factor, 1.0);  // 8-bit frames: nothing to scale
}

// The bits are guessed from frames spread over the film, not the first alone: a film that
// brightens later (a lamp warming up, the dimer moving into the light) would otherwise be
// clipped at the first frame's bits.
TEST(LevelScale, TheGuessRestsOnFramesSpreadOverTheFilm) {
  std::vector<cv::Mat> frames = Frames(CV_16UC1, 900, 40);
  frames[30].at<uint16_t>(4, 5) = 3000;  // a later, brighter frame
  MemorySource film(frames);
  const LevelScale s = ChooseLevelScale(film);
  EXPECT_EQ(s.bits, 12);
  EXPECT_NE(s.reason.find("frame"), std::string::npos) << s.reason;
}

// A frame brighter than the bits the film was taken for (none of those sampled was) is clipped
// by the scaling, and counted once however often it is read, so that the track file and
// stderr can say so.
TEST(LevelScale, FramesTheScalingClipsAreCounted) {
  std::vector<cv::Mat> frames = Frames(CV_16UC1, 900, 40);
  frames[31].at<uint16_t>(4, 5) = 3000;  // frame 31 is not among the 16 sampled
  MemorySource film(frames);
  const LevelScale s = ChooseLevelScale(film);
  ASSERT_EQ(s.bits, 10);
  const auto scaled = ScaledLevels(film, s.factor);
  EXPECT_EQ(scaled->clipped_frames(), 0u);
  EXPECT_EQ(scaled->Read(30).image.at<uint16_t>(2, 3), uint16_t(std::lround(900 * s.factor)));
  EXPECT_EQ(scaled->clipped_frames(), 0u);
  EXPECT_EQ(scaled->Read(31).image.at<uint16_t>(4, 5), 65535);
  scaled->Read(31);
  EXPECT_EQ(scaled->clipped_frames(), 1u);
  EXPECT_EQ(scaled->first_clipped(), film.Read(31).name);
}

}  // namespace
}  // namespace dimer::tracking
