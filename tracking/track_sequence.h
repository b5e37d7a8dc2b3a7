#pragma once
// A film tracked: every frame of a source through the tracker, in parallel, as a sequence of
// stages (docs/DESIGN.md, "The tracking pipeline"): a camera's levels scaled; the first readable
// frame opened (its size, polarity and radius; the sensor's stuck pixels, the lens, the plate
// edge's slope); the method chosen and, for the template, the appearances learnt; the frames
// followed in chunks and joined; the spheres named by the rigid dimer; then matches that were not the sphere dropped, an
// over-exposed plate's rows refitted, the contact line, the template's offsets and the
// precision. `dimerlab track` (run_track.h) calibrates and writes what this returns.
//
// Parallelism with deterministic results: the sequence is cut into chunks of a fixed number of
// frames; each chunk is decoded and tracked by its own worker with its own FrameFollower
// (which acquires at the chunk start), and chunks are joined in order; the spheres' names are
// then the film's, given by the rigid dimer over the whole film (dimer_identity.h). Results depend on the chunk size, never on the number
// of threads or on scheduling. Memory: at most `threads` chunks of results in flight, and
// frames are decoded one at a time per worker (sequential sources such as video decode ahead
// one chunk per worker).
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tracking/io/defect_pixels.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/lens_undistortion.h"
#include "tracking/io/level_scale.h"
#include "tracking/dimer_identity.h"
#include "tracking/match_scores.h"
#include "tracking/plate_slope.h"
#include "tracking/learn_method.h"
#include "tracking/held_rows.h"
#include "tracking/length_constancy.h"
#include "tracking/track_precision.h"
#include "tracking/frame_follower.h"
#include "tracking/method_trial.h"

namespace dimer::tracking {
struct SequenceOptions {
  FollowerOptions follower;
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
  DimerNames dimer_names;        // the spheres named by the rigid dimer (dimer_identity.h)
  MatchScores scores;            // template: matches far below their sphere's scores, dropped
  // auto, where the template was learnt: each candidate's noise on the film's first frames
  // (method_trial.h), the template first; empty otherwise.
  std::vector<TrialScores> method_trial;
  // Template: the first readable frame's noise (grey levels, precision_bound.h) and each
  // sphere's bound (col, row; px) on how precisely its learnt appearance can be placed in it.
  double frame_noise = std::numeric_limits<double>::quiet_NaN();
  std::array<Eigen::Vector2d, 2> precision_bound{
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()),
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN())};
  // Each sphere's centres' scatter from frame to frame beside that bound (track_precision.h).
  std::array<SpherePrecision, 2> precision;
  // Each sphere's rows against the plate under it and a free fall (held_rows.h): windows where
  // they did neither, held by something standing still behind it.
  std::array<HeldRows, 2> held_rows;
  // The dimer's length against its own frame-to-frame noise (length_constancy.h): frames where
  // it departs, one sphere or both off.
  LengthConstancy length;
  // Template: each sphere's learnt positions against its rough centres (detection_agreement.h).
  std::array<DetectionAgreement, 2> detection_agreement;
  // Template: the spheres learnt again after the referee rejected their first appearance
  // (learn_method.h, SequenceMethod::relearnt); detection_agreement is then the new one's.
  std::array<bool, 2> relearnt{false, false};
  // Template: each sphere's rows on the learning frames against the plate it rests on
  // (SequenceMethod::plate_agreement), and whether that referee had it learnt again.
  std::array<PlateAgreement, 2> plate_agreement;
  std::array<bool, 2> relearnt_by_plate{false, false};
  std::array<bool, 2> relearnt_by_length{false, false};  // length_relearn.h
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

}  // namespace dimer::tracking
