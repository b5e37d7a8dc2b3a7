#pragma once
// The tracker's notes and warnings (tracking/diagnostics.h) on stderr, one line each, as
// `dimerlab track` and `dimerlab analyze` print them.
#include <string>

#include "tracking/diagnostics.h"

namespace dimer::app {

// Prints each as it comes; under --quiet only those marked shown_when_quiet (warnings), so a
// quiet run with nothing to warn about leaves stderr empty.
tracking::Diagnostics::Sink PrintTrackDiagnostics(bool quiet);

// A subcommand's closing one-line summary, on stdout (render, track, analyze).
void PrintSummaryLine(const std::string& line);

}  // namespace dimer::app
