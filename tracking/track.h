#pragma once
// `dimerlab track FRAMES -o track.h5`: the tracker over a whole source, in parallel, and the
// track file of docs/FORMATS.md.
//
// Parallelism with deterministic results: the sequence is cut into chunks of a fixed number of
// frames; each chunk is decoded and tracked by its own worker with its own SequenceTracker
// (which acquires at the chunk start), and chunks are joined in order, identities stitched by
// nearest position across the boundary. Results depend on the chunk size, never on the number
// of threads or on scheduling. Memory: at most `threads` chunks of results in flight, and
// frames are decoded one at a time per worker (sequential sources such as video decode ahead
// one chunk per worker).
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tracking/io/defect_pixels.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/lens_undistortion.h"
#include "tracking/io/level_scale.h"
#include "tracking/match_scores.h"
#include "tracking/track_precision.h"
#include "tracking/plate_slope.h"
#include "tracking/template_sequence.h"
#include "tracking/tracker.h"

namespace dimer::tracking {

struct SequenceOptions {
  TrackerOptions tracker;
  int threads = 0;            // worker threads; 0: all cores
  size_t chunk_frames = 512;  // frames per chunk (changing it may change the last digits)
  // Template method: the sphere radius for the plate-contact offset, px; NaN: the measured one.
  double contact_radius_px = std::numeric_limits<double>::quiet_NaN();
  // Template method: the learning's passes (appearance_model.h, LearnOptions); it runs on
  // `threads` threads.
  int learn_passes = kLearnPasses;
  // Template method: the jackknife groups of the column offset's uncertainty (appearance_model.h,
  // LearnOptions); 0: none.
  int jackknife_groups = kJackknifeGroups;
  // Template method: how near the film's median separation a learning frame's two seeds from the
  // highlights must stand to be learnt from, px (appearance_model.h, LearnOptions); 0: twice
  // the learning's search.
  double seed_agreement_px = 0;
  // The plate edge's motion per px in the dimer plane's px (plate_contact.h,
  // GivenPlateMotionScale); NaN: 1, or fitted on a polished plate.
  double plate_motion_scale = std::numeric_limits<double>::quiet_NaN();
  // The camera's bits per pixel for 16-bit frames (level_scale.h): 0, the .cine header's;
  // 8..15 scale such levels to the 16-bit range; 16, never scaled.
  int camera_bits = 0;
  // Template method: gravity in the frames per px of sphere radius, 2 g / (diameter × fps^2),
  // 1/frame^2: times the radius in px, g in px per frame^2, which bends a bouncing sphere's
  // approach and rebound (impact_vertex.h). NaN: left out of them.
  double gravity_per_radius_px = std::numeric_limits<double>::quiet_NaN();
  // The lens's calibration (`track --lens`, lens_undistortion.h): every frame is undistorted,
  // after its stuck pixels are replaced, before anything is measured on it. Null: none.
  std::shared_ptr<const LensCalibration> lens;
  void Check() const;
};

struct SkippedFrame {
  size_t index = 0;
  std::string name, reason;
};

// Where the plate's bright side clips (over-exposure): how many frames, the level they share
// (clipped_edge.h) and how many rows were fitted again at it.
struct PlateClip {
  size_t frames = 0;
  ClippedLevel level;
  size_t refitted = 0;
};

struct SequenceResult {
  std::vector<FrameTrack> frames;       // readable frames, in order
  std::vector<std::string> names;       // file name of each row of `frames`
  std::vector<SkippedFrame> skipped;    // unreadable or wrong-size frames
  int polarity = 0;                     // the polarity used
  int width = 0, height = 0;            // frame size
  bool complete = true;                 // false when interrupted
  Method method = Method::kCentroid;    // the method used (auto resolved)
  std::string method_reason;            // why (auto, template); empty for centroid/discfit asked
  std::array<Appearance, 2> appearance; // template: the learnt appearances
  TemplateOffsets offsets;              // template: reference -> centre, already applied
  // Where the sphere radius in pixels came from: "scale" (contact_radius_px given), "outline"
  // (template on footage without silhouettes: limb_fit.h) or "silhouette" (the methods' measure).
  std::string radius_source = "silhouette";
  // The plate's visible edge to its contact line with the spheres (plate_contact.h); applied
  // already to every frame's plate_row when `plate_shift.applied`.
  PlateShift plate_shift;
  PlateMotionScale plate_scale;  // the edge's motion to the contact line's (with plate_shift)
  PlateClip plate_clip;          // an over-exposed plate's level and the rows fitted at it
  PlateSlope plate_slope;        // the plate edge's slope in the image (plate_slope.h)
  DefectPixels defects;          // the sensor's stuck pixels, replaced in every frame
  MatchScores scores;            // template: matches far below their sphere's scores, dropped
  // Template: the first readable frame's noise (grey levels, precision_bound.h) and each
  // sphere's bound (col, row; px) on how precisely its learnt appearance can be placed in it.
  double frame_noise = std::numeric_limits<double>::quiet_NaN();
  std::array<Eigen::Vector2d, 2> precision_bound{
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()),
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN())};
  // Each sphere's centres' scatter from frame to frame beside that bound (track_precision.h).
  std::array<SpherePrecision, 2> precision;
  LevelScale level_scale;        // a 10- or 12-bit camera's levels, scaled (level_scale.h)
  // The lens calibration the frames were undistorted with (null: none), and the largest shift
  // its undistortion made in these frames, px.
  std::shared_ptr<const LensCalibration> lens;
  double lens_max_shift_px = 0;
};

