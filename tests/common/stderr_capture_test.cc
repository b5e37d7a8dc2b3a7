#include "common/stderr_capture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace dimer {
namespace {

TEST(StderrCapture, LinesWrittenToStderrFromAnyThreadReachTheHandlerAndNothingElse) {
  std::mutex m;
  std::vector<std::string> lines;
  ::testing::internal::CaptureStderr();  // what reaches the real stderr
  {
    StderrCapture capture([&](const std::string& line) {
      std::lock_guard<std::mutex> lock(m);
      lines.push_back(line);
    });
    ASSERT_TRUE(capture.active());
    std::fprintf(stderr, "libfoo: first\n");
    std::thread([] { ::write(STDERR_FILENO, "libbar: second\nlibbar: third", 28); }).join();
    std::fprintf(StderrCapture::Diagnostics(), "dimerlab: ours\n");
  }
  const std::string real = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(real, "dimerlab: ours\n");
  EXPECT_EQ(lines, (std::vector<std::string>{"libfoo: first", "libbar: second", "libbar: third"}));
  // Restored: stderr is the real one again, and Diagnostics() is stderr.
  EXPECT_EQ(StderrCapture::Diagnostics(), stderr);
}

}  // namespace
}  // namespace dimer
