#pragma once
// Grey frames from a colour camera's raw mosaic (a Bayer colour filter array: each pixel sees
// red, green or blue through its own filter, in 2x2 cells of one red, two green and one blue),
// without knowing which of the four Bayer layouts the sensor has (the .cine format describes its
// layout codes ambiguously).
//
// Two steps, both blind to the layout:
//  1. White balance of the four phases (a pixel's row and column parity): each phase's level
//     relative to its 2x2 cell's mean, the median over the bright, unsaturated cells of one
//     frame (MosaicBalance). A scene of one colour (steel, an aluminium plate and a black or
//     white backdrop under one lamp's tint: the scenes this tool tracks) then reads as a grey
//     scene: every pixel its cell's (R + 2G + B) / 4, with no blur.
//  2. Where the balanced cell still shows colour (a painted part, a highlight clipped in one
//     colour only), the kernel [1 2 1]^T [1 2 1] / 16 (MosaicFilterToGrey): every pixel becomes
//     (R + 2G + B) / 4 of its 3x3 neighbourhood whichever colour it is and whichever the layout,
//     symmetric about the pixel (no edge moves), a blur like a Gaussian of sigma 0.71 px. A cell
//     shows colour when its checkerboard component (v00 + v11 - v01 - v10) / 2, which a linear
//     brightness gradient does not produce, is beyond kMosaicColourSigmas times the pixels'
//     noise (robust, from same-colour neighbours) and half a level.
// Why not the filter everywhere: on POV-Ray front_point under a warm light (B, G, R = 0.55,
// 0.8, 1) it left scatter 0.068 / 0.051 px against 0.042 / 0.034 for the grey frames, the
// pattern's leak at the highlights' sharp edges, and its blur after the sensor clips is not the
// clipped plate edge's model (see povray.cine); balanced, the same frames track as grey ones.
//
// The borders are mirrored without repeating the edge pixel (BORDER_REFLECT_101), which keeps
// each mirrored pixel's colour. 8-bit and 16-bit frames come back in their own depth, rounded to
// the nearest level (ties to even); everything is computed the same way on every machine.
#include <opencv2/core.hpp>

#include <array>
#include <string>

namespace dimer::tracking {

inline constexpr double kMosaicColourSigmas = 4.0;

// Each phase's level over its cell's mean (phase = 2 * (row % 2) + col % 2); all 1 when the
// frame has too few bright unsaturated cells (then every coloured cell is filtered).
struct MosaicBalance {
  std::array<double, 4> ratio{1, 1, 1, 1};
  size_t cells = 0;  // cells the ratios rest on
  double noise = 0;  // the pixels' noise sigma after the balance, levels (0: none assumed)
  bool found() const { return cells > 0; }
};

// From one raw frame (CV_8UC1 or CV_16UC1), with its noise (kept for the file's other frames:
// the sensor's noise does not change); `saturation`: the camera's top level (cells with a pixel
// at or above it are left out).
MosaicBalance EstimateMosaicBalance(const cv::Mat& raw, double saturation);

// Steps 1 and 2 above. `raw`: CV_8UC1 or CV_16UC1, the mosaic as the sensor read it. Throws
// std::invalid_argument on another type.
cv::Mat MosaicToGrey(const cv::Mat& raw, const MosaicBalance& balance);

// The 3x3 filter alone, on every pixel.
cv::Mat MosaicFilterToGrey(const cv::Mat& raw);

}  // namespace dimer::tracking
