#pragma once
// A direct decoder for the BMP files cameras and OpenCV write for grey frames: 8 bits per pixel,
// uncompressed (BI_RGB), a grey palette (entry i = (i, i, i)), rows padded to 4 bytes, bottom
// row first (or top first for a negative height). Such a file's bytes are the frame's pixels:
// one copy per row, no palette lookup and no colour conversion, about 5x faster than
// cv::imdecode. Any other BMP (colour, a non-grey palette, RLE, 1/4/16/24/32 bits) is left to
// OpenCV: the result is then the same as cv::imdecode's with IMREAD_GRAYSCALE.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>

namespace dimer::tracking {

// True and *image set (CV_8U) when `bytes` is a grey 8-bit BMP this decoder takes; false (and
// *image untouched) otherwise, including for truncated or inconsistent files.
bool DecodeGreyBmp(const uint8_t* bytes, size_t size, cv::Mat* image);

}  // namespace dimer::tracking
