#pragma once
// Messages that C libraries print on stderr by themselves (libpng's "libpng error: ...",
// libjpeg's "Corrupt JPEG data: ...", a codec's complaints) would otherwise appear beside
// dimerlab's own one-line warnings, in their words and format. While a StderrCapture lives, the
// process's stderr (file descriptor 2) goes into a pipe: every line a library writes there is
// handed to `on_line` (called from the capture's reader thread), which turns it into a dimerlab
// warning or drops it. dimerlab's own messages go to Diagnostics(), the real stderr.
// One capture at a time per process; decoding threads may run freely while it is active.
#include <cstdio>
#include <functional>
#include <string>
#include <thread>

namespace dimer {

class StderrCapture {
 public:
  explicit StderrCapture(std::function<void(const std::string&)> on_line);
  ~StderrCapture();  // restores stderr, then hands over any last line without a newline
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  bool active() const { return saved_fd_ >= 0; }
  // The real stderr: during a capture a stream on the saved descriptor, otherwise stderr.
  static FILE* Diagnostics();
  // Whether the real stderr is a terminal (for live progress lines).
  static bool DiagnosticsIsTerminal();

 private:
  void ReadLines(int fd);
  std::function<void(const std::string&)> on_line_;
  int saved_fd_ = -1;
  std::thread reader_;
};

}  // namespace dimer
