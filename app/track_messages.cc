#include "app/track_messages.h"

#include <cstdio>
#include <string>

namespace dimer::app {

tracking::Diagnostics::Sink PrintTrackDiagnostics(bool quiet) {
  return [quiet](const tracking::Diagnostic& d) {
    if (quiet && !d.shown_when_quiet) return;
    std::fputs((tracking::FormatDiagnostic(d) + "\n").c_str(), stderr);
  };
}

void PrintSummaryLine(const std::string& line) { std::printf("%s\n", line.c_str()); }

}  // namespace dimer::app
