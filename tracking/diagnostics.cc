#include "tracking/diagnostics.h"

namespace dimer::tracking {

std::string FormatDiagnostic(const Diagnostic& d) {
  if (d.severity == Severity::kInputWarning) return "dimerlab: warning: " + d.message;
  std::string line = "dimerlab track: ";
  if (!d.topic.empty()) line += d.topic + ": ";
  if (d.severity == Severity::kWarning) line += "warning: ";
  return line + d.message;
}

}  // namespace dimer::tracking
