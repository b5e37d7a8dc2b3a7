#pragma once
// The learning refereed by the rigid rod (length_constancy.h) on the film's first consecutive
// frames, before any chunk is followed. The learning's own referees judge each sphere apart:
// by its detections (detection_agreement.h) and by the plate it rests on (plate_agreement.h).
// On POV-Ray ruler_above_plate rendered to 100 frames, frames 20-100 with the scale, both
// passed the hopping right sphere's appearance, whose lower half held the ruler's white band:
// followed, its rows stood still and stepped, up to 13 px off, while the dimer's length
// departed from its median by up to 2.5 px against a frame-to-frame noise of 0.08 px.
//
// Where the learnt appearances, followed over the trial frames, give a length that departs
// (JudgeLengthConstancy), both spheres are learnt again from their highlights without the
// pixels that stand still behind them (LearnOptions::relearn_held, the learning's answer to a
// sphere its referees find held), and each sphere takes the new appearance or keeps its own as
// the length decides: of the pairs (new, old), (old, new) and (new, new), followed over the same
// frames, the one whose length departs in the fewest frames, then by the least, is kept where
// it departs in fewer frames than the learnt pair (povray.long_ruler,
// WhereTheLengthDepartsTheHeldSphereIsLearntAgain).
#include <array>
#include <string>
#include <vector>

#include "tracking/frame_follower.h"
#include "tracking/io/frame_source.h"
#include "tracking/learn_method.h"
#include "tracking/length_constancy.h"

namespace dimer::tracking {

// `trial`: the film's first consecutive frames, cleaned; `follow`: the chunks' follower options
// (the reference's polarity and radius applied; method and appearance are set here); the rest
// as PrepareSequenceMethod takes them. `followed`: the learnt appearances' length over `trial`
// where `auto`'s trial measured it already (method_trial.h; null: followed here). `*prepared` (a
// template method) is replaced where a pair learnt again keeps the length better. Returns what
// is added to the method's reason ("" where the length held).
std::string RefereeTheLearningByTheLength(const std::vector<Frame>& learning,
                                          const std::vector<Frame>& trial,
                                          const FollowerOptions& reference,
                                          const FollowerOptions& follow, Method requested,
                                          bool radius_known, const LearnOptions& learn,
                                          const LengthConstancy* followed,
                                          SequenceMethod* prepared);

// The length of `appearance` followed over `frames` (consecutive), judged.
LengthConstancy FollowedLength(const std::vector<Frame>& frames, FollowerOptions follow,
                               const std::array<Appearance, 2>& appearance);

}  // namespace dimer::tracking
