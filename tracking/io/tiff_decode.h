#pragma once
// A direct decoder for the plainest TIFF files, the kind camera software exports: one page,
// little-endian ("II"), uncompressed, one grey sample of 8 or 16 bits (unsigned, black is zero),
// stored in strips, top row first. Such a file's strips are the frame's rows: one copy, about
// 15x less CPU than libtiff through cv::imdecode. Every other TIFF (compressed, colour, tiled,
// big-endian, multi-page, other orientations or sample formats) is left to OpenCV, whose
// result this decoder's equals.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace dimer::tracking {

// True and *image set (CV_8U or CV_16U) when `bytes` is such a TIFF; false and *image untouched
// otherwise, including for truncated or inconsistent files.
bool DecodePlainTiff(const uint8_t* bytes, size_t size, cv::Mat* image);

// True when the TIFF file at `path` surely has exactly one page (its first directory links to
// no next one), from three small reads; false when it has more or cannot tell (the caller then
// asks libtiff). Either byte order.
bool TiffHasOnePage(const std::string& path);

}  // namespace dimer::tracking
