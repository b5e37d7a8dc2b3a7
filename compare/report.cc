#include "compare/report.h"

#include <cassert>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "compare/report_parts.h"

namespace dimer::compare {

std::string ModeColour(Mode mode) {
  switch (mode) {
    case Mode::kRest: return "#7f7f7f";
    case Mode::kDrift: return "#2ca02c";
    case Mode::kJump: return "#1f77b4";
    case Mode::kFlutter: return "#ff7f0e";
    case Mode::kIrregular: return "#d62728";
  }
  return "#d62728";
}

void WriteReport(const std::string& dir, const ReportInputs& in) {
  assert(in.track != nullptr && "WriteReport needs the track's analysis");
  namespace fs = std::filesystem;
  const fs::path figures = fs::path(dir) / "figures";
  fs::create_directories(figures);
  const std::vector<FigureOutcome> drawn = WriteFigures(figures.string(), in);
  const std::string path = (fs::path(dir) / "summary.md").string();
  std::ofstream out(path);
  out << SummaryMarkdown(in, drawn);
  if (!out.flush()) throw std::runtime_error(path + ": write failed");
}

}  // namespace dimer::compare
