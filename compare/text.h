#pragma once
// Numbers in messages (errors, warnings, notes): a few significant digits, no trailing zeros.
#include <sstream>
#include <string>

namespace dimer::compare {

inline std::string Num(double v, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace dimer::compare
