#pragma once
// The whole track refereed by the rigid rod: the distance between the two centres is one
// length in every frame, to the centres' own noise. The matches' check (match_scores.h) drops
// a single frame's wrong pair against a tolerance of 10 robust sigmas of the lengths about
// their median; a sphere held for tens of frames by something behind it bends the length
// slowly, that spread grows with it, and nothing is dropped or said. On POV-Ray
// ruler_above_plate rendered to 100 frames and tracked over frames 20-100 with the scale, as
// learnt without the learning's length referee (length_relearn.h), the hopping right sphere's
// rows stood still, then stepped, up to 11 px off its truth, scattering 0.005 px from frame to
// frame, and the dimer's length ranged over 3.3 px (137.75 in truth) while it scattered 0.075
// px from frame to frame; over frames 20-80 without the scale the left sphere is 2.1 px off and
// only the length says so (LengthConstancy.*, povray.long_ruler).
//
// So the length is judged against its own frame-to-frame noise, which a slow bend leaves
// small: frames whose length departs from the track's median by more than kLengthNoiseSigmas times
// that noise and kLengthDepartMinPx are frames where one sphere or both are off by at least
// half the departure. On the POV-Ray films the tracker follows (20 and 100 frames, every
// lighting and camera), the largest departure is 0.34 px, at most 5.4 times the noise.
#include <cstddef>
#include <limits>
#include <vector>

#include "tracking/frame_follower.h"

namespace dimer::tracking {

inline constexpr double kLengthDepartMinPx = 0.5;
inline constexpr double kLengthNoiseSigmas = 10.0;
// Fewer frames with both spheres whole, or fewer consecutive triples for the noise: not judged.
inline constexpr size_t kLengthMinFrames = 10;

struct LengthConstancy {
  size_t frames = 0;  // frames with both spheres found whole
  double median_px = std::numeric_limits<double>::quiet_NaN();
  // The length's scatter from frame to frame: the median absolute second difference over
  // consecutive frames / 0.6745 / sqrt(6), px (NaN: not judged).
  double noise_px = std::numeric_limits<double>::quiet_NaN();
  double tolerance_px = std::numeric_limits<double>::quiet_NaN();  // departure allowed
  size_t departing = 0;       // frames departing beyond the tolerance
  size_t first = 0, last = 0;  // the first and last of them (index into the track)
  double worst_px = std::numeric_limits<double>::quiet_NaN();  // the largest |departure|, px
};

// The length per frame of `frames` (frame order), px: NaN where either sphere is not found whole.
std::vector<double> DimerLengths(const std::vector<FrameTrack>& frames);

// Judges `frames` (frame order) by the constancy of their dimer's length.
LengthConstancy JudgeLengthConstancy(const std::vector<FrameTrack>& frames);

}  // namespace dimer::tracking
