#pragma once
// Test scenes built in code (no simulator): exact trajectories of a dimer in pixels or metres,
// rendered with known truth.
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>

#include "common/h5_file.h"
#include "common/provenance.h"
#include "common/trajectory.h"
#include "common/trajectory_io.h"
#include "render/render.h"
#include "render/scene_renderer.h"

namespace dimer::tracking::testing {

// Sample dimer of the paper: 9.5 mm spheres, A_r = 3.9 (centre distance 2 (A_r - 1) R).
inline constexpr double kDiameterM = 9.5e-3;
inline constexpr double kAspectRatio = 3.9;
inline constexpr double kMPerPx = 2.0e-4;

// DIMERLAB_TEST_SCALE (default 1) shortens long property tests under sanitizers.
inline double TestScale() {
  const char* s = std::getenv("DIMERLAB_TEST_SCALE");
  return s ? std::max(0.01, std::atof(s)) : 1.0;
}

// A dimer resting with its left sphere on the plate and tilted by `tilt_rad`, left sphere centre
// at column `col`, in pixels; plate surface at `plate_row`.
inline SceneGeometry TiltedDimer(double col, double plate_row, double radius_px, double tilt_rad,
                                 double rod_half_width_px) {
  SceneGeometry s;
  s.radius_px = radius_px;
  s.rod_half_width_px = rod_half_width_px;
  s.plate_row = plate_row;
  const double dist = 2.0 * (kAspectRatio - 1.0) * radius_px;
  s.left = {col, plate_row - radius_px};
  s.right = s.left + dist * Eigen::Vector2d(std::cos(tilt_rad), -std::sin(tilt_rad));
  return s;
}

// Drift-like motion in metres (lab frame): the CM creeps to the right, the right sphere bounces
// once per plate period while the left one stays on the plate, the plate oscillates.
// `aspect_ratio` 2 makes the spheres touch (centre distance one diameter).
inline Trajectory DriftTrajectory(size_t n, double fps, double freq_hz = 25.0,
                                  double aspect_ratio = kAspectRatio) {
  Trajectory traj;
  traj.Reserve(n);
  const double r = 0.5 * kDiameterM, half = (aspect_ratio - 1.0) * r;
  const double amplitude = 0.35e-3, drift_speed = 2e-3;  // m, m/s (10 mm in 5 s)
  for (size_t i = 0; i < n; ++i) {
    const double t = double(i) / fps;
    const double phase = 2.0 * std::numbers::pi * freq_hz * t;
    const double plate = amplitude * std::sin(phase);
    const double lift = 0.3 * kDiameterM * std::abs(std::sin(0.5 * phase));
    const Eigen::Vector2d left(-half + drift_speed * t, plate + r);
    const double theta = std::asin(lift / (2 * half));
    const Eigen::Vector2d right = left + 2 * half * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    traj.Append(t, left, right, plate, theta);
  }
  return traj;
}

// The jump mode in metres (lab frame): the dimer level, both spheres leaving the plate together
// and landing on it once per plate period (at the plate's zero crossings, frames 0, P, 2P, ...
// for P = fps / freq_hz), the plate oscillating by 0.35 mm. Neither sphere rests.
inline Trajectory JumpTrajectory(size_t n, double fps, double freq_hz = 25.0) {
  Trajectory traj;
  traj.Reserve(n);
  const double r = 0.5 * kDiameterM, half = (kAspectRatio - 1.0) * r;
  const double amplitude = 0.35e-3, g = 9.81, period = 1.0 / freq_hz;
  const double rebound = 0.5 * g * period;  // m/s: back on the plate one period later
  for (size_t i = 0; i < n; ++i) {
    const double t = double(i) / fps;
    const double plate = amplitude * std::sin(2.0 * std::numbers::pi * freq_hz * t);
    const double since = t - period * std::floor(t / period + 1e-9);
    const double z = r + rebound * since - 0.5 * g * since * since;
    traj.Append(t, Eigen::Vector2d(-half, z), Eigen::Vector2d(half, z), plate, 0.0);
  }
  return traj;
}

// A trajectory in metres as our renderer films it: 512 x 256 at kMPerPx, plate row 200, the
// dimer's centre column 256, rod 7.5 px, sensor noise 2 grey levels, frame i's noise seeded by
// i; with each frame's exact scene.
struct RenderedFilm {
  std::vector<cv::Mat> frames;
  std::vector<SceneGeometry> truth;
};
inline RenderedFilm RenderTrajectory(const Trajectory& traj, Lighting lighting) {
  RenderPlan plan;
  plan.map = {kMPerPx, 200.0, 256.0};
  plan.radius_px = 0.5 * kDiameterM / plan.map.m_per_px;
  plan.rod_half_width_px = 3.75;
  RenderOptions o;
  o.lighting = lighting;
  o.noise = 2.0;
  RenderedFilm f;
  for (size_t i = 0; i < traj.size(); ++i) {
    f.truth.push_back(plan.SceneAt(traj, traj.t[i]));
    f.frames.push_back(RenderFrame({f.truth.back()}, o, i));
  }
  return f;
}

// A file that looks like a simulator's output (kind sim, diameter, fps), from a trajectory.
inline void WriteSimFile(const std::string& path, const Trajectory& traj, double fps,
                         bool with_diameter = true) {
  H5Writer w(path);
  AttrList params = {{"fps", fps}, {"freq", 25.0}};
  if (with_diameter) params.push_back({"diameter", kDiameterM});
  WriteProvenance(w, "sim", params);
  WriteTrajectory(w, traj);
  w.Close();
}

}  // namespace dimer::tracking::testing
