#include "common/progress.h"

#include <cstdio>

namespace dimer {

using Clock = std::chrono::steady_clock;

ProgressMeter::ProgressMeter(std::string label, std::string unit, double total, bool enabled)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), enabled_(enabled),
      start_(Clock::now()), last_print_(start_) {}

void ProgressMeter::Update(double done) {
  if (!enabled_) return;
  auto now = Clock::now();
  if (now - last_print_ < std::chrono::milliseconds(250)) return;
  last_print_ = now;
  Print(done, false);
}

void ProgressMeter::Finish(double done) {
  if (enabled_) Print(done, true);
}

void ProgressMeter::Print(double done, bool final_line) {
  double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  double rate = elapsed > 0 ? done / elapsed : 0.0;
  if (total_ > 0) {
    double eta = rate > 0 ? (total_ - done) / rate : 0.0;
    std::fprintf(stderr, "\r%s: %.0f/%.0f %s, %.0f %s/s, ETA %.1f s   ", label_.c_str(), done,
                 total_, unit_.c_str(), rate, unit_.c_str(), final_line ? 0.0 : eta);
  } else {
    std::fprintf(stderr, "\r%s: %.0f %s, %.0f %s/s   ", label_.c_str(), done, unit_.c_str(), rate,
                 unit_.c_str());
  }
  if (final_line) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace dimer
