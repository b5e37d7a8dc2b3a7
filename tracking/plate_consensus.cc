#include "tracking/plate_consensus.h"

#include <algorithm>
#include <cmath>

#include "common/median.h"
#include "tracking/plate/plate_edge.h"
#include "tracking/plate/plate_step.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {

size_t KeepOnePlate(double radius_px, std::vector<LearningSample>* samples) {
  std::vector<double> rows;
  for (const LearningSample& s : *samples) {
    if (std::isfinite(s.plate_row)) rows.push_back(s.plate_row);
  }
  if (rows.size() < kPlateConsensusMinFrames) return 0;
  const double median = QuantileOf(rows, 0.5);
  const double iqr = QuantileOf(rows, 0.75) - QuantileOf(rows, 0.25);
  const double tolerance = std::max(double(kPlateCandidateSeparationRows), kPlateConsensusIqr * iqr);
  const double clear = (std::isfinite(radius_px) ? radius_px : 0.0) + kPlateSphereClearPx;
  size_t moved = 0;
  for (LearningSample& s : *samples) {
    if (!std::isfinite(s.plate_row) || std::abs(s.plate_row - median) <= tolerance) continue;
    std::vector<std::pair<double, double>> excluded;
    for (int k = 0; k < 2; ++k) {
      if (s.found[k]) excluded.emplace_back(s.centre[k].x() - clear, s.centre[k].x() + clear);
    }
    const double row = RefinePlateRow(s.image, median, excluded, kPlatePsfSigmaPx, nullptr,
                                      s.plate_slope, s.plate_col);
    if (std::isfinite(row) && std::abs(row - median) <= tolerance) {
      s.plate_row = row;
      ++moved;
    }
  }
  return moved;
}

}  // namespace dimer::tracking
