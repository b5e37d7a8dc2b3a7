#pragma once
// Blanks (space, tab, CR) cut from both ends of a line: the one rule every `name = value` file
// of the project (scene files, sweep specs) reads its lines by.
#include <string>

namespace dimer {

inline std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

}  // namespace dimer
