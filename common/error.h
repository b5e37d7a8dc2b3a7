#pragma once
// Error tiers (see STYLE.md):
//  - InputError: bad input from the user (file, option, value). The CLI prints it as one line
//    "dimerlab: error: <message>" and exits non-zero. Messages name the file or option, the value,
//    and what was expected.
//  - Broken invariants are assert()s; expected numerical outcomes are statuses in result structs.
#include <stdexcept>
#include <string>

namespace dimer {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

// Raised when the user interrupts (Ctrl-C) a long computation; partial output is kept valid.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace dimer
