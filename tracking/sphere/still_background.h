#pragma once
// What stands still behind the spheres, in the frame's own coordinates: a ruler's or a
// backdrop's edges, which do not move with a sphere that passes in front of them.
//
// Why: an appearance learnt without the pixels that spread over its learning samples
// (LearnOptions::still_background_spread) leaves out where the still edges lay relative to the
// sphere in those samples only. Where the sphere then goes lower or higher than it went while
// learning, the still edges fall on pixels the appearance kept and pull it: on POV-Ray
// ruler_above_plate cut to frames 10-70 the hopping sphere, landing 2 px below its learnt
// heights, was held on the ruler's upper edge, 1.2-1.8 px high (povray.long_ruler,
// TheStillBackgroundKeepsALandingSphereOffTheRulersEdge). Known in frame coordinates, the
// background the appearance did not learn is cut wherever the sphere is (FrameMask).
#include <opencv2/core.hpp>

namespace dimer::tracking {

struct StillBackground {
  // CV_32F, the frame's size: each pixel's median over the learning frames in which no sphere
  // came near it, where it stood still there (spread within kStillPixelNoise of the noise);
  // NaN where it moved or was too often covered to tell.
  cv::Mat level;
  // Grey levels: a pixel of an appearance about or beyond its sphere's rim is cut where the
  // still background there differs from the background the appearance learnt by more than this
  // (kStillBackgroundSpread times the frames' noise).
  double spread = 0;
};

// An appearance's pixels within this of its disc's rim mix the sphere with what is behind it
// (the rim's blur): they are compared with the background the appearance learnt just beyond the
// rim, and never cut nearer the centre (StillBackground.FrameMaskCutsTheBackground...).
inline constexpr double kStillRimPx = 2.0;

}  // namespace dimer::tracking
