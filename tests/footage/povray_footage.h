#pragma once
// Test footage rendered by POV-Ray (an independent renderer) with truth from the scene geometry.
//
// For each frame: the exposure (default 300 us at 2000 frames/s) is split into `subframes`
// equal slices, the scene is written at the middle of each slice (povray_scene.h) into one .pov
// file, POV-Ray renders the slices as an animation (16-bit linear PNG, antialiased), and the
// slices are averaged (motion blur by sub-frame averaging). Then, in this order: the lighting's
// sensor gain (ramp, under/over-exposure), a Gaussian PSF (sigma `psf_sigma_px`), Gaussian read
// noise of `noise` grey levels of the 8-bit scale (seeded per frame, identical for any thread
// count), quantisation to 8 or 16 bits with clipping.
//
// The output folder (written atomically) holds frame_000000.png ..., `truth.csv` in the layout
// of `dimerlab render` (docs/FORMATS.md, "Render folders": exact sphere centres projected
// through the pinhole, plate row in the dimer plane, at each frame's sample time = centre of
// the exposure), `footage.json` (camera, lighting, every parameter, the scene hash, the render
// time) and `pov/` (the scene file of every frame, to re-render by hand).
#include <opencv2/core.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tests/footage/footage_motion.h"
#include "tests/footage/povray_scene.h"

namespace dimer::footage {

struct FootageOptions {
  Lighting lighting = Lighting::kFrontPoint;
  DimerShape shape;
  Camera camera;               // centre_x NaN: the mean x of the dimer over the frames
  SceneOptions scene;
  double fps = 2000.0;         // frame rate (the exposure slices are placed around each sample)
  double exposure_s = 300e-6;  // shutter open time, s (0: sharp frames, one slice)
  int subframes = 6;           // slices averaged per frame
  double psf_sigma_px = 0.5;   // Gaussian PSF, px (0: none)
  double noise = 2.0;          // read noise sigma, grey levels of the 8-bit scale
  int bit_depth = 8;           // 8 or 16
  uint64_t seed = 1;           // noise seed
  // Lamps on the mains: every frame's light scaled by 1 + flicker sin(2 pi flicker_hz t), t the
  // frame's sample time (a lamp's flicker is slow against the exposure). 0: steady light.
  double flicker = 0;
  double flicker_hz = 100;
  // A lens that is not a pinhole: radial distortion (OpenCV's k1, about the optical axis's
  // pixel, normalised by the focal length in px), applied to the optical image before the PSF;
  // truth.csv stays the pinhole's, and the folder gets the lens's calibration as `lens.yml`
  // (OpenCV's calibration sample's layout). 0: a pinhole. Pincushion only (>= 0): a barrel lens
  // would need pixels from outside the rendered frame.
  double lens_k1 = 0;
  // The dimer's mean x this far to the right of the optical axis, m, when camera.centre_x is NaN
  // (where distortion is large); 0: on the axis.
  double dimer_off_axis = 0;
  int aa_depth = 4;            // POV-Ray adaptive antialiasing depth (+AM2 +R4: up to 17x17
                               // rays per pixel at edges, no jitter); 0: none
  int jobs = 0;                // POV-Ray processes at once (each single-threaded); 0: three
                               // per core (a POV-Ray run idles most of its wall time)
  std::string povray = "povray";
  bool force = false;          // replace an existing folder
  bool reuse = false;          // keep an existing folder made from the same scenes (cache)
  bool quiet = false;          // no progress on stderr

  FootageOptions() { camera.centre_x = std::numeric_limits<double>::quiet_NaN(); }
  // The defaults of a lighting: its camera and scene (povray_scene.h, DefaultCamera).
  static FootageOptions For(Lighting lighting);
  void Check() const;          // UsageError listing every invalid field
};

struct FootageResult {
  size_t frames = 0;
  bool reused = false;              // an up-to-date folder was kept
  std::string scene_hash;           // hash of every scene text and post-processing parameter
  double povray_cpu_seconds_per_frame = 0;  // CPU time of POV-Ray per frame (all slices)
  double wall_seconds = 0;          // the whole call
};

// The pinhole camera matrix of `camera` (fx = fy = FocalPx(), the optical axis's pixel): the
// calibration a lab would find for the POV-Ray camera, with the lens's distortion beside it.
cv::Matx33d CameraMatrix(const Camera& camera);

FootageResult WriteFootage(const Motion& motion, const FootageOptions& options,
                           const std::string& output);

// Renders `scene_text` (an animation of `subframes` frames when > 1) with POV-Ray in
// `work_dir` (created, removed afterwards) and returns each slice as CV_32F grey in [0, 1],
// linear, cropped to the camera's output frame. `aa_depth`: 0 no antialiasing, else POV-Ray's
// adaptive method 2 to that depth (up to (2^depth + 1)^2 rays per pixel where contrast > 0.02),
// without jitter. Throws InputError with POV-Ray's last message when it fails.
std::vector<cv::Mat> RenderPov(const std::string& scene_text, const Camera& camera,
                               int subframes, int aa_depth, const std::string& work_dir,
                               const std::string& povray = "povray");

// "POV-Ray 3.7.0.10..." (the first line of `povray --version`), or "" if it does not run.
std::string PovrayVersion(const std::string& povray = "povray");

// 64-bit FNV-1a, as 16 hex digits: the cache key of a footage folder.
std::string HashText(const std::string& text);

}  // namespace dimer::footage
