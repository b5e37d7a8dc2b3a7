#pragma once
// What the dimer does in a piece of test footage: the sample time of each frame and the scene at
// any instant (sub-frames of the exposure fall between samples). Three sources:
//  - HopMotion: a built-in drift-like motion (no simulator): the centre of mass creeps to the
//    right, the right sphere lifts and lands once per plate period while the left one rests on
//    the oscillating plate. Positions sweep every sub-pixel phase within a few dozen frames.
//  - TrajectoryMotion: a trajectory file (kind sim or track, docs/FORMATS.md), interpolated
//    linearly between samples like `dimerlab render`.
//  - PoseMotion: a list of poses (t, x, z, theta, plate_z) per frame, e.g. read from a CSV file,
//    interpolated linearly; equal consecutive poses give static frames.
#include <functional>
#include <string>
#include <vector>

#include "common/trajectory.h"
#include "tests/footage/povray_scene.h"

namespace dimer::footage {

struct Motion {
  std::vector<double> t;                // sample time of each frame, s
  std::function<Instant(double)> at;    // the scene at any time, s
  std::string description;              // for the sidecar
};

struct HopOptions {
  double freq_hz = 25.0;        // plate frequency
  double amplitude = 0.25e-3;   // plate amplitude, m
  double drift_speed = 0.05;    // centre-of-mass speed, m/s (0.125 px per frame at 2000 fps)
  double lift = 0.35;           // right sphere's highest lift, fraction of the diameter
  double t_start = 0.004;       // time of frame 0, s
};
Motion HopMotion(const DimerShape& shape, size_t frames, double fps, const HopOptions& hop = {});

// Every sample of `traj` (or the first `max_frames`, 0: all). Throws InputError naming `path`
// for NaN positions.
Motion TrajectoryMotion(const Trajectory& traj, size_t max_frames, const std::string& path);

// A simulation of a plate tilted by `tilt_deg` (its lab trajectory, x horizontal) as a level
// camera films it: the scene is built in the plate's frame (POV-Ray's plate is level) and the
// camera turned by -tilt_deg more (`camera_roll_deg` is updated), so the plate's edge rises
// toward +x by the tilt in the frames and truth.csv is in that camera's pixels. 0: as
// TrajectoryMotion.
Motion TiltedTrajectoryMotion(const Trajectory& lab, double tilt_deg, size_t max_frames,
                              const std::string& path, double* camera_roll_deg);

struct Pose {
  double t = 0, x = 0, z = 0, theta = 0, plate_z = 0;  // s, m, m, rad, m
};
Motion PoseMotion(const DimerShape& shape, const std::vector<Pose>& poses);
// CSV with a header line `t,x,z,theta,plate_z` (SI units), '#' comments. Throws InputError
// naming the file and line for anything else.
std::vector<Pose> ReadPoseCsv(const std::string& path);

}  // namespace dimer::footage
