#pragma once
// printf into a std::string (GCC 12 has no std::format): the numbers in messages, reports and
// figures, whose formats are part of what users read.
#include <string>

namespace dimer {

std::string Format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace dimer
