#pragma once
// A trajectory file (track or sim, docs/FORMATS.md "Trajectory") put on a uniform frame grid, the
// one input of every analysis step. Tracks may lack frames (skipped, unreadable) and spheres
// (found = 0): they become NaN rows on the grid, and the gaps are listed so reports can name
// them. Sim files also bring their exact state and drive, used only to check the analysis
// (never by it: a simulation is analysed exactly as a track).
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "common/trajectory.h"

namespace dimer::compare {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Gap {
  size_t first = 0, count = 0;  // frames [first, first + count) have no valid tip
};

struct SampledRun {
  std::string path;            // the file it was read from
  std::string kind;            // "track" or "sim"
  double t0 = 0, dt = 0;       // time of frame 0 and frame interval, s
  size_t n = 0;                // frames on the grid
  std::array<std::vector<double>, 2> x, z;  // tip centres (0 left, 1 right), lab, m; NaN missing
  std::vector<double> plate_z;              // plate surface under the dimer, m; NaN missing
  std::vector<double> theta;                // axis angle, rad (counter-clockwise, left -> right)
  std::array<std::vector<Gap>, 2> gaps;     // runs of frames without that tip
  double diameter_m = kNaN;    // sphere diameter d (file attribute), m
  double ar = kNaN;            // A_r measured as median |c_r - c_l| / d + 1
  double m_per_px = kNaN;      // track files: calibration, m/px (col = x / m_per_px)
  // Track files: where that scale came from (`track`'s m_per_px_given): "--m-per-px",
  // "--diameter" (the measured sphere radius) or "--ar" (the dimer's length, A_r given: the
  // measured `ar` is then the given one); "" for sim files and older tracks.
  std::string scale_source;
  double row0_px = kNaN;       // track files: row of z = 0 (row = row0 - z / m_per_px)
  // Track files whose plate edge sloped (`track`'s plate_slope, rows per column, and the pivot
  // column col0): x and z run along the plate and its normal; 0 and 0 when level or older.
  double plate_slope = 0;
  double col0_px = 0;
  // The pixel (col, row) of the lab point (x_m, z_m), m, by the track file's calibration.
  Eigen::Vector2d PixelOf(double x_m, double z_m) const;
  std::vector<std::string> frame_files;  // track files: the image of each grid frame ("" none)
  // Track files: how the plate edge's motion was scaled to the dimer plane's (`track`'s
  // plate_motion_scale and its source: "--plate-m-per-px", "fitted" or "none"; "" when older).
  double plate_motion_scale = kNaN;
  std::string plate_scale_source;
  // Track files of a video: its codec (`track`'s video_codec) and whether it keeps every pixel;
  // a lossy one moves the spheres' edges (analysis.h warns). "" and false otherwise.
  std::string video_codec;
  bool video_lossy = false;
  // Track files made with `track --lens`: the calibration its frames were undistorted with
  // (/lens/camera_matrix, 9 values row by row, and /lens/distortion); empty otherwise. The
  // overlay undistorts the recorded frames the same way, so that the centres land on them.
  std::vector<double> lens_camera, lens_distortion;
  // Sim files only (empty or NaN for tracks).
  // A simulation of a tilted plate (its `tilt_deg`) is turned into the plate's frame (x along
  // the plate, z along its normal: common/plate_frame.h), the frame a track of it is in.
  double sim_tilt_deg = 0;
  std::vector<std::array<double, 6>> state;  // (x, z, theta, u, v, omega) per frame, lab or plate frame
  double sim_freq_hz = kNaN, sim_gamma = kNaN, sim_plate_phase = kNaN;  // phase: fraction
  double sim_t_start = kNaN;   // start of the sim's first period (its t_start), s
  std::string sim_settled_mode;
  std::vector<double> sim_impact_t;     // impacts of either sphere (kind impact/double_impact)
  std::vector<int> sim_impact_sphere;   // 0, 1 or 2 (both)

  double Time(size_t i) const { return t0 + static_cast<double>(i) * dt; }
  double fps() const { return 1.0 / dt; }
  bool Valid(size_t i) const;  // both tips known on frame i
};

// Reads a track or sim file. InputError (one line naming the file) when it is not HDF5, not a
// trajectory kind, has non-increasing or irregular times, or a tip that is NaN throughout.
SampledRun LoadSampledRun(const std::string& path);

// Recomputes run->gaps from the NaN tips (after tips are removed, e.g. as outliers).
void FindGaps(SampledRun* run);

// The same from a trajectory in memory (simulations run by compare itself): `fps` > 0 sets the
// grid, `diameter_m` the sphere size. Throws InputError naming `label` like LoadSampledRun.
SampledRun SampleTrajectory(const Trajectory& traj, double fps, double diameter_m,
                            const std::string& label, const std::string& kind);

}  // namespace dimer::compare
