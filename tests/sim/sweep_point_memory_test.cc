// A sweep point's memory does not grow with its event log: the impact types are tallied as the
// events come (RunControls::on_event) and the log is not kept. Its own test binary, because it
// counts every heap allocation of the process (global operator new replaced below).
#include <gtest/gtest.h>
#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "sim/simulator.h"
#include "sim/sweep_point.h"
#include "sim/sweep_spec.h"

namespace {

std::atomic<long> g_live_bytes{0}, g_peak_bytes{0};

void Count(long bytes) {
  const long live = g_live_bytes += bytes;
  long peak = g_peak_bytes.load();
  while (live > peak && !g_peak_bytes.compare_exchange_weak(peak, live)) {
  }
}

}  // namespace

void* operator new(size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  Count(static_cast<long>(malloc_usable_size(p)));
  return p;
}
void operator delete(void* p) noexcept {
  if (!p) return;
  Count(-static_cast<long>(malloc_usable_size(p)));
  std::free(p);
}
void operator delete(void* p, size_t) noexcept { operator delete(p); }

namespace dimer::sim {
namespace {

// The peak heap of `f` above what was live when it started, bytes.
template <typename F>
long PeakHeapOf(F f) {
  const long base = g_live_bytes.load();
  g_peak_bytes = base;
  f();
  return g_peak_bytes.load() - base;
}

// 3000 periods of the paper's drift (~18 events a period): the kept log is ~10 MB, the point
// without it ~0.2 MB (one sample and one PeriodStats a period). The bound sits between.
TEST(SweepPointMemory, TheEventLogIsNotKept) {
  SweepSpec spec;
  SetSpecValue(&spec, "ar", "3.9", "");
  SetSpecValue(&spec, "transient", "1000", "");
  SetSpecValue(&spec, "periods", "2000", "");
  PointResult p;
  const long point_bytes = PeakHeapOf([&] { p = RunSweepPoint(spec, 0); });
  ASSERT_EQ(p.mode, "drift");
  long events = 0;
  const long log_bytes = PeakHeapOf([&] {
    const SimResult r = RunSimulation(spec.PointOptions(0));  // the whole log kept
    events = static_cast<long>(r.events.size());
  });
  EXPECT_GT(events, 3000 * 10);
  EXPECT_GT(log_bytes, 5'000'000) << "the measure itself";
  EXPECT_LT(point_bytes, 1'000'000) << "a sweep point kept " << point_bytes << " bytes";
}

}  // namespace
}  // namespace dimer::sim
