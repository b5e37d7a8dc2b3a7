// Output samples (docs/FORMATS.md, "Samples"): n defined once, sample k at exactly
// t_start + k / fps, the end time included whenever duration * fps is whole up to rounding;
// a run stopped early carries the time it reached as t_end.
#include <gtest/gtest.h>

#include "common/h5_file.h"
#include <cmath>
#include <utility>
#include <vector>

#include "sim/run_sim.h"
#include "sim/sim_file.h"
#include "sim/simulator.h"
#include "tests/common/test_tmpdir.h"

namespace dimer::sim {
namespace {

TEST(SampleCount, WholePeriodsAtEveryRateIncludeTheEndTime) {
  // Integer frequencies and rates: n - 1 = floor(N F / f) is exact in integers, the oracle.
  for (long f : {7L, 25L, 30L, 50L, 75L}) {
    for (long fps : {333L, 600L, 1000L, 2000L}) {
      for (long cycles = 1; cycles <= 300; ++cycles) {
        SimOptions o;
        o.freq_hz = static_cast<double>(f);
        o.fps = static_cast<double>(fps);
        o.cycles = static_cast<double>(cycles);
        ASSERT_EQ(o.SampleCount(), cycles * fps / f + 1)
            << cycles << " periods at " << f << " Hz, " << fps << " samples/s";
      }
    }
  }
}

TEST(SampleCount, DurationsAtTheRoundingEdges) {
  SimOptions o;
  o.fps = 2000;
  // 0.3 * 2000 = 600.0000000000001 and 0.7 * 2000 = 1400.0000000000002 in doubles; 0.15 * 2000
  // = 299.99999999999997: all whole numbers up to rounding, so the end is a sample.
  for (const auto& [duration, n] : std::vector<std::pair<double, long>>{
           {0.1, 201}, {0.3, 601}, {0.7, 1401}, {0.15, 301}, {0.0123, 25}, {0.00049, 1}}) {
    o.duration_s = duration;
    EXPECT_EQ(o.SampleCount(), n) << duration << " s";
  }
  o.fps = 0;
  EXPECT_EQ(o.SampleCount(), 0);  // events only
}

// Every sample of a run is at exactly t_start + k / fps, and there are SampleCount() of them.
void ExpectExactGrid(const SimOptions& o, const SimResult& r) {
  ASSERT_EQ(static_cast<long>(r.t.size()), o.SampleCount());
  ASSERT_EQ(r.lab.size(), r.t.size());
  for (size_t k = 0; k < r.t.size(); ++k) {
    ASSERT_EQ(r.t[k], r.t_start + static_cast<double>(k) / o.fps) << "sample " << k;
  }
  EXPECT_LE(r.t.back(), r.t_end + 1e-9 * r.model.period);
}

TEST(SampleCount, RunsWriteExactlyTheDefinedSamples) {
  for (double cycles : {1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 10.0, 2.5}) {
    SimOptions o;
    o.cycles = cycles;
    const SimResult r = RunSimulation(o);
    SCOPED_TRACE(cycles);
    ExpectExactGrid(o, r);
    if (cycles == std::floor(cycles)) {
      EXPECT_EQ(r.t.size(), static_cast<size_t>(80 * cycles + 1));
    }
  }
  SimOptions jump;  // starts at the orbit's phase, not at 0
  jump.init = InitKind::kJump;
  jump.cycles = 4;
  jump.fps = 1000;
  const SimResult rj = RunSimulation(jump);
  EXPECT_GT(rj.t_start, 0);
  ExpectExactGrid(jump, rj);
}

TEST(PartialRun, CarriesTheTimeItReachedAsTEnd) {
  dimer::testing::TempDir dir;
  SimOptions o;
  o.cycles = 100;
  RunControls c;
  int polls = 0;
  c.should_stop = [&] { return ++polls >= 7; };
  const SimResult r = RunSimulation(o, c);
  ASSERT_TRUE(r.interrupted);
  EXPECT_NEAR(r.t_end, r.t_start + 7 * r.model.period, 1e-12);  // not the requested 4 s
  EXPECT_LE(r.t.back(), r.t_end);
  WriteSimFile(dir / "partial.h5", false, o, r);
  H5Reader h(dir / "partial.h5");
  EXPECT_EQ(h.AttrDouble("/", "t_end"), r.t_end);
  EXPECT_EQ(h.AttrDouble("/", "interrupted"), 1.0);
  const SimResult full = RunSimulation(o);
  EXPECT_FALSE(full.interrupted);
  EXPECT_EQ(full.t_end, full.t_start + o.Duration());
}

}  // namespace
}  // namespace dimer::sim
