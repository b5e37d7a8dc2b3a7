// Sweep throughput: points/s and simulated periods/s of `dimerlab sweep` (RunSweep: the
// in-process points, the fsync'd journal and the final file included) on 1 and 2 threads, for
// the paper's Fig. 4a grid (A_r 2..10 step 0.1 = 81 values, as samples/sweeps/fig4a.sweep, f = 25, 50, 75 Hz, 300 periods per
// point: 100 discarded + 200 measured). Target (docs/BENCHMARKS.md): the whole grid in < 10 s on
// 2 cores. Usage: bench_sweep [ar_step] (a coarser step, e.g. 0.4, for a quick look)
#include <unistd.h>

#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "sim/sweep_run.h"

using namespace dimer::sim;

int main(int argc, char** argv) {
  const std::string step = argc > 1 ? argv[1] : "0.1";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("bench_sweep_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  SweepSpec spec;
  SetSpecValue(&spec, "ar", "2:10:" + step, "");
  SetSpecValue(&spec, "freq", "25,50,75", "");
  SetSpecValue(&spec, "transient", "100", "");
  SetSpecValue(&spec, "periods", "200", "");
  // CPU seconds (all threads) beside the wall time: on a shared machine the wall time measures
  // the other processes too; CPU s / threads is the wall time the grid needs on idle cores.
  std::printf("| grid | points | periods/point | threads | wall s | CPU s | points/s | periods/s | periods/CPU s | drift points |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int threads : {1, 2}) {
    SweepRunArgs a;
    a.spec = spec;
    a.output = (dir / ("sweep_" + std::to_string(threads) + ".h5")).string();
    a.threads = threads;
    a.progress = false;
    const std::clock_t c0 = std::clock();
    const SweepRunStats s = RunSweep(a);
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    std::printf("| A_r 2:10:%s x f 25,50,75 | %ld | %ld | %d | %.2f | %.2f | %.1f | %.0f | %.0f | %ld |\n",
                step.c_str(), s.computed, spec.transient + spec.periods, threads, s.seconds, cpu,
                s.computed / s.seconds, s.periods / s.seconds, s.periods / cpu, s.drift);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
