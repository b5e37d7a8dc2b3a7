#pragma once
// The still background (still_background.h) measured on the learning frames.
#include <memory>
#include <vector>

#include "tracking/sphere/appearance_model.h"
#include "tracking/sphere/still_background.h"

namespace dimer::tracking {

// A still pixel's robust spread over the frames that show it (1.4826 MAD) is within this many
// times the frames' noise.
inline constexpr double kStillPixelNoise = 2.0;
// A learning frame shows a pixel where both spheres' rough centres are further than this many
// radii from it (rough centres can be half a radius off: learning_reach, tolerances.h).
inline constexpr double kStillCoverRadii = 1.5;
// Learning frames that must show a pixel for it to be told still.
inline constexpr int kStillMinFrames = 8;

// The still background of the learning frames `samples` (their rough centres and images);
// null where the frames' noise cannot be measured or fewer than kStillMinFrames show any pixel.
std::shared_ptr<const StillBackground> MeasureStillBackground(
    const std::vector<LearningSample>& samples, double radius_px);

}  // namespace dimer::tracking