// Tracks every frame of `source`. `on_progress(done)` is called from the calling thread.
// Skipped frames are reported through `on_skip` as they are met (may be empty).
SequenceResult TrackSequence(FrameSource& source, const SequenceOptions& options,
                             const std::function<void(size_t)>& on_progress = {},
                             const std::function<void(const SkippedFrame&)>& on_skip = {});

struct TrackArgs {
  std::string input;            // folder of frames, multi-page TIFF, .cine or video
  std::string frames;           // --frames A:B (frame_range.h); empty: all
  std::string output;           // track.h5
  std::string output_label;     // how messages name the output (empty: `output`)
  bool force = false;           // replace an existing output
  // Frame rate, frames/s. NaN (not given): the .cine header's, else kDefaultFps. Given and
  // different from a .cine header's: a warning, and this value is used.
  double fps = std::numeric_limits<double>::quiet_NaN();
  double m_per_px = std::numeric_limits<double>::quiet_NaN();  // m/px; NaN: from --diameter
  double diameter = 9.5e-3;     // sphere diameter, m (calibration when m_per_px is not given)
  // --ar: the dimer's aspect ratio, length / diameter (dimer_length_scale.h). With m_per_px not
  // given, the scale is (ar - 1) diameter over the tracked centre distance, and the template
  // tracks with the radius that implies; with m_per_px given, a check. NaN: not given.
  double ar = std::numeric_limits<double>::quiet_NaN();
  double row0 = std::numeric_limits<double>::quiet_NaN();      // z = 0 row, px; NaN: plate median
  // The plate edge's own scale, m/px, where it is not in the dimer's plane (a plate's front
  // edge is nearer the camera); needs m_per_px or ar. NaN: the dimer plane's.
  double plate_m_per_px = std::numeric_limits<double>::quiet_NaN();
  // --lens: an OpenCV camera calibration file (lens_undistortion.h); empty: frames as recorded.
  std::string lens;
  std::string method = "auto";  // auto | centroid | discfit | template
  std::string polarity = "auto";  // auto | bright | dark
  SequenceOptions sequence;
  bool quiet = false;           // no progress on stderr
  // Called from the calling thread with the frames done so far, after each joined chunk
  // (tests use it to interrupt at a known point); may be empty.
  std::function<void(size_t)> on_progress;
  void Check() const;           // InputError listing every invalid field
};

// Runs the whole command; throws InputError for bad input, Interrupted after writing a valid
// partial file on Ctrl-C.
void RunTrack(const TrackArgs& args);

}  // namespace dimer::tracking
