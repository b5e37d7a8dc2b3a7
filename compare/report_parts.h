#pragma once
// Internal to the report (report*.cc) and the overlay: the figures and the summary are written
// by separate files, the summary listing what the figures step drew or skipped.
#include <string>
#include <vector>

#include "common/format.h"
#include "compare/gnuplot.h"
#include "compare/report.h"

namespace dimer::compare {

struct FigureOutcome {
  std::string name;      // file stem (figures/NAME.png)
  std::string caption;   // what it shows, for summary.md
  bool drawn = false;
  std::string note;      // why it was not drawn, or gnuplot's warnings
};

// The colour of each mode in figures (bands in modes.png), as gnuplot's "#rrggbb".
std::string ModeColour(Mode mode);

// Periods shown in the detailed figures (heights, sim_vs_track), as in the paper's Fig. 2.
inline constexpr int kDetailPeriods = 4;

// Frames [*first, *last) of `run` whose time lies in [t_begin, t_end).
void FramesIn(const SampledRun& run, double t_begin, double t_end, size_t* first, size_t* last);

// gnuplot clauses joined into one command, one clause per continued line.
inline std::string Join(const std::vector<std::string>& clauses) {
  std::string out;
  for (size_t k = 0; k < clauses.size(); ++k) out += (k ? ", \\\n     " : "") + clauses[k];
  return out + "\n";
}

// True when some entry of `v` is finite.
bool AnyFinite(const std::vector<double>& v);

// A figure ready to draw (`ready`), or the reason it is not (outcome.note).
struct PlannedFigure {
  FigureOutcome outcome;
  Figure figure;
  bool ready = false;
};

// The figures of a comparison and of a fit (report_compare_figures.cc).
PlannedFigure PlanSimVsTrack(const Analysis& track, const Comparison& comparison);
PlannedFigure PlanFitProfile(const FitResult& fit);

// Draws every figure that has data into `figures_dir` (which exists).
std::vector<FigureOutcome> WriteFigures(const std::string& figures_dir, const ReportInputs& in);

// summary.md's text.
std::string SummaryMarkdown(const ReportInputs& in, const std::vector<FigureOutcome>& figures);

}  // namespace dimer::compare
