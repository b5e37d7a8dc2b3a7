#pragma once
// The analysis of one trajectory, tracked or simulated, as a chain of steps each returning a
// small table (plate -> contacts -> free fall -> periods and modes -> drift -> slip). Tracks and
// sim files go through the same code; a sim file's drive is read from its attributes (exact),
// a track's is fitted.
#include <array>
#include <string>
#include <vector>

#include "compare/contacts.h"
#include "compare/free_fall.h"
#include "compare/outliers.h"
#include "compare/periods.h"
#include "compare/plate_fit.h"
#include "compare/sampled_run.h"
#include "compare/slip.h"

namespace dimer::compare {

struct AnalysisOptions {
  double freq_hz = kNaN;     // --freq: the drive's frequency when no plate is visible (also a fit seed), Hz
  double gamma = kNaN;       // --gamma: the drive's Gamma when no plate is visible
  int window_periods = 10;   // --mode-window: periods per window of the mode timeline
  int phase_bins = 40;       // --phase-bins: bins of the phase-averaged slip
  double travel_mm = 55.0;   // --travel-mm: the paper's travel distance for its drift timing, mm
  // To see a simulation through a camera's eyes (the fit): contact thresholds at least these
  // (per sphere, m; NaN: from the data) and this slip filter half-width (frames; 0: from the data).
  std::array<double, 2> min_contact_threshold_m{kNaN, kNaN};
  int slip_half_window = 0;
  // Every invalid field at once ("--flag: value: expected ..."); empty if valid.
  std::vector<std::string> Check() const;
};

struct Drift {
  int bouncing_sphere = -1;
  double speed = kNaN, speed_err = kNaN;    // m/s, positive toward the bouncing end
  double scaled = kNaN, scaled_err = kNaN;  // <u> f / g
  int periods = 0;                          // whole periods averaged
  // The paper's measure: the time to travel travel_mm from the settled window's start.
  double travel_mm = kNaN, travel_time_s = kNaN, travel_speed = kNaN;
  std::string travel_note;
};

struct Analysis {
  SampledRun run;                     // with tracking outliers removed (outliers.h)
  std::vector<Outlier> outliers;
  AnalysisOptions options;
  PlateDrive plate;
  Contacts contacts;
  FreeFall free_fall;
  Periods periods;
  Drift drift;
  SlipResult slip;
  std::vector<std::string> warnings;  // also printed in summary.md
};

// InputError (one line naming the file) when the run cannot be analysed: no visible plate and
// no --freq/--gamma, or shorter than 2 plate periods.
Analysis Analyze(const SampledRun& run, const AnalysisOptions& options);

// `base` with a track's eyes: each sphere's contact threshold at least the track's and its slip
// filter, so that a simulation analysed with them is read over the frames and at the noise the
// camera allowed (compare --sim and --simulate, and every trial of the fit).
AnalysisOptions SeenAsTrack(const Analysis& track, AnalysisOptions base);

}  // namespace dimer::compare
