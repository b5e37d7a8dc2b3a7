#pragma once
// Grey frames from a colour camera's raw mosaic (a Bayer colour filter array: each pixel sees
// red, green or blue through its own filter, in 2x2 cells of one red, two green and one blue).
//
// Why this filter. The tracker needs grey levels that follow the light, with no shift of
// where things are; it does not need colour. The 3x3 kernel [1 2 1]^T [1 2 1] / 16 gives every
// pixel (R + 2 G + B) / 4 of its neighbourhood, whichever of the four Bayer layouts the sensor
// has and whichever colour the centre pixel is (a red centre weighs red 4/16, green 8/16 and
// blue 4/16, and so do green and blue centres), so the camera's layout code need not be trusted
// (the file format describes it ambiguously). The kernel is symmetric about the pixel, so it
// moves no edge: a grey scene's linear ramp comes back unchanged. It blurs like a Gaussian of
// sigma 0.71 px, which adds in quadrature to the lens's blur, and it lowers white noise to 0.375
// of its level (correlated over neighbours).
//
// The borders are mirrored without repeating the edge pixel (OpenCV's BORDER_REFLECT_101),
// which keeps each mirrored pixel's colour, so the weights hold there too. 8-bit and 16-bit
// frames come back in their own depth, rounded to the nearest level; the sums are exact in
// float (at most 16 x 65535), so the result does not depend on the machine.
#include <opencv2/core.hpp>

namespace dimer::tracking {

// `raw`: CV_8UC1 or CV_16UC1, the mosaic as the sensor read it. Throws std::invalid_argument
// on another type.
cv::Mat MosaicToGrey(const cv::Mat& raw);

}  // namespace dimer::tracking
