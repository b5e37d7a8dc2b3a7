#pragma once
// f(i) for every i in [0, n), on up to `threads` threads (the calling one among them). The
// sequence-level learning (appearance_model.cc, learn_method.cc) registers each learning
// frame on its own, ~3 ms of ECC each and ~1,000 of them per run: serial, that was seconds of a
// single core before the first frame was tracked.
//
// Each i is taken exactly once, by whichever thread is free (registrations differ in cost), and
// f must write only what belongs to i: then the results are the same for any thread count, as
// the tracker's are (docs/DESIGN.md). The first exception thrown by f is rethrown here, after
// every thread has stopped.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace dimer {

template <class F>
void ParallelFor(size_t n, int threads, F&& f) {
  const size_t workers = std::min<size_t>(n, size_t(threads > 1 ? threads : 1));
  if (workers <= 1) {
    for (size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&]() {
    for (size_t i; (i = next.fetch_add(1)) < n;) {
      try {
        f(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(n);  // the others stop at their next index
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < workers; ++t) pool.emplace_back(run);
  run();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace dimer
