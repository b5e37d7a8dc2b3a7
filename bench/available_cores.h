#pragma once
// How many cores a benchmark really gets right now: CPU time over wall time of `threads` busy
// loops (2.0 on an idle 2-core machine; less when another job competes). Printed beside wall
// rates so that a table measured on a shared machine says how shared it was.
#include <sys/resource.h>

#include <chrono>
#include <thread>
#include <vector>

namespace dimer::bench {

inline double AvailableCores(int threads) {
  rusage before, after;
  getrusage(RUSAGE_SELF, &before);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int k = 0; k < threads; ++k) {
    pool.emplace_back([] {
      volatile double x = 0;
      for (long i = 0; i < 200000000; ++i) x = x + 1e-9;
    });
  }
  for (auto& t : pool) t.join();
  getrusage(RUSAGE_SELF, &after);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  auto cpu = [](const rusage& u) { return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec; };
  return (cpu(after) - cpu(before)) / wall;
}

}  // namespace dimer::bench
