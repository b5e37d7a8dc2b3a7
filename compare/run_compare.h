#pragma once
// `dimerlab compare TRAJ.h5 -o REPORT` and `dimerlab analyze FRAMES -o REPORT`: the analysis
// chain, the optional simulation beside it and coefficient fit, and the report folder
// (compare.h5, summary.md, figures/, and with --frames an overlay video). The CLI only parses
// into these structs.
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "compare/fit.h"
#include "compare/overlay.h"
#include "compare/simulate.h"
#include "sim/model.h"
#include "tracking/run_track.h"

namespace dimer::compare {

struct CompareArgs {
  std::string input;          // trajectory file (track or sim)
  std::string output;         // report folder to create
  bool force = false;         // replace an existing report folder
  std::string sim_path;       // --sim: a simulation to compare with
  bool simulate = false;      // --simulate: simulate the scene the track shows
  bool fit = false;           // --fit: fit eps, mu_hat, mu_hat_s, mu, mu_s by simulation
  std::string frames_dir;     // --frames: recorded frames for the overlay video
  AnalysisOptions analysis;
  sim::SimOptions scene;      // coefficients (default: the paper's) for --simulate / --fit
  int transient_periods = kDefaultTransientPeriods;  // --transient: simulated before comparing
  FitOptions fit_options;
  OverlayOptions overlay;
  bool quiet = false;         // no progress on stderr
  std::vector<std::string> commands;  // command lines quoted in summary.md
  void Check() const;         // InputError listing every invalid field
};

// Returns the exit code (0). Throws InputError on bad input (nothing is written then).
int RunCompare(const CompareArgs& args);

struct AnalyzeArgs {
  tracking::TrackArgs track;  // input folder and tracking options; output is REPORT/track.h5
  CompareArgs compare;        // output = REPORT; input is set to the track file
};

// track + compare (--simulate unless --no-simulate), all in one report folder.
int RunAnalyze(const AnalyzeArgs& args);

}  // namespace dimer::compare
