#include "common/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace dimer {
namespace {

std::string Contents(FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string out;
  for (int c; (c = std::fgetc(f)) != EOF;) out += static_cast<char>(c);
  return out;
}

TEST(ProgressMeter, PlainOutputIsWholeLinesWithoutCarriageReturns) {
  FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    ProgressMeter m("sim", "periods", 10, true, log, /*live=*/false, /*plain_interval_s=*/0);
    for (int i = 1; i <= 3; ++i) m.Update(i);
    m.Finish(10);
  }
  const std::string text = Contents(log);
  std::fclose(log);
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 4u) << text;  // three updates and the final line
  EXPECT_NE(text.find("sim: 3/10 periods"), std::string::npos) << text;
  EXPECT_NE(text.find("sim: 10/10 periods"), std::string::npos) << text;
}

// A total that is an estimate (a fit that moves and profiles again) can be passed: the count
// and rate are shown, never a negative ETA.
TEST(ProgressMeter, PastItsEstimateShowsNoEta) {
  FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    ProgressMeter m("fit", "simulations", 10, true, log, /*live=*/false, /*plain_interval_s=*/0);
    m.Update(5);
    m.Update(15);
  }
  const std::string text = Contents(log);
  std::fclose(log);
  EXPECT_NE(text.find("fit: 5/10 simulations"), std::string::npos) << text;
  EXPECT_NE(text.find("fit: 15 simulations"), std::string::npos) << text;
  EXPECT_EQ(text.find("ETA -"), std::string::npos) << text;
}

TEST(ProgressMeter, PlainOutputIsThrottledToItsInterval) {
  FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    ProgressMeter m("track", "frames", 1000, true, log, /*live=*/false, /*plain_interval_s=*/60);
    for (int i = 1; i <= 1000; ++i) m.Update(i);  // far faster than one line a minute
    m.Finish(1000);
  }
  const std::string text = Contents(log);
  std::fclose(log);
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 1u) << text;  // only the final line
}

TEST(ProgressMeter, LiveOutputRedrawsInPlaceAndDisabledIsSilent) {
  FILE* tty = std::tmpfile();
  FILE* quiet = std::tmpfile();
  {
    ProgressMeter live("sim", "periods", 10, true, tty, /*live=*/true);
    live.Finish(10);
    ProgressMeter off("sim", "periods", 10, false, quiet, /*live=*/true);
    off.Update(5);
    off.Finish(10);
  }
  const std::string text = Contents(tty);
  EXPECT_EQ(text.front(), '\r');
  EXPECT_EQ(text.back(), '\n');
  EXPECT_TRUE(Contents(quiet).empty());
  std::fclose(tty);
  std::fclose(quiet);
}

}  // namespace
}  // namespace dimer
