#include "app/track_messages.h"

#include <cstdio>
#include <string>

#include "common/stderr_capture.h"

namespace dimer::app {

tracking::Diagnostics::Sink PrintTrackDiagnostics(bool quiet) {
  return [quiet](const tracking::Diagnostic& d) {
    if (quiet && !d.shown_when_quiet) return;
    // During a run, stderr may be the decoders' capture (common/stderr_capture.h): the real one.
    FILE* out = StderrCapture::Diagnostics();
    std::fputs(((d.during_progress ? "\n" : "") + tracking::FormatDiagnostic(d) + "\n").c_str(),
               out);
  };
}

void PrintSummaryLine(const std::string& line) { std::printf("%s\n", line.c_str()); }

}  // namespace dimer::app
