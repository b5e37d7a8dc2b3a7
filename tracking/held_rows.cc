#include "tracking/held_rows.h"

#include <algorithm>
#include <cmath>

#include "common/median.h"

namespace dimer::tracking {

HeldRows FindHeldRows(const std::vector<double>& rows, const std::vector<double>& plate,
                      double gravity_px) {
  HeldRows h;
  if (!(gravity_px > 0) || rows.size() != plate.size()) return h;
  // A free fall from rest at the window's middle drops kHeldFallPx by either end.
  const size_t window = size_t(std::ceil(2.0 * std::sqrt(2.0 * kHeldFallPx / gravity_px))) + 1;
  if (window > rows.size()) return h;
  h.window_frames = window;
  double least = std::numeric_limits<double>::infinity();
  // Windows half overlapping: every frame is in two, but the first and last half window's.
  for (size_t first = 0; first + window <= rows.size(); first += window / 2) {
    double row_lo = INFINITY, row_hi = -INFINITY;
    std::vector<double> edge;
    bool complete = true;
    for (size_t i = first; i < first + window && complete; ++i) {
      complete = std::isfinite(rows[i]) && std::isfinite(plate[i]);
      row_lo = std::min(row_lo, rows[i]), row_hi = std::max(row_hi, rows[i]);
      edge.push_back(plate[i]);
    }
    if (!complete) continue;
    // The plate's excursion between its kHeldPlateQuantile and 1 - that: a frame where another
    // edge was taken for the plate does not stretch it.
    const double row_range = row_hi - row_lo;
    const double plate_range =
        QuantileOf(edge, 1.0 - kHeldPlateQuantile) - QuantileOf(edge, kHeldPlateQuantile);
    if (plate_range < kHeldMinPlateExcursionPx) continue;
    ++h.windows;
    if (row_range >= kHeldFraction * std::min(plate_range, kHeldFallPx)) continue;
    ++h.held;
    if (row_range / plate_range < least) {
      least = row_range / plate_range;
      h.first = first;
      h.row_range = row_range;
      h.plate_range = plate_range;
    }
  }
  return h;
}

}  // namespace dimer::tracking
