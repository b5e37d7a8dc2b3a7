#include "tracking/plate/plate_step.h"

#include <algorithm>
#include <cmath>

#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// A plate whose top is in view shows two edges of one sign, a few pixels apart: the backdrop to
// the top (far edge) and the top to the front face (near edge), often of about the same size,
// so the strongest flips between them from frame to frame with the noise (POV-Ray mirror_plate:
// 7.7 and 6.3 grey levels, 7 px apart). The upper one is taken: the plate's edge as seen is its
// top boundary, every frame the same (plate_contact.h then finds the contact line below it).
// A step counts as a separate edge at least kSeparateEdgeRows above the strongest (closer, it
// is the same blurred edge) and no further than kPlateBandHalfPx, of the same sign and at least
// kUpperEdgeFraction of its size.
constexpr int kSeparateEdgeRows = 5;
constexpr double kUpperEdgeFraction = 0.5;

}  // namespace

int UpperComparableStep(const std::vector<double>& profile, int k, double step_k, double* size) {
  for (int i = std::max(0, k - kPlateBandHalfPx); i <= k - kSeparateEdgeRows; ++i) {
    const double step = profile[i + 1] - profile[i];
    const bool peak = (i == 0 || std::abs(step) >= std::abs(profile[i] - profile[i - 1])) &&
                      std::abs(step) >= std::abs(profile[i + 2] - profile[i + 1]);
    if (step * step_k > 0 && std::abs(step) >= kUpperEdgeFraction * std::abs(step_k) && peak) {
      *size = std::abs(step);
      return i;
    }
  }
  return k;
}

int PlateStepIndex(const std::vector<double>& profile, double* size) {
  int k = -1;
  double best = 0;
  for (int i = 0; i + 1 < int(profile.size()); ++i) {
    const double step = std::abs(profile[i + 1] - profile[i]);
    if (step > best) {
      best = step;
      k = i;
    }
  }
  *size = best;
  return k < 0 ? k : UpperComparableStep(profile, k, profile[k + 1] - profile[k], size);
}

}  // namespace dimer::tracking
