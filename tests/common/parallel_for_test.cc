// common/parallel_for.h: every index exactly once whatever the thread count, the calling
// thread among the workers, and an exception from one index reaches the caller.
#include "common/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace dimer {
namespace {

// Uneven work per index (as registrations are), so that threads interleave.
double Work(size_t i) {
  double x = 0;
  for (size_t j = 0; j < 2000 * (i % 7 + 1); ++j) x += std::sin(double(i + j));
  return x;
}

TEST(ParallelFor, EveryIndexOnceAndTheSameResultsForAnyThreadCount) {
  const size_t n = 101;
  std::vector<double> serial(n);
  for (size_t i = 0; i < n; ++i) serial[i] = Work(i);
  for (int threads : {0, 1, 2, 3, 8, 200}) {
    std::vector<double> out(n, -1);
    std::vector<std::atomic<int>> calls(n);
    ParallelFor(n, threads, [&](size_t i) {
      ++calls[i];
      out[i] = Work(i);
    });
    for (size_t i = 0; i < n; ++i) {
      EXPECT_EQ(calls[i].load(), 1) << "index " << i << ", " << threads << " threads";
      EXPECT_EQ(out[i], serial[i]) << "index " << i << ", " << threads << " threads";
    }
  }
}

TEST(ParallelFor, RunsOnSeveralThreadsIncludingTheCaller) {
  std::mutex m;
  std::set<std::thread::id> seen;
  // Indices 0 and 1 each wait (up to 10 s) until two threads have taken work: with the caller
  // among the workers both are taken by different threads, however the scheduler orders them
  // on a loaded machine (a worker alone would otherwise finish all 64 before the caller starts).
  std::atomic<int> arrived{0};
  ParallelFor(64, 2, [&](size_t i) {
    if (i < 2) {
      ++arrived;
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (arrived < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    }
    Work(i);
    const std::lock_guard<std::mutex> lock(m);
    seen.insert(std::this_thread::get_id());
  });
  EXPECT_TRUE(seen.count(std::this_thread::get_id())) << "the calling thread works too";
  EXPECT_LE(seen.size(), 2u);
  size_t calls = 0;
  ParallelFor(0, 4, [&](size_t) { ++calls; });
  EXPECT_EQ(calls, 0u) << "nothing to do";
}

TEST(ParallelFor, AnExceptionReachesTheCaller) {
  for (int threads : {1, 2, 4}) {
    EXPECT_THROW(ParallelFor(50, threads,
                             [&](size_t i) {
                               if (i == 17) throw std::runtime_error("index 17");
                             }),
                 std::runtime_error)
        << threads << " threads";
  }
}

}  // namespace
}  // namespace dimer
