#pragma once
// DIMER_CHECK(condition, what): an invariant a library's public entry point relies on (sizes
// that agree, a frame that holds pixels, a positive length), checked in every build, Release
// included: each is a comparison or two beside the work behind the entry point. A failure is
// the caller's bug, not bad input (bad input is an InputError with its own message, checked
// first: common/error.h): it throws InvariantError naming what broke, the condition and where,
// which the CLI reports as an error (exit code 1) and a test can expect.
#include <stdexcept>
#include <string>

namespace dimer {

class InvariantError : public std::logic_error {
 public:
  explicit InvariantError(const std::string& what) : std::logic_error(what) {}
};

[[noreturn]] inline void FailCheck(const char* condition, const char* what, const char* file,
                                   int line) {
  throw InvariantError(std::string("internal error: ") + what + " (" + condition + " failed at " +
                       file + ":" + std::to_string(line) + ")");
}

}  // namespace dimer

#define DIMER_CHECK(condition, what)                                            \
  do {                                                                          \
    if (!(condition)) ::dimer::FailCheck(#condition, (what), __FILE__, __LINE__); \
  } while (false)
