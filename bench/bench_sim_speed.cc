// Simulator speed: simulated plate periods per second on one core, in the drift mode and the
// other modes, with and without output sampling (docs/BENCHMARKS.md, bench_sim_speed); a
// rest state costs (almost) nothing per period. --baseline compares it with another build
// measured in the same run.
//
// A second table times the whole `dimerlab sim` (RunSim: simulate while the file's chunks are
// compressed, then write the sim file) by CPU time per plate period, all threads counted, and
// wall time, compressing on one thread and on every core; beside it the MuJoCo model of the
// same dimer (docs/BENCHMARKS.md, bench_sim_speed: 4.9-6.1 ms CPU per period at h = 2e-5 s,
// measured outside the project, MuJoCo not being a dependency).
//
// Usage: bench_sim_speed [periods] [--baseline OLD_BENCH_BINARY] [--repeats N]
//   --repeats N also sets how many times each case of the second table runs (default 3).
//   Without --baseline: one table of this build. With it: OLD_BENCH_BINARY (another build of
//   this program, e.g. from main) and this build run alternately N times (default 3) with the
//   same periods; each case's best periods/s of the N runs (the least disturbed by other load
//   on the machine) is compared.
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sim/run_sim.h"
#include "sim/simulator.h"

using namespace dimer::sim;

namespace {

struct Row {
  std::string label;
  SimOptions o;
};

struct Measured {
  double periods = 0, events_per_period = 0, seconds = 0;
  std::string mode;
  double Rate() const { return periods / seconds; }
};

Measured Measure(const SimOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  RunControls c;
  c.keep_events = o.fps > 0;
  const SimResult r = RunSimulation(o, c);
  Measured m;
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  m.periods = static_cast<double>(r.periods.size());
  m.events_per_period = r.diag.events / m.periods;
  m.mode = r.mode.label;
  return m;
}

std::vector<Row> Rows(double periods) {
  auto make = [&](double ar, double freq, InitKind init, double fps) {
    SimOptions o;
    o.ar = ar;
    o.freq_hz = freq;
    o.init = init;
    o.fps = fps;
    o.cycles = periods;
    return o;
  };
  return {
      {"drift A_r 3.9, 25 Hz, events only", make(3.9, 25, InitKind::kDrift, 0)},
      {"drift A_r 3.9, 25 Hz, 2000 samples/s + event log", make(3.9, 25, InitKind::kDrift, 2000)},
      {"drift A_r 6.1, 25 Hz, events only", make(6.1, 25, InitKind::kDrift, 0)},
      {"drift A_r 3.9, 75 Hz, events only", make(3.9, 75, InitKind::kDrift, 0)},
      {"jump A_r 3.9, 25 Hz, events only", make(3.9, 25, InitKind::kJump, 0)},
      {"rest A_r 3.9, 25 Hz, events only", make(3.9, 25, InitKind::kRest, 0)},
  };
}

// One table of this build (the format --baseline parses from another build).
std::map<std::string, double> RunTable(const std::vector<Row>& rows, bool print) {
  std::map<std::string, double> rate;
  if (print) {
    std::printf("| case | periods | events/period | wall s | periods/s | settled |\n");
    std::printf("|---|---:|---:|---:|---:|---|\n");
  }
  for (const Row& row : rows) {
    const Measured m = Measure(row.o);
    rate[row.label] = m.Rate();
    if (print) {
      std::printf("| %s | %.0f | %.1f | %.3f | %.0f | %s |\n", row.label.c_str(), m.periods,
                  m.events_per_period, m.seconds, m.Rate(), m.mode.c_str());
      std::fflush(stdout);
    }
  }
  return rate;
}

// Runs another build of this program and reads its table: label -> periods/s.
std::map<std::string, double> RunBaseline(const std::string& binary, double periods) {
  const std::string cmd = "'" + binary + "' " + std::to_string(static_cast<long>(periods));
  std::map<std::string, double> rate;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    std::fprintf(stderr, "bench_sim_speed: cannot run %s\n", cmd.c_str());
    std::exit(1);
  }
  char line[512];
  while (std::fgets(line, sizeof line, p)) {
    // | label | periods | events/period | wall s | periods/s | settled |
    std::vector<std::string> cells;
    std::string cell;
    for (const char* c = line; *c && *c != '\n'; ++c) {
      if (*c == '|') {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += *c;
      }
    }
    if (cells.size() < 6) continue;
    auto trim = [](std::string s) {
      const size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
      return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
    };
    const std::string label = trim(cells[1]);
    char* end = nullptr;
    const std::string value = trim(cells[5]);
    const double v = std::strtod(value.c_str(), &end);
    if (label == "case" || end == value.c_str()) continue;
    rate[label] = v;
  }
  if (pclose(p) != 0 || rate.empty()) {
    std::fprintf(stderr, "bench_sim_speed: %s: no table\n", cmd.c_str());
    std::exit(1);
  }
  return rate;
}

