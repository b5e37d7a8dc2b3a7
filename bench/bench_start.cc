// Start-time benchmark: how long a user waits for a `dimerlab` process that does almost nothing,
// measured as a user runs it (fork + exec + dynamic loading + exit), median of many runs.
//   bench_start BUILD_APP_DIR [runs]
// BUILD_APP_DIR holds `dimerlab` and `dimerlab-full`. Rows:
//   dimerlab --version             the light binary (no OpenCV); target < 20 ms
//   dimerlab sim (1 period, no output samples)  a whole tiny simulation, file written
//   dimerlab-full --version        every command linked in one binary (what `dimerlab` was)
//   dimerlab track --help          light binary handing over to dimerlab-full (exec)
// The shared-library count of each binary (ldd) is printed beside, since loading them is what
// the start costs.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace {

// Runs argv with stdout/stderr to /dev/null; wall time in ms, or -1 when it failed.
double RunOnce(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  waitpid(pid, &status, 0);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? ms : -1;
}

int SharedLibraries(const std::string& binary) {
  const std::string cmd = "ldd '" + binary + "' 2>/dev/null | wc -l";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -1;
  int n = -1;
  if (std::fscanf(p, "%d", &n) != 1) n = -1;
  pclose(p);
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_start BUILD_APP_DIR [runs]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int runs = argc > 2 ? std::atoi(argv[2]) : 50;
  const std::string light = dir + "/dimerlab", full = dir + "/dimerlab-full";
  const std::string out =
      (std::filesystem::temp_directory_path() / "dimerlab_bench_start.h5").string();
  struct Row {
    const char* label;
    std::string binary;
    std::vector<std::string> args;
  };
  const std::vector<Row> rows = {
      {"dimerlab --version", light, {light, "--version"}},
      {"dimerlab sim --cycles 1 --fps 0", light,
       {light, "sim", "--cycles", "1", "--fps", "0", "-q", "--force", "-o", out}},
      {"dimerlab-full --version", full, {full, "--version"}},
      {"dimerlab track --help (exec)", full, {light, "track", "--help"}},
  };
  std::printf("%d runs each, median and fastest wall time per process\n\n", runs);
  std::printf("| command | shared libs | median ms | min ms |\n|---|---:|---:|---:|\n");
  for (const Row& row : rows) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
      const double ms = RunOnce(row.args);
      if (ms < 0) {
        std::fprintf(stderr, "bench_start: %s failed\n", row.label);
        return 1;
      }
      t.push_back(ms);
    }
    std::sort(t.begin(), t.end());
    std::printf("| `%s` | %d | %.1f | %.1f |\n", row.label, SharedLibraries(row.binary),
                t[t.size() / 2], t.front());
  }
  std::filesystem::remove(out);
  return 0;
}
