#pragma once
// The exit codes of the README's table (docs/DESIGN.md, "Errors and exit codes"), and the one
// way errors reach the user: one line "dimerlab: error: <message>" on stderr.
#include <cstdio>
#include <string>

namespace dimer::app {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;       // bad input (files) or a failed run
inline constexpr int kExitUsage = 2;         // unknown subcommand or option, bad value
inline constexpr int kExitInterrupted = 130;  // Ctrl-C: partial output complete and valid

// Prints the one-line error and returns `code`, for `return ReportError(...)` in main().
inline int ReportError(int code, const std::string& message) {
  std::fprintf(stderr, "dimerlab: error: %s\n", message.c_str());
  return code;
}

}  // namespace dimer::app
