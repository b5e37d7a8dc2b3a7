#pragma once
// A sweep point's result read back from a journal is checked like a fresh one: a record whose
// checksum holds can still carry values no run produces (an altered or buggy writer), and a
// resumed sweep must never write them into its file. The checks are the ranges every fresh
// result satisfies for its spec, and the redundancy between its fields.
#include <string>

#include "sim/sweep_point.h"
#include "sim/sweep_spec.h"

namespace dimer::sim {

// Empty when `p` could be a result of point p.index of `spec`; otherwise what is wrong with it,
// as a short phrase ("drift_scaled is not drift_speed f/g").
std::string PointResultProblem(const PointResult& p, const SweepSpec& spec);

}  // namespace dimer::sim
