#pragma once
// Simulating the scene a track shows (--simulate, --fit): geometry and drive measured from the
// track (A_r from the tip distance, d from the file, f and Gamma from the plate fit), the
// coefficients given by the user (defaults: the paper's), the release of the observed mode
// (drift: one end lifted; jump, flutter, rest: their own launches), a transient before the
// part that is compared, and the track's sample rate. The simulation is then analysed with the
// same code as the track.
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "sim/model.h"
#include "sim/simulator.h"

namespace dimer::compare {

inline constexpr int kDefaultTransientPeriods = 50;

// `given` carries the coefficients (and anything the user set); its geometry, drive, init,
// duration and rate are replaced by what the track shows. `notes` says what was taken from where.
sim::SimOptions SceneFromTrack(const Analysis& track, const sim::SimOptions& given,
                               int transient_periods, std::vector<std::string>* notes);

// Runs `options` in memory and analyses it; `result` (optional) keeps the raw run.
// `stop` (optional) is polled once per period (Ctrl-C).
Analysis SimulateAndAnalyze(const sim::SimOptions& options, const AnalysisOptions& analysis,
                            const std::string& label, sim::SimResult* result = nullptr,
                            const sim::RunControls& controls = {});

}  // namespace dimer::compare
