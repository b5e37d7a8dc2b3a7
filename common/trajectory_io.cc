#include "common/trajectory_io.h"

#include "common/error.h"

namespace dimer {
namespace {

std::vector<double> Flatten(const std::vector<Eigen::Vector2d>& v) {
  std::vector<double> out;
  out.reserve(2 * v.size());
  for (const auto& p : v) {
    out.push_back(p.x());
    out.push_back(p.y());
  }
  return out;
}

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
  const hsize_t n = traj.size();
  w.WriteDoubles("/t", traj.t, {n}, "s");
  w.SetAttr("/t", "description", "time of each sample");
  w.WriteDoubles("/tips/left", Flatten(traj.tip_left), {n, 2}, "m", "x,z");
  w.SetAttr("/tips/left", "description",
            "centre of the left sphere, lab frame (x right, z up from the plate's mean surface)");
  w.WriteDoubles("/tips/right", Flatten(traj.tip_right), {n, 2}, "m", "x,z");
  w.SetAttr("/tips/right", "description",
            "centre of the right sphere, lab frame (x right, z up from the plate's mean surface)");
  w.WriteDoubles("/plate_z", traj.plate_z, {n}, "m");
  w.SetAttr("/plate_z", "description", "height of the plate surface under the dimer");
  w.WriteDoubles("/theta", traj.theta, {n}, "rad");
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
