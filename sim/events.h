#pragma once
// The event log of a run (docs/FORMATS.md, /events/*) and per-period statistics used to say which
// mode a run settled in.
#include <cstdint>
#include <string>
#include <vector>

#include "common/modes.h"
#include "sim/state.h"

namespace dimer::sim {

enum class EventKind { kImpact, kDoubleImpact, kCollapse, kLiftoff, kStick, kSlip, kPainleve };
std::string ToString(EventKind k);

struct EventRecord {
  double t;            // absolute time, s
  double t_local;      // the same instant in the simulator's re-based time (same plate phase):
                       // use it to convert before/after to the lab frame without round-off
  EventKind kind;
  int8_t sphere;       // 0 left, 1 right, 2 both
  std::string detail;  // impacts: continuous_slide | slip_stick | slip_reversal (per sphere)
  State before, after; // plate frame (converted to lab when written)
};

// Per-period statistics (impacts faster than the collapse speed, time in persistent contact)
// use the project's one PeriodStats (common/modes.h).
using dimer::PeriodStats;

}  // namespace dimer::sim
