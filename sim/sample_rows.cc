#include "sim/sample_rows.h"

#include "sim/reference_frames.h"

namespace dimer::sim {

TrajectoryRows SampleTrajectoryRows(const Model& m, const SampleArrays* s) {
  auto tip = [&m, s](int sphere) -> RowFill {
    return [&m, s, sphere](size_t first, size_t rows, double* out) {
      for (size_t i = first; i < first + rows; ++i, out += 2) {
        const Eigen::Vector2d p = TipLab(m, s->lab[i], sphere);
        out[0] = p.x();
        out[1] = p.y();
      }
    };
  };
  TrajectoryRows r;
  r.t = [s](size_t first, size_t rows, double* out) {
    for (size_t i = first; i < first + rows; ++i) *out++ = s->t[i];
  };
  r.tip_left = tip(kLeft);
  r.tip_right = tip(kRight);
  r.plate_z = [&m, s](size_t first, size_t rows, double* out) {
    for (size_t i = first; i < first + rows; ++i) *out++ = PlateSurfaceZ(m, s->t[i], s->lab[i].x);
  };
  r.theta = [s](size_t first, size_t rows, double* out) {
    for (size_t i = first; i < first + rows; ++i) *out++ = s->lab[i].th;
  };
  return r;
}

void LabStateRow(const State& q, double* out) {
  out[0] = q.x, out[1] = q.z, out[2] = q.th, out[3] = q.u, out[4] = q.v, out[5] = q.w;
}

RowFill StateRowFill(const SampleArrays* s) {
  return [s](size_t first, size_t rows, double* out) {
    for (size_t i = first; i < first + rows; ++i, out += kLabStateColumns) {
      LabStateRow(s->lab[i], out);
    }
  };
}

void AddSampleDatasets(ChunksAhead* ahead, const Model& m, const SampleArrays* s) {
  const TrajectoryRows r = SampleTrajectoryRows(m, s);
  ahead->AddDoubleRows("/t", 1, r.t);
  ahead->AddDoubleRows("/tips/left", 2, r.tip_left);
  ahead->AddDoubleRows("/tips/right", 2, r.tip_right);
  ahead->AddDoubleRows("/plate_z", 1, r.plate_z);
  ahead->AddDoubleRows("/theta", 1, r.theta);
  ahead->AddDoubleRows("/state", kLabStateColumns, StateRowFill(s));
}

}  // namespace dimer::sim
