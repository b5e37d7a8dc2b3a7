#pragma once
// What `dimerlab track FRAMES -o track.h5` is asked to do: the command line, typed, with the
// tracker's options (track_sequence.h) inside it. RunTrack (run_track.h) runs it.
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "tracking/diagnostics.h"
#include "tracking/track_sequence.h"

namespace dimer::tracking {

// What the spheres look like against their surroundings (--polarity): found by the tracker
// (auto), or given: brighter (front-lit steel, a disc) or darker (backlit) than the backdrop.
enum class Polarity { kAuto, kBright, kDark };
std::string ToString(Polarity p);  // "auto", "bright", "dark"
// The name as --polarity takes it; UsageError naming `option` otherwise.
Polarity ParsePolarity(const std::string& name, const std::string& option = "--polarity");
// The tracker's sign of the spheres' contrast (FollowerOptions::polarity): +1, -1, 0 for auto.
int Sign(Polarity p);

// The frame rates a film may have, frames/s (docs/FORMATS.md, ranges): a camera's 1 .. 10^7.
inline constexpr double kMinTrackFps = 1.0;
inline constexpr double kMaxTrackFps = 1e7;

struct TrackArgs {
  std::string input;            // folder of frames, multi-page TIFF, .cine or video
  std::string frames;           // --frames A:B (frame_range.h); empty: all
  std::string output;           // track.h5
  std::string output_label;     // how messages name the output (empty: `output`)
  bool force = false;           // replace an existing output
  // Values a user may leave out are empty when not given.
  // Frame rate, frames/s. Not given: the frames' time stamps', the .cine header's, else
  // kDefaultFps. Given and different from a .cine header's: a warning, and this value is used.
  std::optional<double> fps;
  std::optional<double> m_per_px;  // m/px; not given: from --diameter or --ar
  double diameter = 9.5e-3;     // sphere diameter, m (calibration when m_per_px is not given)
  // --ar: the dimer's aspect ratio, length / diameter (dimer_length_scale.h). With m_per_px not
  // given, the scale is (ar - 1) diameter over the tracked centre distance, and the template
  // tracks with the radius that implies; with m_per_px given, a check.
  std::optional<double> ar;
  std::optional<double> row0;   // z = 0 row, px; not given: the plate's median row
  // The plate edge's own scale, m/px, where it is not in the dimer's plane (a plate's front
  // edge is nearer the camera); needs m_per_px or ar. Not given: the dimer plane's.
  std::optional<double> plate_m_per_px;
  // --lens: an OpenCV camera calibration file (lens_undistortion.h); empty: frames as recorded.
  std::string lens;
  Method method = Method::kAuto;        // --method
  Polarity polarity = Polarity::kAuto;  // --polarity
  SequenceOptions sequence;
  bool quiet = false;           // no progress on stderr
  // Called from the calling thread with the frames done so far, after each joined chunk
  // (tests use it to interrupt at a known point); may be empty.
  std::function<void(size_t)> on_progress;
  // Each note and warning about the film as it is made (diagnostics.h), from the calling
  // thread; app/ prints them. May be empty.
  Diagnostics::Sink on_diagnostic;
  // The closing one-line summary (app/ prints it on stdout); may be empty.
  std::function<void(const std::string&)> on_summary;
  void Check() const;           // InputError listing every invalid field
};

}  // namespace dimer::tracking
