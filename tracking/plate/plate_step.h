#pragma once
// The plate's step in a profile of rows (each row's level across the plate's columns): where the
// level changes most, read as the plate's top boundary. plate_edge.h finds the plate with it,
// clipped_edge.h fits an over-exposed plate's edge around it.
#include <vector>

namespace dimer::tracking {

// Rows read on each side of the plate's step: the coverage sum reads the levels this far off.
inline constexpr int kPlateBracketRows = 3;

// Index i of the plate's step in `profile`, between profile[i] and profile[i + 1] (-1 if flat),
// and its size: the strongest step, or the upper of two comparable ones (a plate whose top is in
// view shows its far and near edges; UpperComparableStep).
int PlateStepIndex(const std::vector<double>& profile, double* size);

// The uppermost separate edge above step `k` (the strongest, of signed size `step_k`), or k.
int UpperComparableStep(const std::vector<double>& profile, int k, double step_k, double* size);

}  // namespace dimer::tracking
