#pragma once
// The sim file's datasets of samples (the trajectory and /state), made row by row from the
// samples' times and lab states: WriteSimFile writes them, and RunSim compresses their whole
// chunks while the simulation still runs (common/h5_chunks_ahead.h). One definition for both,
// so both give the same bytes (SimFile.RunSimGivesHdf5sBytes).
#include <cstddef>

#include "common/h5_chunks_ahead.h"
#include "common/trajectory_io.h"
#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

// Where the samples are (SimResult::t and ::lab, or RunControls::on_samples' arrays). The fills
// read it when they run, so it may be set after they are made.
struct SampleArrays {
  const double* t = nullptr;
  const State* lab = nullptr;
};

// The trajectory of docs/FORMATS.md: times, sphere centres, plate height under the CM, angle.
TrajectoryRows SampleTrajectoryRows(const Model& m, const SampleArrays* s);
// /state: the lab state x, z, theta, u, v, omega.
RowFill StateRowFill(const SampleArrays* s);
// A lab state as a row of /state (and of /events/before and /events/after).
inline constexpr size_t kLabStateColumns = 6;
void LabStateRow(const State& q, double* out);

// Every sample dataset above, for `ahead` (names as the file has them).
void AddSampleDatasets(ChunksAhead* ahead, const Model& m, const SampleArrays* s);

}  // namespace dimer::sim
