#include "compare/gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace dimer::compare {
namespace {

namespace fs = std::filesystem;

// gnuplot's stderr is quoted in errors up to this length (its messages are a few lines).
constexpr size_t kMaxQuotedStderr = 2000;

std::string FormatNumber(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string Trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  if (s.size() > kMaxQuotedStderr) s = s.substr(0, kMaxQuotedStderr) + " ...";
  return s;
}

// Reads `fd` to its end.
std::string ReadAll(int fd) {
  std::string out;
  char buf[4096];
  for (;;) {
    const ssize_t k = read(fd, buf, sizeof buf);
    if (k > 0) {
      out.append(buf, static_cast<size_t>(k));
    } else if (k == 0 || errno != EINTR) {
      break;
    }
  }
  return out;
}

}  // namespace

void WriteDataFile(const std::string& path, const std::vector<DataBlock>& blocks) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the figure's data file");
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (b > 0) out << "\n\n";  // gnuplot's block separator (index)
    out << "# " << blocks[b].comment << "\n#";
    for (const auto& c : blocks[b].columns) out << ' ' << c;
    out << '\n';
    for (const auto& row : blocks[b].rows) {
      for (size_t c = 0; c < row.size(); ++c) out << (c ? " " : "") << FormatNumber(row[c]);
      out << '\n';
    }
  }
  if (!out.flush()) throw std::runtime_error(path + ": write failed");
}

std::string RunGnuplot(const std::string& dir, const std::string& script) {
  const std::string where = (fs::path(dir) / script).string();
  int pipe_fd[2];
  if (pipe(pipe_fd) != 0) throw std::runtime_error(where + ": cannot start gnuplot (pipe)");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], 2);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[1]);
  std::string arg0 = "gnuplot", arg1 = script;
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int spawn_err = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fd[1]);
  if (spawn_err != 0) {
    close(pipe_fd[0]);
    throw std::runtime_error(where + ": cannot run gnuplot (" + std::strerror(spawn_err) +
                             "); install it with `apt-get install gnuplot-nox`");
  }
  const std::string err = ReadAll(pipe_fd[0]);
  close(pipe_fd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : "killed by a signal";
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) {
      throw std::runtime_error(where + ": gnuplot not found; install it with "
                               "`apt-get install gnuplot-nox`");
    }
    throw std::runtime_error(where + ": gnuplot failed (" + how + "): " + Trimmed(err));
  }
  return Trimmed(err);
}

std::string DrawFigure(const std::string& dir, const Figure& figure) {
  const fs::path base = fs::path(dir) / figure.name;
  WriteDataFile(base.string() + ".dat", figure.blocks);
  const std::string script = figure.name + ".gp";
  {
    std::ofstream gp((fs::path(dir) / script).string());
    gp << "# " << figure.name << ".png from " << figure.name
       << ".dat (dimerlab report). Replot: gnuplot " << script << "\n"
       << "set terminal pngcairo size " << figure.width_px << "," << figure.height_px
       << " noenhanced font \"sans,11\"\nset encoding utf8\n"
       << "set output " << GnuplotQuote(figure.name + ".png") << "\n"
       << "datafile = " << GnuplotQuote(figure.name + ".dat") << "\n"
       << figure.script;
    if (!figure.script.empty() && figure.script.back() != '\n') gp << '\n';
    gp << "unset output\n";
    if (!gp.flush()) throw std::runtime_error(base.string() + ".gp: write failed");
  }
  const std::string warnings = RunGnuplot(dir, script);
  std::error_code ec;
  if (fs::file_size(base.string() + ".png", ec) == 0 || ec) {
    throw std::runtime_error((fs::path(dir) / script).string() + ": gnuplot wrote no image" +
                             (warnings.empty() ? "" : ": " + warnings));
  }
  return warnings;
}

std::string GnuplotQuote(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace dimer::compare
