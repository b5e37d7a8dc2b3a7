#include "common/stderr_capture.h"

#include <unistd.h>

#include <atomic>

namespace dimer {
namespace {

// The stream on the real stderr while a capture is active (one capture at a time).
std::atomic<FILE*> g_diagnostics{nullptr};
std::atomic<int> g_real_fd{-1};

}  // namespace

StderrCapture::StderrCapture(std::function<void(const std::string&)> on_line)
    : on_line_(std::move(on_line)) {
  if (g_diagnostics.load() != nullptr) return;  // nested: the outer capture already holds fd 2
  int fds[2];
  if (pipe(fds) != 0) return;  // no capture: library messages stay as they are
  std::fflush(stderr);
  saved_fd_ = dup(STDERR_FILENO);
  FILE* diagnostics = saved_fd_ >= 0 ? fdopen(dup(saved_fd_), "w") : nullptr;
  if (!diagnostics || dup2(fds[1], STDERR_FILENO) < 0) {
    if (diagnostics) std::fclose(diagnostics);
    if (saved_fd_ >= 0) close(saved_fd_);
    saved_fd_ = -1;
    close(fds[0]);
    close(fds[1]);
    return;
  }
  close(fds[1]);  // fd 2 is now the pipe's only write end
  std::setvbuf(diagnostics, nullptr, _IONBF, 0);
  g_real_fd = saved_fd_;
  g_diagnostics = diagnostics;
  reader_ = std::thread([this, fd = fds[0]] { ReadLines(fd); });
}

StderrCapture::~StderrCapture() {
  if (saved_fd_ < 0) return;
  std::fflush(stderr);
  dup2(saved_fd_, STDERR_FILENO);  // closes the pipe's write end: the reader sees end of file
  reader_.join();
  FILE* diagnostics = g_diagnostics.exchange(nullptr);
  g_real_fd = -1;
  std::fclose(diagnostics);
  close(saved_fd_);
}

void StderrCapture::ReadLines(int fd) {
  std::string pending;
  char buf[4096];
  for (ssize_t n; (n = read(fd, buf, sizeof buf)) > 0;) {
    pending.append(buf, static_cast<size_t>(n));
    for (size_t eol; (eol = pending.find('\n')) != std::string::npos;) {
      std::string line = pending.substr(0, eol);
      pending.erase(0, eol + 1);
      if (!line.empty()) on_line_(line);
    }
  }
  if (!pending.empty()) on_line_(pending);
  close(fd);
}

FILE* StderrCapture::Diagnostics() {
  FILE* f = g_diagnostics.load();
  return f ? f : stderr;
}

bool StderrCapture::DiagnosticsIsTerminal() {
  const int fd = g_real_fd.load();
  return isatty(fd >= 0 ? fd : STDERR_FILENO) == 1;
}

}  // namespace dimer
