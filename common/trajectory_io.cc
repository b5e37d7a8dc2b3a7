#include "common/trajectory_io.h"

#include <algorithm>

#include "common/error.h"

namespace dimer {
namespace {

std::vector<Eigen::Vector2d> ReadPoints(const H5Reader& r, const std::string& name, size_t n) {
  Dims dims;
  std::vector<double> flat = r.ReadDoubles(name, &dims);
  if (dims.size() != 2 || dims[1] != 2 || dims[0] != n) {
    throw InputError(r.path() + ": dataset " + name + " should be " + std::to_string(n) +
                     "x2");
  }
  std::vector<Eigen::Vector2d> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = {flat[2 * i], flat[2 * i + 1]};
  return out;
}

}  // namespace

void WriteTrajectory(H5Writer& w, const Trajectory& traj) {
  traj.CheckConsistent();
  auto values = [](const std::vector<double>& v) -> RowFill {
    return [&v](size_t first, size_t rows, double* out) {
      std::copy(v.begin() + first, v.begin() + first + rows, out);
    };
  };
  auto points = [](const std::vector<Eigen::Vector2d>& v) -> RowFill {
    return [&v](size_t first, size_t rows, double* out) {
      for (size_t i = first; i < first + rows; ++i, out += 2) {
        out[0] = v[i].x();
        out[1] = v[i].y();
      }
    };
  };
  WriteTrajectory(w, traj.size(),
                  {values(traj.t), points(traj.tip_left), points(traj.tip_right),
                   values(traj.plate_z), values(traj.theta)});
}

void WriteTrajectory(H5Writer& w, size_t n, const TrajectoryRows& rows) {
  w.WriteDoubleRows("/t", {n}, rows.t, "s");
  w.SetAttr("/t", "description", "time of each sample");
  w.WriteDoubleRows("/tips/left", {n, 2}, rows.tip_left, "m", "x,z");
  w.SetAttr("/tips/left", "description",
            "centre of the left sphere, lab frame (x right, z up from the plate's mean surface)");
  w.WriteDoubleRows("/tips/right", {n, 2}, rows.tip_right, "m", "x,z");
  w.SetAttr("/tips/right", "description",
            "centre of the right sphere, lab frame (x right, z up from the plate's mean surface)");
  w.WriteDoubleRows("/plate_z", {n}, rows.plate_z, "m");
  w.SetAttr("/plate_z", "description", "height of the plate surface under the dimer");
  w.WriteDoubleRows("/theta", {n}, rows.theta, "rad");
  w.SetAttr("/theta", "description",
            "axis angle from the left to the right sphere, counter-clockwise from +x");
}

Trajectory ReadTrajectory(const H5Reader& r) {
  Trajectory traj;
  traj.t = r.ReadDoubles("/t");
  const size_t n = traj.t.size();
  traj.tip_left = ReadPoints(r, "/tips/left", n);
  traj.tip_right = ReadPoints(r, "/tips/right", n);
  traj.plate_z = r.ReadDoubles("/plate_z");
  traj.theta = r.ReadDoubles("/theta");
  if (traj.plate_z.size() != n || traj.theta.size() != n) {
    throw InputError(r.path() + ": /plate_z and /theta must have as many rows as /t");
  }
  return traj;
}

std::string FileKind(const H5Reader& r) { return r.AttrString("/", "kind").value_or(""); }

}  // namespace dimer
