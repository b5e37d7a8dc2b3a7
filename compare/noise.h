#pragma once
// Position noise estimated from the data itself (trackpy's habit: never ask the user for it).
// A smooth path has third differences of order z''' dt^3, tiny at 2000 frames/s, while white
// noise of standard deviation sigma gives third differences of variance 20 sigma^2. The median
// absolute third difference is robust to the few that straddle an impact, so
//   sigma = 1.4826 median|d3| / sqrt(20).
#include <vector>

namespace dimer::compare {

// sigma of `v` (NaN entries and any difference touching one are left out); 0 if fewer than
// 8 usable differences.
double NoiseSigma(const std::vector<double>& v);

}  // namespace dimer::compare
