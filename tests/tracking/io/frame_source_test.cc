#include "tracking/io/frame_source.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace dimer::tracking {
namespace {

TEST(NaturalLess, NumbersCompareByValue) {
  std::vector<std::string> v = {"frame_10.png", "frame_2.png", "frame_1.png", "frame_02.png",
                                "a.png", "frame_100.png"};
  std::sort(v.begin(), v.end(), NaturalLess);
  EXPECT_EQ(v, (std::vector<std::string>{"a.png", "frame_1.png", "frame_2.png", "frame_02.png",
                                         "frame_10.png", "frame_100.png"}));
  EXPECT_FALSE(NaturalLess("x", "x"));
}

}  // namespace
}  // namespace dimer::tracking
