#include "tracking/plate/plate_under_dimer.h"

#include <cmath>

namespace dimer::tracking {

int CandidateTheDimerStandsOn(const std::vector<PlateCandidate>& candidates,
                              double lowest_point_row) {
  if (!std::isfinite(lowest_point_row)) return -1;
  int best = -1;
  double nearest = kPlateMeetPx;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const double d = std::abs(candidates[i].row - lowest_point_row);
    if (d <= nearest) {
      nearest = d;
      best = int(i);
    }
  }
  return best;
}

}  // namespace dimer::tracking
