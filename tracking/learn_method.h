#pragma once
// The sequence-level part of `--method template` and `--method auto` (track_sequence.cc calls it):
// which frames the appearances are learnt from, the choice of method, and the offsets applied
// to the template's positions once the whole sequence is tracked (appearance_model.h).
#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "tracking/detection_agreement.h"
#include "tracking/plate_agreement.h"
#include "tracking/sphere/appearance_model.h"
#include "tracking/plate_contact.h"
#include "tracking/io/frame_source.h"
#include "tracking/method_choice.h"
#include "tracking/frame_follower.h"

namespace dimer::tracking {

// Learning frames among `frames` (0..frames-1): every k-th of the first kLearnSpanFrames, about
// kLearnFrames of them. Frame indices only: the same for any thread count.
std::vector<size_t> LearningIndices(size_t frames);

struct SequenceMethod {
  MethodChoice choice;
  std::shared_ptr<const std::array<Appearance, 2>> appearance;  // template only
  std::array<LearntSphere, 2> learnt;
  bool radius_from_outline = false;  // the appearances' radius_px was measured on the outline
  // The found plate edge to the contact line (plate_contact.h), from the learning frames; when
  // applied, added to every frame's plate row before the offsets are estimated.
  PlateShift plate_shift;
  // Template: each sphere's learnt positions refereed by its rough centres on the learning
  // frames (detection_agreement.h); a disagreement is also a clause of choice.reason.
  std::array<DetectionAgreement, 2> agreement;
  // Whether each sphere was learnt again, from its highlights and without what stood still
  // behind it, after the referee rejected its first appearance (RelearnHeldSpheres).
  std::array<bool, 2> relearnt{false, false};
  // Each sphere's rows on the learning frames refereed by the plate it rests on
  // (plate_agreement.h): its registered rows, or, where those were rejected, the final
  // appearance's followed rows; and whether that referee had it learnt again
  // (RelearnHeldByThePlate; relearnt is then true too).
  std::array<PlateAgreement, 2> plate_agreement;
  std::array<bool, 2> relearnt_by_plate{false, false};
  // Whether the dimer's length over the trial frames had it learnt again (length_relearn.h;
  // relearnt is then true too).
  std::array<bool, 2> relearnt_by_length{false, false};
};

// Measures the learning frames with the existing methods (a fresh acquisition each, with the
// reference's polarity and radius in `reference`), chooses the method and, for the template
// method, learns both appearances. `requested` is kAuto or an explicit method. `radius_known`:
// the reference's radius comes from the scale; otherwise it is the silhouette methods' measure
// and, on footage that is not made of silhouettes, the radius is taken from the spheres'
// outline (limb_fit.h) and held in the appearances' radius_px. The learning frames are measured
// on `learn.threads` threads too (the result does not depend on it).
SequenceMethod PrepareSequenceMethod(const std::vector<Frame>& learning,
                                     const FollowerOptions& reference, Method requested,
                                     bool radius_known, const LearnOptions& learn = {});

struct TemplateOffsets {
  std::array<OffsetEstimate, 2> col, row;  // per sphere (left, right): reference -> centre
  // Where one sphere's row was carried over to the other: how unlike their appearances are once
  // registered (AppearanceMismatch, appearance_mismatch.h); NaN where not measured.
  double appearance_mismatch = std::numeric_limits<double>::quiet_NaN();
};

// From silhouettes when the footage has clean ones, else rows from the plate contact over the
// whole track (`contact_radius_px`; `gravity_px`, g in px per frame^2, bends the arms of a
// bouncing sphere's impacts: ContactRowOffset, NaN: left out) and columns from the appearance's
// outline. Each stated uncertainty is widened where the sphere's learnt positions disagree
// with its detections (m.agreement, WidenForDisagreement).
TemplateOffsets EstimateOffsets(const SequenceMethod& m, const std::vector<FrameTrack>& frames,
                                double contact_radius_px,
                                double gravity_px = std::numeric_limits<double>::quiet_NaN());
void ApplyOffsets(const TemplateOffsets& o, std::vector<FrameTrack>* frames);

}  // namespace dimer::tracking
