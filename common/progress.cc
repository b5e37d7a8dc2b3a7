#include "common/progress.h"

#include <unistd.h>

namespace dimer {

using Clock = std::chrono::steady_clock;

ProgressMeter::ProgressMeter(std::string label, std::string unit, double total, bool enabled)
    : ProgressMeter(std::move(label), std::move(unit), total, enabled, stderr,
                    isatty(STDERR_FILENO) == 1) {}

ProgressMeter::ProgressMeter(std::string label, std::string unit, double total, bool enabled,
                             FILE* out, bool live, double plain_interval_s)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), enabled_(enabled),
      out_(out), live_(live), interval_s_(live ? kLiveIntervalS : plain_interval_s),
      start_(Clock::now()), last_print_(start_) {}

void ProgressMeter::Update(double done) {
  if (!enabled_) return;
  auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_print_).count() < interval_s_) return;
  last_print_ = now;
  Print(done, false);
}

void ProgressMeter::Finish(double done) {
  if (enabled_) Print(done, true);
}

void ProgressMeter::Print(double done, bool final_line) {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  std::string text;
  char buf[256];
  // A total is an estimate for some work (a fit that moves to a lower point profiles again):
  // past it, the count and rate are shown without an ETA.
  if (total_ > 0 && done <= total_) {
    const double eta = rate > 0 ? (total_ - done) / rate : 0.0;
    std::snprintf(buf, sizeof buf, "%s: %.0f/%.0f %s, %.0f %s/s, ", label_.c_str(), done, total_,
                  unit_.c_str(), rate, unit_.c_str());
    text = buf;
    std::snprintf(buf, sizeof buf, final_line ? "%.1f s" : "ETA %.1f s", final_line ? elapsed : eta);
    text += buf;
  } else {
    std::snprintf(buf, sizeof buf, "%s: %.0f %s, %.0f %s/s", label_.c_str(), done, unit_.c_str(),
                  rate, unit_.c_str());
    text = buf;
  }
  if (live_) {
    std::fprintf(out_, "\r%s   %s", text.c_str(), final_line ? "\n" : "");
  } else {
    std::fprintf(out_, "%s\n", text.c_str());
  }
  std::fflush(out_);
}

}  // namespace dimer
