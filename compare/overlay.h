#pragma once
// The tracked (and simulated) dimer drawn over the recorded frames: a check by eye that the
// tracker found the spheres and that the aligned simulation moves like them.
//
// On each frame of the settled window (converted to 8-bit colour): the tracked tip centres
// (crosses, one colour per sphere) with circles of diameter d, the aligned simulation's spheres
// at the same instant (circles in a third colour) when a comparison is given, and a line of text
// with the time and the mode of the timeline window containing it. Pixels from the track's
// calibration: col = x / m_per_px, row = row0_px - z / m_per_px (turned with a sloping plate's
// edge: SampledRun::PixelOf).
//
// Writes overlay.avi (MJPG) over the first max_frames frames of the settled window and
// stills/still_K.png (K = 0 .. stills - 1) at phases K / stills of its first period. Missing or
// unreadable frames are skipped with one warning line on stderr.
#include <string>
#include <vector>

#include "compare/analysis.h"
#include "compare/comparison.h"

namespace dimer::compare {

struct OverlayOptions {
  std::string frames_dir;  // the frames that were tracked (folder, multi-page TIFF or video)
  int max_frames = 400;    // frames in the video (> 0)
  int stills = 4;          // stills over one period of the settled window (>= 0)
  double video_fps = 25;   // frame rate of overlay.avi, frames/s (> 0)
  bool quiet = false;      // no progress meter
  // Every invalid field at once ("field: value: expected ..."); empty if valid.
  std::vector<std::string> Check() const;
};

// Writes overlay.avi and stills/ into `dir` (which exists). InputError (one line) when the
// options are invalid, `track` is not a calibrated track with frame names, frames_dir cannot be
// opened, or no frame of the settled window can be read.
void WriteOverlay(const std::string& dir, const Analysis& track, const Comparison* comparison,
                  const OverlayOptions& o);

}  // namespace dimer::compare
