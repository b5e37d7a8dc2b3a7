#include "tests/footage/footage_motion.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/error.h"
#include "common/plate_frame.h"

namespace dimer::footage {
namespace {

// Index i such that t[i - 1] <= time < t[i] (clamped to 1..n-1) and the fraction between them.
std::pair<size_t, double> Bracket(const std::vector<double>& t, double time) {
  const size_t n = t.size();
  if (n < 2) return {0, 0.0};
  size_t i = size_t(std::upper_bound(t.begin(), t.end(), time) - t.begin());
  i = std::clamp<size_t>(i, 1, n - 1);
  const double dt = t[i] - t[i - 1];
  return {i, dt > 0 ? std::clamp((time - t[i - 1]) / dt, 0.0, 1.0) : 0.0};
}

}  // namespace

Motion HopMotion(const DimerShape& shape, size_t frames, double fps, const HopOptions& hop) {
  Motion m;
  for (size_t i = 0; i < frames; ++i) m.t.push_back(hop.t_start + double(i) / fps);
  const double r = 0.5 * shape.diameter, l = shape.CentreDistance();
  m.at = [=](double t) {
    const double phase = std::numbers::pi * hop.freq_hz * t;
    const double plate = hop.amplitude * std::sin(2 * phase);
    const double lift = hop.lift * shape.diameter * std::pow(std::sin(phase), 2);
    const double theta = l > 0 ? std::asin(std::min(1.0, lift / l)) : 0.0;
    const double x = hop.drift_speed * t;
    Instant s;
    s.plate_z = plate;
    s.left = {x - 0.5 * l * std::cos(theta), plate + r};
    s.right = s.left + l * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    return s;
  };
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "hop: plate %.4g Hz, amplitude %.4g m; drift %.4g m/s; right sphere lifts up to "
                "%.4g diameters once per period; frame 0 at t = %.6g s",
                hop.freq_hz, hop.amplitude, hop.drift_speed, hop.lift, hop.t_start);
  m.description = buf;
  return m;
}

Motion TiltedTrajectoryMotion(const Trajectory& lab, double tilt_deg, size_t max_frames,
                              const std::string& path, double* camera_roll_deg) {
  if (tilt_deg != 0) *camera_roll_deg -= tilt_deg;
  return TrajectoryMotion(InPlateFrame(lab, tilt_deg), max_frames, path);
}

Motion TrajectoryMotion(const Trajectory& traj, size_t max_frames, const std::string& path) {
  const size_t n = max_frames > 0 ? std::min(max_frames, traj.size()) : traj.size();
  if (n == 0) throw InputError(path + ": the trajectory has no samples");
  for (size_t i = 0; i < traj.size(); ++i) {
    if (!traj.tip_left[i].allFinite() || !traj.tip_right[i].allFinite() ||
        !std::isfinite(traj.plate_z[i]) || !std::isfinite(traj.t[i])) {
      throw InputError(path + ": sample " + std::to_string(i) +
                       " has a NaN position; footage needs a complete trajectory");
    }
  }
  Motion m;
  m.t.assign(traj.t.begin(), traj.t.begin() + long(n));
  m.at = [traj](double t) {
    const auto [i, u] = Bracket(traj.t, t);
    const size_t i0 = i > 0 ? i - 1 : 0;
    Instant s;
    s.left = traj.tip_left[i0] + u * (traj.tip_left[i] - traj.tip_left[i0]);
    s.right = traj.tip_right[i0] + u * (traj.tip_right[i] - traj.tip_right[i0]);
    s.plate_z = traj.plate_z[i0] + u * (traj.plate_z[i] - traj.plate_z[i0]);
    return s;
  };
  m.description = "trajectory file " + path;
  return m;
}

Motion PoseMotion(const DimerShape& shape, const std::vector<Pose>& poses) {
  Motion m;
  for (const Pose& p : poses) m.t.push_back(p.t);
  m.at = [shape, poses, t = m.t](double time) {
    const auto [i, u] = Bracket(t, time);
    const size_t i0 = i > 0 ? i - 1 : 0;
    const Pose& a = poses[i0];
    const Pose& b = poses[i];
    auto lerp = [u = u](double p, double q) { return p + u * (q - p); };
    return FromPose(shape, lerp(a.x, b.x), lerp(a.z, b.z), lerp(a.theta, b.theta),
                    lerp(a.plate_z, b.plate_z));
  };
  m.description = "pose list (" + std::to_string(poses.size()) + " poses)";
  return m;
}

std::vector<Pose> ReadPoseCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read pose file");
  std::vector<Pose> poses;
  std::string line;
  bool header = false;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("t,x,z,theta,plate_z", 0) != 0) {
        throw InputError(path + ": line " + std::to_string(number) +
                         ": expected the header t,x,z,theta,plate_z");
      }
      header = true;
      continue;
    }
    std::istringstream fields(line);
    Pose p;
    char c1 = 0, c2 = 0, c3 = 0, c4 = 0;
    if (!(fields >> p.t >> c1 >> p.x >> c2 >> p.z >> c3 >> p.theta >> c4 >> p.plate_z) ||
        c1 != ',' || c2 != ',' || c3 != ',' || c4 != ',' || !std::isfinite(p.t + p.x + p.z + p.theta + p.plate_z)) {
      throw InputError(path + ": line " + std::to_string(number) +
                       ": expected 5 finite numbers t,x,z,theta,plate_z");
    }
    if (!poses.empty() && !(p.t > poses.back().t)) {
      throw InputError(path + ": line " + std::to_string(number) + ": t must increase");
    }
    poses.push_back(p);
  }
  if (poses.empty()) throw InputError(path + ": no poses");
  return poses;
}

}  // namespace dimer::footage
