#pragma once
// Reading and writing the shared trajectory datasets (/t, /tips/left, /tips/right, /plate_z,
// /theta) of docs/FORMATS.md, each with its `units` attribute.
#include <string>

#include "common/h5_file.h"
#include "common/trajectory.h"

namespace dimer {

void WriteTrajectory(H5Writer& w, const Trajectory& traj);
// The same datasets of n samples from rows made on demand (H5Writer::WriteDoubleRows): one value
// per row for t, plate_z and theta, two (x, z) for the tips.
struct TrajectoryRows {
  RowFill t, tip_left, tip_right, plate_z, theta;
};
void WriteTrajectory(H5Writer& w, size_t n, const TrajectoryRows& rows);
// Throws InputError naming the file if a dataset is missing or the lengths disagree.
Trajectory ReadTrajectory(const H5Reader& r);
// The file's `kind` root attribute ("sim", "track", ...), or "" if absent.
std::string FileKind(const H5Reader& r);

}  // namespace dimer
