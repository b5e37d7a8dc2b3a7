#pragma once
// The plate edge's slope in the image, once per sequence. A camera is seldom exactly level: turned
// by 0.5 degrees about its axis it shows the plate's edge 5.6 px lower at one end of a 640 px
// frame than at the other, and a sphere resting 70 px from the column where the plate's row was
// read sits 0.6 px off the row "plate - R" (POV-Ray front_point rolled 0.5 degrees, 40 frames:
// both spheres' rows 0.6 px off). A plate tilted on purpose looks the same. The slope is
// measured on a few frames (PlateEdgeSlope on each, the spheres' columns left out), and taken
// when it moves the edge by at least kMinSlopeEffectPx across the frame and stands out of its
// uncertainty; the tracker then reads the plate's row under the dimer and at each sphere
// (frame_follower.h, FrameTrack::PlateRowAt), and the track file's metres run along the plate.
#include <opencv2/core.hpp>

#include <limits>
#include <string>
#include <vector>

namespace dimer::tracking {

struct PlateSlope {
  double value = 0;   // rows per column (> 0: descending to the right); 0 unless applied
  double measured = std::numeric_limits<double>::quiet_NaN();  // the median over the frames
  double err = std::numeric_limits<double>::quiet_NaN();       // its standard uncertainty
  size_t frames = 0;  // frames that measured one
  bool applied = false;
  std::string reason;  // why it is (not) applied
};

// The slope is taken when it moves the edge by this much across the frame's width...
inline constexpr double kMinSlopeEffectPx = 0.1;
// ... and stands this many standard uncertainties out.
inline constexpr double kMinSlopeSigmas = 3.0;
// Frames the slope is measured on (spread over those given).
inline constexpr size_t kSlopeFrames = 9;

// `frames`: images of the sequence (any number; at most kSlopeFrames, spread over them, are
// used); `polarity` as DetectPolarity's.
PlateSlope EstimatePlateSlope(const std::vector<cv::Mat>& frames, int polarity);

}  // namespace dimer::tracking
