#pragma once
// Plate periods of a sampled trajectory and the modes over them, with the project's one
// definition of the modes (common/modes.h).
//
// Impacts count as the simulator counts them: approaching faster than kSignificantImpactRel g/f
// (common/modes.h). An approach too short to fit (a micro-bounce of a few frames) is judged by
// the fastest it can have been, from the height it fell (Impact::speed_bound); unknown, it
// counts. Counting every unfitted approach made 5 impacts a period of the resting end where
// the simulator counts 1 on the same file, A_r 3.9 (SimModes.*, ImpactCount.*).
// Periods start at the first frame and last 1/f each (a sim file's periods start at its
// t_start, its first sample, so compare's windows are the simulator's). Per period: impacts and
// rest time per sphere (contacts.h), the CM's lab x at its start (interpolated to the exact
// boundary by a cubic through the 4 nearest frames), and the paper's energy measure: the sum of
// the two spheres' highest elevation above the plate in the period, in units of g T^2.
// A period with more than 5 % of its frames missing is incomplete: it is listed but no window
// that contains it is labelled.
#include <array>
#include <vector>

#include "common/modes.h"
#include "compare/contacts.h"
#include "compare/plate_fit.h"
#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr double kMaxMissingInPeriod = 0.05;

struct PeriodRow {
  double t_start = 0;                      // s
  PeriodStats stats;                       // impacts, rest_time, x_start (common/modes.h)
  std::array<double, 2> elevation_m{};     // highest gap above the contact level, m
  double energy_gT2 = kNaN;                // sum of the two elevations / (g T^2)
  double missing_fraction = 0;             // frames without both tips
  bool complete = true;
};

struct ModeWindow {
  int first = 0, count = 0;  // periods
  double t_start = 0, t_end = 0;
  ModeSummary summary;
};

struct Periods {
  double period_s = 0;
  std::vector<PeriodRow> rows;      // whole periods only
  double x_end = kNaN;              // CM x at the end of the last whole period
  std::vector<ModeWindow> timeline; // consecutive windows of `window` complete periods
  ModeWindow settled;               // the settled window (common/modes.h SettledWindow)
};

// Whether `imp` counts toward the modes (above).
bool SignificantImpact(const Impact& imp, double period_s);

Periods AnalyzePeriods(const SampledRun& run, const PlateDrive& plate, const Contacts& contacts,
                       int window_periods);

// CM lab x at time t, interpolated (cubic through the 4 nearest frames; exact on a frame).
double CentreXAt(const SampledRun& run, double t);

}  // namespace dimer::compare
