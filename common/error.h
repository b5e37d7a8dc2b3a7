#pragma once
// Error tiers (docs/DESIGN.md, "Errors and exit codes"):
//  - UsageError: a bad command line (an option's value out of range, options that contradict
//    each other). The CLI prints it as one line and exits 2, like CLI11's own parse errors.
//  - InputError: bad input the user cannot fix on the command line alone (a missing, corrupt or
//    wrong file; an output that cannot be written). One line "dimerlab: error: <message>",
//    exit 1. Messages name the file or option, the value, and what was expected.
//  - Broken invariants are assert()s; expected numerical outcomes are statuses in result structs.
#include <stdexcept>
#include <string>

namespace dimer {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

// A bad option value: a kind of InputError (callers that catch InputError still catch it), kept
// apart so that main() can give usage errors their own exit code.
class UsageError : public InputError {
 public:
  explicit UsageError(const std::string& what) : InputError(what) {}
};

// Raised when the user interrupts (Ctrl-C) a long computation; partial output is kept valid.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace dimer
