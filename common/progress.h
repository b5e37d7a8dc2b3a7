#pragma once
// Progress on stderr for long work: done/total, rate (items/s) and ETA, redrawn at most a few
// times per second. Silent when disabled (tests, --quiet) or when stderr is not wanted.
#include <chrono>
#include <cstdint>
#include <string>

namespace dimer {

class ProgressMeter {
 public:
  // `unit` names what is counted ("frames", "periods"); total <= 0 means unknown.
  ProgressMeter(std::string label, std::string unit, double total, bool enabled);
  void Update(double done);
  void Finish(double done);

 private:
  void Print(double done, bool final_line);
  std::string label_, unit_;
  double total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace dimer
