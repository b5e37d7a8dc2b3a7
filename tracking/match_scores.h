#pragma once
// A learnt appearance matched where its sphere is not. The template method accepts a match whose
// correlation coefficient reaches kMinTemplateScore (0.5, sphere/sphere_locator.h): low, because a sphere in
// under-exposed footage scores that low in earnest (POV-Ray under-exposed: 0.52 at worst). A sphere
// leaving the frame cannot be matched whole, and the best match left inside the frame lies beside
// it: on POV-Ray front_point drifting out of a narrow frame the right sphere came out 9-10 px short
// of its centre, scoring 0.53-0.63 where it had scored 0.989-0.991 in every frame before
// (see povray.leaving_the_frame). What is low is relative to the sphere's own
// scores: after the sequence, a match scoring far below its sphere's median is taken for no match.
// Where ECC did not converge there is no score to compare, and such a match 10 px short of a sphere
// at the frame's edge stayed; but the dimer is rigid and moves in the image's plane, so the
// distance between its centres is one length in every frame (its scatter a few hundredths of a
// pixel): a frame whose two centres are further from the sequence's median length than
// kLengthTolerancePx has one of them wrong, and the one less like its sphere (lower score against
// its own median, no score counting lowest) is taken for no match.
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "tracking/frame_follower.h"

namespace dimer::tracking {

// A match is dropped when its score is below the sphere's median over the sequence by more than
// kScoreDropSigmas robust sigmas of those scores, and by at least kMinScoreDrop (a sphere's
// scores vary a little with its height, the blur, an impact; no match of the POV-Ray test
// footage is dropped). The median and the dimer's length are taken over whole spheres (a cut
// one, FrameTrack::cut, is matched on part of its appearance); every match is judged by them. Fewer than kMinScoredFrames matches: none dropped.
inline constexpr double kScoreDropSigmas = 8.0;
inline constexpr double kMinScoreDrop = 0.15;
inline constexpr size_t kMinScoredFrames = 10;
// The centres' distance may differ from its median by this much (and kLengthSigmas robust
// sigmas of it) before a frame's pair is taken for wrong; fewer than kMinScoredFrames pairs:
// no check.
inline constexpr double kLengthTolerancePx = 1.0;
inline constexpr double kLengthSigmas = 10.0;

struct MatchScores {
  std::array<double, 2> median{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};
  std::array<double, 2> floor{std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN()};
  std::array<size_t, 2> dropped{0, 0};  // matches below the floor, set to not found
  double length_px = std::numeric_limits<double>::quiet_NaN();  // median distance of the centres
  std::array<size_t, 2> dropped_length{0, 0};  // matches dropped as the dimer's length was wrong
};

// Drops the outlying matches of `frames` (found = false, centre and score cleared): by score,
// then by the dimer's length. Frames without scores (other methods) are judged by the length
// alone. The same for any order of the frames.
MatchScores DropOutlyingMatches(std::vector<FrameTrack>* frames);

}  // namespace dimer::tracking
