#pragma once
// Progress on stderr for long work: done/total, rate (items/s) and ETA. On a terminal, a live
// line redrawn in place (carriage return) a few times per second; anywhere else (a log file, a
// pipe, CI), one plain line every few seconds and a final one, never a carriage return.
// Silent when disabled (tests, -q/--quiet).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace dimer {

class ProgressMeter {
 public:
  // `unit` names what is counted ("frames", "periods"); total <= 0 means unknown. Writes to
  // stderr, live when stderr is a terminal.
  ProgressMeter(std::string label, std::string unit, double total, bool enabled);
  // The same, to `out`, live or plain as asked, a plain line at most every `plain_interval_s`.
  ProgressMeter(std::string label, std::string unit, double total, bool enabled, FILE* out,
                bool live, double plain_interval_s = kPlainIntervalS);
  void Update(double done);
  void Finish(double done);

  static constexpr double kLiveIntervalS = 0.25;   // redraws of the live line, s
  static constexpr double kPlainIntervalS = 5.0;   // plain lines in a log, s

 private:
  void Print(double done, bool final_line);
  std::string label_, unit_;
  double total_;
  bool enabled_;
  FILE* out_;
  bool live_;
  double interval_s_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace dimer
