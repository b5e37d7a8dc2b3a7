#include "tracking/diagnostics.h"

#include <cstdarg>
#include <cstdio>

namespace dimer::tracking {

std::string FormatDiagnostic(const Diagnostic& d) {
  if (d.severity == Severity::kInputWarning) return "dimerlab: warning: " + d.message;
  std::string line = "dimerlab track: ";
  if (!d.topic.empty()) line += d.topic + ": ";
  if (d.severity == Severity::kWarning) line += "warning: ";
  return line + d.message;
}

std::string Printf(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string out(n > 0 ? size_t(n) : 0, '\0');
  if (n > 0) std::vsnprintf(out.data(), out.size() + 1, format, again);
  va_end(again);
  return out;
}

}  // namespace dimer::tracking
