#include "tracking/length_relearn.h"

#include <array>
#include <cstdio>
#include <memory>

#include "tracking/method_trial.h"

namespace dimer::tracking {
namespace {

// Fewer departing frames, then a smaller worst departure.
bool KeepsTheLengthBetter(const LengthConstancy& a, const LengthConstancy& b) {
  if (a.departing != b.departing) return a.departing < b.departing;
  return a.worst_px < b.worst_px;
}

}  // namespace

LengthConstancy FollowedLength(const std::vector<Frame>& frames, FollowerOptions follow,
                               const std::array<Appearance, 2>& appearance) {
  follow.method = Method::kTemplate;
  follow.appearance = std::make_shared<const std::array<Appearance, 2>>(appearance);
  return JudgeLengthConstancy(FollowFrames(frames, follow));
}

std::string RefereeTheLearningByTheLength(const std::vector<Frame>& learning,
                                          const std::vector<Frame>& trial,
                                          const FollowerOptions& reference,
                                          const FollowerOptions& follow, Method requested,
                                          bool radius_known, const LearnOptions& learn,
                                          const LengthConstancy* followed,
                                          SequenceMethod* prepared) {
  if (prepared->choice.method != Method::kTemplate || !prepared->appearance) return "";
  const std::array<Appearance, 2>& learnt = *prepared->appearance;
  const LengthConstancy before = followed ? *followed : FollowedLength(trial, follow, learnt);
  if (before.departing == 0) return "";
  char clause[400];
  std::snprintf(clause, sizeof clause,
                "; followed over %zu trial frames, the dimer's length departed from its median "
                "by up to %.2f px in %zu (noise %.3f px)",
                before.frames, before.worst_px, before.departing, before.noise_px);
  std::string reason = clause;
  LearnOptions again_options = learn;
  again_options.relearn_held = {true, true};
  SequenceMethod again =
      PrepareSequenceMethod(learning, reference, requested, radius_known, again_options);
  if (again.choice.method != Method::kTemplate || !again.appearance ||
      (!again.relearnt[0] && !again.relearnt[1])) {
    return reason + "; neither sphere could be learnt again without what stands still behind it";
  }
  // The pairs with one sphere or both learnt again: `take[k]` for the new appearance.
  std::array<bool, 2> best_take{false, false};
  LengthConstancy best = before;
  for (const std::array<bool, 2>& take :
       {std::array<bool, 2>{true, false}, {false, true}, {true, true}}) {
    if ((take[0] && !again.relearnt[0]) || (take[1] && !again.relearnt[1])) continue;
    std::array<Appearance, 2> pair = learnt;
    for (int k = 0; k < 2; ++k) {
      if (take[k]) pair[size_t(k)] = (*again.appearance)[size_t(k)];
    }
    const LengthConstancy c = FollowedLength(trial, follow, pair);
    if (KeepsTheLengthBetter(c, best)) best = c, best_take = take;
  }
  if (!best_take[0] && !best_take[1]) {
    return reason + "; learnt again without what stands still behind the spheres, it departed "
                    "as much: the first appearances kept";
  }
  // The spheres that keep their first appearance keep everything learnt of it.
  std::array<Appearance, 2> follow_pair = learnt;
  for (int k = 0; k < 2; ++k) {
    if (!best_take[k]) {
      again.learnt[k] = prepared->learnt[k];
      again.agreement[k] = prepared->agreement[k];
      again.relearnt[k] = prepared->relearnt[k];
      again.plate_agreement[k] = prepared->plate_agreement[k];
      again.relearnt_by_plate[k] = prepared->relearnt_by_plate[k];
      again.relearnt_by_length[k] = prepared->relearnt_by_length[k];
    } else {
      follow_pair[size_t(k)] = (*again.appearance)[size_t(k)];
      again.relearnt_by_length[k] = true;
    }
  }
  again.appearance = std::make_shared<const std::array<Appearance, 2>>(follow_pair);
  again.choice = prepared->choice;
  again.radius_from_outline = prepared->radius_from_outline;
  std::snprintf(clause, sizeof clause,
                "; %s learnt again from the highlights without what stands still behind %s: "
                "then %zu departing frames, by up to %.2f px",
                best_take[0] && best_take[1] ? "both spheres"
                : best_take[0]               ? "the left sphere"
                                             : "the right sphere",
                best_take[0] && best_take[1] ? "them" : "it", best.departing, best.worst_px);
  reason += clause;
  *prepared = std::move(again);
  return reason;
}

}  // namespace dimer::tracking
