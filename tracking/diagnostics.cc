#include "tracking/diagnostics.h"

namespace dimer::tracking {

std::string FormatDiagnostic(const Diagnostic& d) {
  std::string line = "dimerlab track: ";
  if (d.severity == Severity::kInputWarning) return line + "warning: " + d.message;
  if (!d.topic.empty()) line += d.topic + ": ";
  if (d.severity == Severity::kWarning) line += "warning: ";
  return line + d.message;
}

}  // namespace dimer::tracking
