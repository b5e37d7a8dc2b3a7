#include "compare/sampled_run.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/h5_file.h"
#include "common/median.h"
#include "common/plate_frame.h"
#include "common/trajectory_io.h"

namespace dimer::compare {
namespace {

// A time stamp may differ from its grid point by this fraction of a frame (round-off of
// t = index / fps in files) and still be that frame.
constexpr double kGridSlackFrames = 1e-3;

}  // namespace

void FindGaps(SampledRun* run) {
  for (int s = 0; s < 2; ++s) {
    auto& gaps = run->gaps[s];
    gaps.clear();
    for (size_t i = 0; i < run->n; ++i) {
      const bool missing = !std::isfinite(run->x[s][i]) || !std::isfinite(run->z[s][i]);
      if (!missing) continue;
      if (!gaps.empty() && gaps.back().first + gaps.back().count == i) {
        ++gaps.back().count;
      } else {
        gaps.push_back({i, 1});
      }
    }
  }
}

bool SampledRun::Valid(size_t i) const {
  return std::isfinite(x[0][i]) && std::isfinite(z[0][i]) && std::isfinite(x[1][i]) &&
         std::isfinite(z[1][i]);
}

Eigen::Vector2d SampledRun::PixelOf(double x_m, double z_m) const {
  if (plate_slope == 0) return {x_m / m_per_px, row0_px - z_m / m_per_px};
  // Calibration::ToMetres (tracking/calibration.h) turned (col - col0, row - row0) by the
  // slope's angle with [[cos, sin], [sin, -cos]], which is its own inverse.
  const double a = std::atan(plate_slope), c = std::cos(a), s = std::sin(a);
  const double u = x_m / m_per_px - col0_px, w = z_m / m_per_px;
  return {col0_px + u * c + w * s, row0_px + u * s - w * c};
}

SampledRun SampleTrajectory(const Trajectory& traj, double fps, double diameter_m,
                            const std::string& label, const std::string& kind) {
  SampledRun run;
  run.path = label;
  run.kind = kind;
  const size_t m = traj.size();
  if (m < 2) throw InputError(label + ": fewer than 2 samples");
  for (size_t i = 1; i < m; ++i) {
    if (!(traj.t[i] > traj.t[i - 1])) {
      throw InputError(label + ": /t is not increasing at row " + std::to_string(i));
    }
  }
  if (!(fps > 0) || !std::isfinite(fps)) {
    std::vector<double> d(m - 1);
    for (size_t i = 1; i < m; ++i) d[i - 1] = traj.t[i] - traj.t[i - 1];
    fps = 1.0 / FiniteMedian(d);
  }
  run.dt = 1.0 / fps;
  run.t0 = traj.t[0];
  const double span = (traj.t[m - 1] - run.t0) / run.dt;
  run.n = static_cast<size_t>(std::llround(span)) + 1;
  if (run.n > 50 * m + 1000) {
    throw InputError(label + ": the times span " + std::to_string(run.n) +
                     " frames for " + std::to_string(m) + " samples (wrong fps?)");
  }
  for (int s = 0; s < 2; ++s) {
    run.x[s].assign(run.n, kNaN);
    run.z[s].assign(run.n, kNaN);
  }
  run.plate_z.assign(run.n, kNaN);
  run.theta.assign(run.n, kNaN);
  for (size_t i = 0; i < m; ++i) {
    const double f = (traj.t[i] - run.t0) / run.dt;
    const long k = std::lround(f);
    if (std::abs(f - k) > kGridSlackFrames) {
      throw InputError(label + ": time " + std::to_string(traj.t[i]) +
                       " s is not on the frame grid of " + std::to_string(fps) + " frames/s");
    }
    run.x[0][k] = traj.tip_left[i].x();
    run.z[0][k] = traj.tip_left[i].y();
    run.x[1][k] = traj.tip_right[i].x();
    run.z[1][k] = traj.tip_right[i].y();
    run.plate_z[k] = traj.plate_z[i];
    run.theta[k] = traj.theta[i];
  }
  FindGaps(&run);
  for (int s = 0; s < 2; ++s) {
    if (run.gaps[s].size() == 1 && run.gaps[s][0].count == run.n) {
      throw InputError(label + ": the " + std::string(s ? "right" : "left") +
                       " sphere is NaN in every frame (never found)");
    }
  }
  run.diameter_m = diameter_m;
  std::vector<double> len(run.n, kNaN);
  for (size_t i = 0; i < run.n; ++i) {
    len[i] = std::hypot(run.x[1][i] - run.x[0][i], run.z[1][i] - run.z[0][i]);
  }
  run.ar = FiniteMedian(len) / diameter_m + 1.0;
  return run;
}

SampledRun LoadSampledRun(const std::string& path) {
  H5Reader r(path);
  const std::string kind = FileKind(r);
  if (kind != "track" && kind != "sim") {
    throw InputError(path + ": kind is '" + kind + "', expected a trajectory (track or sim)");
  }
  const double tilt_deg = kind == "sim" ? r.AttrDouble("/", "tilt_deg").value_or(0.0) : 0.0;
  if (!std::isfinite(tilt_deg)) throw InputError(path + ": 'tilt_deg' is not a number");
  const Trajectory traj = InPlateFrame(ReadTrajectory(r), tilt_deg);
  const double fps = r.AttrDouble("/", "fps").value_or(kNaN);
  const double d = r.AttrDouble("/", "diameter").value_or(kNaN);
  if (!(d > 0)) throw InputError(path + ": no positive 'diameter' attribute (sphere size, m)");
  SampledRun run = SampleTrajectory(traj, fps, d, path, kind);
  if (kind == "track") {
    run.m_per_px = r.AttrDouble("/", "m_per_px").value_or(kNaN);
    const double given = r.AttrDouble("/", "m_per_px_given").value_or(kNaN);
    run.scale_source = given == 1   ? "--m-per-px"
                       : given == 2 ? "--ar"
                       : given == 0 ? "--diameter"
                                    : "";
    run.row0_px = r.AttrDouble("/", "row0").value_or(kNaN);
    run.plate_slope = r.AttrDouble("/", "plate_slope").value_or(0.0);
    run.col0_px = r.AttrDouble("/", "col0").value_or(0.0);
    run.plate_motion_scale = r.AttrDouble("/", "plate_motion_scale").value_or(kNaN);
    run.plate_scale_source = r.AttrString("/", "plate_motion_scale_source").value_or("");
    run.video_codec = r.AttrString("/", "video_codec").value_or("");
    run.video_lossy = !run.video_codec.empty() && r.AttrDouble("/", "video_codec_lossless").value_or(0) == 0;
    if (r.Has("/lens/camera_matrix") && r.Has("/lens/distortion")) {
      run.lens_camera = r.ReadDoubles("/lens/camera_matrix");
      run.lens_distortion = r.ReadDoubles("/lens/distortion");
    }
    if (r.Has("/frame_files") && r.Has("/frame_index")) {
      const std::vector<std::string> files = r.ReadStrings("/frame_files");
      run.frame_files.assign(run.n, "");
      for (size_t i = 0; i < traj.size() && i < files.size(); ++i) {
        const long k = std::lround((traj.t[i] - run.t0) / run.dt);
        run.frame_files[k] = files[i];
      }
    }
    return run;
  }
  run.sim_tilt_deg = tilt_deg;
  run.sim_freq_hz = r.AttrDouble("/", "freq").value_or(kNaN);
  run.sim_gamma = r.AttrDouble("/", "gamma").value_or(kNaN);
  run.sim_plate_phase = r.AttrDouble("/", "plate_phase").value_or(0.0);
  run.sim_t_start = r.AttrDouble("/", "t_start").value_or(run.t0);
  run.sim_settled_mode = r.AttrString("/", "settled_mode").value_or("");
  if (r.Has("/state")) {
    Dims dims;
    const std::vector<double> flat = r.ReadDoubles("/state", &dims);
    if (dims.size() == 2 && dims[1] == 6 && dims[0] == traj.size()) {
      run.state.assign(run.n, {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN});
      for (size_t i = 0; i < traj.size(); ++i) {
        const long k = std::lround((traj.t[i] - run.t0) / run.dt);
        std::array<double, 6> lab;
        for (int c = 0; c < 6; ++c) lab[c] = flat[6 * i + c];
        run.state[k] = StateInPlateFrame(lab, tilt_deg);
      }
    }
  }
  if (r.Has("/events/t")) {
    const std::vector<double> et = r.ReadDoubles("/events/t");
    const std::vector<std::string> ek = r.ReadStrings("/events/kind");
    const std::vector<int8_t> es = r.ReadInt8("/events/sphere");
    for (size_t i = 0; i < et.size() && i < ek.size() && i < es.size(); ++i) {
      if (ek[i] == "impact" || ek[i] == "double_impact") {
        run.sim_impact_t.push_back(et[i]);
        run.sim_impact_sphere.push_back(es[i]);
      }
    }
  }
  return run;
}

}  // namespace dimer::compare
