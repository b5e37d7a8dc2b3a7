#pragma once
// Stage "names": each found sphere named by its place on the rigid dimer.
//
// A film's chunks are tracked on their own (track_sequence.h), each starting without history,
// so a chunk's names are only its own: a chunk that starts with one sphere out of the frame
// cannot tell which one it sees. The film as a whole can, because the dimer is rigid: where one
// sphere is seen the other is one rod vector away, and the rod turns little from frame to frame.
// Names are fixed at the first frame where both spheres stand a dimer's length apart (`left` is
// the one with the smaller column there, docs/FORMATS.md) and carried forward and backward from
// it: a pair by the rod's direction, a lone sphere by the nearer of the two positions the rigid
// dimer predicts (the unseen end carried along with the seen one). A lone sphere that neither
// position claims by half a length is left unnamed (not found) rather than risk a swap.
// Held by DimerIdentity.NeverSwappedOverRandomWalksOutOfEitherEdge.
#include <cstddef>
#include <limits>
#include <vector>

#include "tracking/frame_follower.h"

namespace dimer::tracking {

// A pair is the dimer when its distance is within this fraction of the film's median distance.
inline constexpr double kPairLengthFraction = 0.25;
// A lone sphere is named when the nearer predicted end is nearer by at least this fraction of
// the dimer's length than the other end.
inline constexpr double kLoneNameMarginFraction = 0.5;

struct DimerNames {
  double length_px = std::numeric_limits<double>::quiet_NaN();  // median centre distance
  size_t pair_frames = 0;  // frames with both spheres found at the dimer's length
  size_t renamed = 0;      // frames whose chunk's names were swapped
  size_t unnamed = 0;      // lone spheres left unnamed (found = false) as ambiguous
};

// Names the found spheres of `frames` (in film order) by the rigid dimer. Frames are unchanged
// when no pair of found spheres stands a dimer's length apart (pair_frames = 0).
DimerNames NameSpheresByTheDimer(std::vector<FrameTrack>* frames);

}  // namespace dimer::tracking
