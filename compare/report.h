#pragma once
// The report of one analysis: summary.md (the headline numbers, the mode timeline, warnings,
// gaps, the comparison with a simulation and the fit, when present) and figures/ (each figure a
// PNG drawn by gnuplot from NAME.dat, with the NAME.gp that drew it, so it can be replotted).
//
// Figures (file stems):
//   heights       the paper's Fig. 2: both tips' heights and the plate over 4 periods of the
//                 settled window, with the plate's fitted sinusoid;
//   positions     Fig. 3: tips' x over the settled window and, below, the resting sphere's slip;
//   slip_phase    the phase-averaged slip with its errors (and the simulation's, if compared);
//   modes         the energy measure and impacts per period, with the mode timeline as bands;
//   sim_vs_track  (comparison only) tip heights of track and simulation, and the residuals;
//   fit_profile   (fit only) the chi2 slice through the optimum of each parameter.
// A figure without data (no resting sphere, no settled window) is not drawn; summary.md says why.
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "compare/comparison.h"
#include "compare/fit.h"

namespace dimer::compare {

// Pixel sizes of the figures (gnuplot pngcairo).
inline constexpr int kFigureWidthPx = 1000;
inline constexpr int kFigureHeightPx = 600;       // one panel
inline constexpr int kPanelsFigureHeightPx = 800;  // positions, modes, sim_vs_track
inline constexpr int kFitPanelHeightPx = 400;      // fit_profile: per row of two panels

// Height of fit_profile.png for `parameters` slices (two panels per row).
int FitProfileHeightPx(int parameters);

struct ReportInputs {
  const Analysis* track = nullptr;        // required: the analysis reported on
  const Comparison* comparison = nullptr; // optional: the track beside a simulation
  const FitResult* fit = nullptr;         // optional: fitted contact coefficients
  std::vector<std::string> commands;      // the command lines that made it (quoted verbatim)
  std::vector<std::string> extra_warnings;  // printed after Analysis::warnings
};

// Writes summary.md and figures/ into `dir`, which exists (the temporary folder of an atomic
// output). Throws std::runtime_error naming the script when gnuplot fails or is missing.
// FitResult::threshold is read as the allowed rise of chi2 above FitResult::chi2 (fit.cc:
// max(1, chi2 / dof)): a parameter's range is where its slice is <= chi2 + threshold.
void WriteReport(const std::string& dir, const ReportInputs& in);

}  // namespace dimer::compare
