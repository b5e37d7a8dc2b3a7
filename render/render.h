#pragma once
// `dimerlab render sim.h5 -o FRAMES_DIR`: one frame per sample of a trajectory file's /t, with
// `truth.csv` (exact pixel centres and plate row per frame) and `render.json` (every parameter
// and the pixel mapping) beside the frames. The folder is written atomically.
//
// Mapping (pixel_map.h): col = x / m_per_px + col_offset, row = row0 - z / m_per_px. Defaults fit
// the paper's dimer (9.5 mm spheres, A_r 3.9, drifting a few mm) in 512x256 frames at 47.5 px
// per diameter: m_per_px = 2e-4, row0 = 0.78 * height (room above for jumps), col_offset
// centring the trajectory's mean x.
// Motion blur: each frame averages `blur_samples` instants spread over the exposure (a fraction
// of the frame interval) centred on the sample time, positions interpolated linearly between
// samples; the truth is the position at the sample time, the blur's centre.
#include <cstdint>
#include <limits>
#include <optional>
#include <functional>
#include <string>
#include <vector>

#include "common/trajectory.h"
#include "render/pixel_map.h"
#include "render/scene_renderer.h"

namespace dimer::tracking {

// How the frames are written: one PNG or TIFF file each, or one Phantom .cine holding them all
// (its frames named frames.cine#i).
enum class FrameFormat { kPng, kTiff, kCine };
std::string ToString(FrameFormat f);  // "png", "tiff", "cine"
// The name as --format takes it; UsageError naming --format otherwise.
FrameFormat ParseFrameFormat(const std::string& name);

struct RenderArgs {
  std::string input;            // trajectory file (kind sim or track)
  std::string output;           // folder to create
  bool force = false;           // replace an existing folder
  double m_per_px = 2.0e-4;     // m per pixel
  // Values a user may leave out are empty when not given.
  std::optional<double> row0;        // z = 0 row, px; not given: 0.78 of the height
  std::optional<double> col_offset;  // x = 0 column, px; not given: the trajectory centred
  std::optional<double> diameter;    // m; not given: the sim file's `diameter`
  double rod_diameter = 1.5e-3; // m (0: no rod)
  double exposure = 0.25;       // shutter open time, fraction of the frame interval (0: sharp)
  int blur_samples = 5;         // instants averaged over the exposure
  FrameFormat format = FrameFormat::kPng;  // --format
  int threads = 0;              // 0: all cores
  size_t max_frames = 0;        // render only the first N samples (0: all)
  bool quiet = false;
  RenderOptions image;          // size, lighting, noise, gradient, bit depth, seed
  // The library prints nothing: its notes (left out under quiet) and the closing one-line
  // summary go to these, which app/ prints on stderr and stdout. Either may be empty.
  std::function<void(const std::string&)> on_note, on_summary;
  void Check() const;           // InputError listing every invalid field
};

// The scene of sample i (centre of exposure) and the instants averaged for motion blur.
struct RenderPlan {
  PixelMap map;
  double radius_px = 0, rod_half_width_px = 0;
  SceneGeometry SceneAt(const Trajectory& traj, double t) const;
  std::vector<SceneGeometry> Exposure(const Trajectory& traj, size_t i, double exposure,
                                      int samples) const;
};

void RunRender(const RenderArgs& args);

}  // namespace dimer::tracking
