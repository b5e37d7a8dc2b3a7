#pragma once
// Tracking outliers: a tip position far from the median of its 9-frame neighbourhood (more
// than max(10 sigma, 0.05 d) in x or z) is a tracker failure, not motion. At 2000 frames/s the
// sharpest real feature, the kink of an impact, moves the median by about two frames of travel
// (~0.02 d at the paper's speeds), so the bound leaves real motion alone. Rejected tips become
// NaN (a gap) and are listed, so the analysis runs where the track is good.
#include <vector>

#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr int kOutlierHalfWindow = 4;
inline constexpr double kOutlierSigmas = 10.0;
inline constexpr double kOutlierRel = 0.05;  // of d

struct Outlier {
  size_t frame = 0;
  int sphere = 0;
  double deviation_m = 0;
};

// Marks outliers NaN in `run` (and recomputes its gaps); returns them in frame order.
std::vector<Outlier> RejectOutliers(SampledRun* run);

}  // namespace dimer::compare
