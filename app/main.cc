// dimerlab: the binary users run. The commands that need only the simulator (`sim`, `sweep`,
// `merge`, and `--version`) run here, in a process that loads no OpenCV: OpenCV's video and
// image back-ends pull in ~200 shared libraries and cost ~90 ms at every start, which a script
// or a Slurm array calling `dimerlab sim` many times would pay each time (docs/BENCHMARKS.md, bench_start). Every other
// command line (render, track, compare, analyze, --help, mistakes) is handed unchanged to
// dimerlab-full by exec: same process, same arguments, same exit code, one set of messages.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <string>
#include <string_view>

#include "app/cli_main.h"
#include "app/commands.h"
#include "app/exit_codes.h"

namespace {

// The command lines this binary runs itself.
bool RunsHere(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view first = argv[1];
  if (first == "--version") return argc == 2;
  return first == "sim" || first == "sweep" || first == "merge";
}

// The folder this executable lives in (from /proc, so it works whatever PATH found it by).
std::string ExecutableDir() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) return ".";
  std::string path(buf, static_cast<size_t>(n));
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// dimerlab-full beside this binary (the build tree) or in PREFIX/libexec/dimerlab (installed).
int ExecFull(char** argv) {
  const std::string dir = ExecutableDir();
  const std::string candidates[] = {dir + "/dimerlab-full", dir + "/../libexec/dimerlab/dimerlab-full"};
  for (const std::string& path : candidates) {
    if (access(path.c_str(), X_OK) == 0) {
      execv(path.c_str(), argv);
      return dimer::app::ReportError(dimer::app::kExitFailure,
                                     "cannot run " + path + ": " + std::strerror(errno));
    }
  }
  return dimer::app::ReportError(
      dimer::app::kExitFailure,
      "dimerlab-full (render, track, compare, analyze) is not installed beside " + dir +
          "/dimerlab; reinstall dimerlab (./dimerlab.sh install)");
}

}  // namespace

int main(int argc, char** argv) {
  if (!RunsHere(argc, argv)) return ExecFull(argv);
  return dimer::app::RunCli(argc, argv, [](CLI::App& app) {
    dimer::app::RegisterSim(app);
    dimer::app::RegisterSweep(app);
    dimer::app::RegisterMerge(app);
  });
}
