#pragma once
// One plate through the film. Each learning frame is probed on its own, and where an edge
// across the frame stands beside the plate's (a ruler's, a backdrop's band) a frame can take it
// for the plate: on POV-Ray ruler_above_plate rendered to 100 frames, 4 of 48 learning frames
// took the ruler's lower edge, 11 px above the plate, and with those the plate's referee
// (plate_agreement.h) found the resting sphere on the plate in 2 frames and decided nothing.
// The plate moves by its motion only: a learning frame whose row stands off the frames' median
// by more than kPlateConsensusIqr of their interquartile range (a sinusoid's frames stand within
// 0.71 of it) and more than kPlateCandidateSeparationRows is measured again near the median
// (PlateConsensus.*).
#include <cstddef>
#include <vector>

#include "tracking/sphere/appearance_model.h"

namespace dimer::tracking {

inline constexpr double kPlateConsensusIqr = 2.0;
// Fewer learning frames with a plate than this decide nothing.
inline constexpr size_t kPlateConsensusMinFrames = 5;

// Measures again, near the learning frames' median plate row, the plate of each sample whose row
// stands off it (above), keeping the new row where it lies within the same tolerance; returns
// how many were moved. `radius_px`: the spheres' columns within it (and a margin) are left out
// of the edge, as when tracking (NaN: the margin only).
size_t KeepOnePlate(double radius_px, std::vector<LearningSample>* samples);

}  // namespace dimer::tracking