// The MuJoCo model of the same dimer at the step its drift speed needs (h = 2e-5 s): CPU time
// per plate period in two runs (issue 36), ms.
constexpr double kMujocoCpuMsPerPeriod[2] = {4.9, 6.1};

double CpuSeconds() {  // this process, every thread, user + system
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The whole `dimerlab sim` of the paper's drift mode: simulate and write the file.
// Each case `repeats` times, alternating the thread counts; the least CPU and the least wall
// time of each (the runs least disturbed by the machine's other load).
void RunFileTable(double periods, int repeats) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "dimerlab_bench_sim_speed";
  std::filesystem::create_directories(dir);
  std::printf("\n`dimerlab sim --ar 3.9 --cycles %.0f` (simulate + write the sim file), best of "
              "%d\n\n", periods, repeats);
  std::printf("| case | compression threads | CPU ms/period | wall ms/period | file MB | "
              "MuJoCo CPU / this CPU |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  for (double fps : {0.0, 2000.0}) {
    double best_cpu[2] = {1e30, 1e30}, best_wall[2] = {1e30, 1e30}, mb = 0;
    for (int r = 0; r < repeats; ++r) {
      for (int threads : {1, 0}) {
        SimRunArgs a;
        a.options.ar = 3.9;
        a.options.cycles = periods;
        a.options.fps = fps;
        a.output = (dir / "sim.h5").string();
        a.force = true;
        a.progress = false;
        a.threads = threads;
        // RunSim's one-line summary goes to /dev/null, not into the table.
        std::fflush(stdout);
        const int saved_stdout = dup(1);
        const int null_fd = open("/dev/null", O_WRONLY);
        dup2(null_fd, 1);
        const double cpu0 = CpuSeconds();
        const auto t0 = std::chrono::steady_clock::now();
        RunSim(a);
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = CpuSeconds() - cpu0;
        std::fflush(stdout);
        dup2(saved_stdout, 1);
        close(saved_stdout);
        close(null_fd);
        best_cpu[threads == 0] = std::min(best_cpu[threads == 0], cpu);
        best_wall[threads == 0] = std::min(best_wall[threads == 0], wall);
        mb = std::filesystem::file_size(a.output) / 1e6;
      }
    }
    for (int every_core : {0, 1}) {
      const double cpu_ms = 1e3 * best_cpu[every_core] / periods;
      std::printf("| %s | %s | %.4f | %.4f | %.2f | %.0f-%.0fx |\n",
                  fps > 0 ? "2000 samples/s + event log" : "events only (--fps 0)",
                  every_core ? "every core" : "1", cpu_ms, 1e3 * best_wall[every_core] / periods,
                  mb, kMujocoCpuMsPerPeriod[0] / cpu_ms, kMujocoCpuMsPerPeriod[1] / cpu_ms);
      std::fflush(stdout);
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  double periods = 20000;
  std::string baseline;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--baseline") && i + 1 < argc) {
      baseline = argv[++i];
    } else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      periods = std::atof(argv[i]);
    }
  }
  const std::vector<Row> rows = Rows(periods);
  if (baseline.empty()) {
    RunTable(rows, true);
    RunFileTable(periods, repeats);
    return 0;
  }
  std::map<std::string, double> best_old, best_new;
  for (int r = 0; r < repeats; ++r) {
    for (const auto& [label, v] : RunBaseline(baseline, periods)) {
      best_old[label] = std::max(best_old[label], v);
    }
    for (const auto& [label, v] : RunTable(rows, false)) {
      best_new[label] = std::max(best_new[label], v);
    }
    std::fprintf(stderr, "run %d of %d done\n", r + 1, repeats);
  }
  std::printf("%.0f periods per case; baseline %s and this build run alternately %d times; best "
              "periods/s of each\n\n", periods, baseline.c_str(), repeats);
  std::printf("| case | baseline periods/s | this build periods/s | speedup |\n");
  std::printf("|---|---:|---:|---:|\n");
  for (const Row& row : rows) {
    const auto it = best_old.find(row.label);
    const double n = best_new[row.label];
    if (it == best_old.end()) {
      std::printf("| %s | - | %.0f | - |\n", row.label.c_str(), n);
    } else {
      std::printf("| %s | %.0f | %.0f | %.2fx |\n", row.label.c_str(), it->second, n,
                  n / it->second);
    }
  }
  return 0;
}
