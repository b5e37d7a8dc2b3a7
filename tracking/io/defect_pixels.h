#pragma once
// Stuck pixels of the camera's sensor: hot (bright) or dead (dark) in every frame, wherever the
// scene is. A high-speed CMOS sensor has some (more when warm and at long exposures; a black
// reference removes most, not all). One inside a sphere's template window is an outlier that the
// registration fits as if it were the sphere: 60 hot pixels on POV-Ray front_point footage (1 in
// 3,400) put one sphere's scatter at 0.54 px against 0.04 (see povray.stuck_pixels).
//
// They are found once per sequence, on frames spread over the first chunk (those the plate's slope
// is measured on), and each is replaced in every frame by an interpolation across it from its
// neighbours that are not stuck themselves. A pixel is stuck when it stands out from every one of
// its 8 neighbours, the same way (above them all, or below them all), by more than kDefectSigmas of
// the frame's noise, in nearly every frame examined. A sphere's highlight also stands out so, but
// moves with the sphere, which a vibrated dimer always does (the plate carries it); a feature of
// the backdrop one pixel small and fixed is replaced too, which costs nothing.
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace dimer::tracking {

// Above or below all 8 neighbours by more than this many noise sigmas (the frame's, from the
// differences of horizontal neighbours), and at least kDefectMinLevels grey levels (8-bit scale).
inline constexpr double kDefectSigmas = 6.0;
inline constexpr double kDefectMinLevels = 6.0;
// ... in at least this fraction of the frames examined, of which there must be kMinDefectFrames.
inline constexpr double kDefectFrameFraction = 0.8;
inline constexpr size_t kMinDefectFrames = 5;
// More than this fraction of the frame standing out so is not a sensor's defects but the scene
// (a fine texture, a grid): nothing is replaced, and the reason says so.
inline constexpr double kMaxDefectFraction = 0.002;

struct DefectPixels {
  std::vector<cv::Point> at;  // (col, row), in row-major order
  cv::Mat mask;               // CV_8U, 1 at the pixels of `at` (empty when there are none)
  size_t frames = 0;          // frames examined
  std::string reason;         // why none are replaced when some stood out (empty otherwise)
};

// `frames`: single-channel 8- or 16-bit images of one size. Fewer than kMinDefectFrames: none.
DefectPixels FindDefectPixels(const std::vector<cv::Mat>& frames);

// `frame` with every stuck pixel replaced by the mean of its sound opposite neighbours (left and
// right, above and below; the diagonals where neither pair is whole) as a new image, or `frame`
// itself (no copy) when there are none.
cv::Mat RepairDefectPixels(const cv::Mat& frame, const DefectPixels& defects);

}  // namespace dimer::tracking
