#pragma once
// Phantom .cine files (Vision Research high-speed cameras) as a FrameSource, read from the
// public file format description (layout: cine_layout.h; assumptions: docs/FORMATS.md, "Phantom
// .cine input").
//
// Supported: grey (uncompressed, CC_RGB with CFA none) images of 8 bits (CV_8U), 16 bits
// (CV_16U, the camera's RealBPP low bits, values not rescaled) and 10-bit packed (BI_PACKED,
// delivered as CV_16U with values 0..1023, the raw packed codes: the camera's 10-to-12-bit
// linearisation table is not applied). A colour camera's files are delivered grey in the same
// depths: its raw Bayer mosaic (Compression 2, CC_UNINT; 8, 16 or 10-bit packed) balanced and,
// where colour is left, filtered, without its layout (mosaic_grey.h; the balance once per file,
// from the first readable frame), its interpolated colour (24 or 48 bits, BGR) through
// OpenCV's BGR2GRAY; RecordingInfo::colour says which. JPEG-compressed files are refused.
// Rows of 8/16-bit images are stored bottom row first when
// biHeight > 0 (the BMP convention), top row first when it is negative; 10-bit packed images are
// read top row first. Frames are numbered by position in the file (0-based) and named
// "FILE#i".
//
// The frames' own time stamps (the TIME_ONLY tagged block, cine_time_stamps.h) are delivered
// as RecordingInfo::frame_times when the file has them; SETUP.bFlipV as RecordingInfo::flip_v,
// not applied (the evidence is beside the code that reads it).
//
// Reads are random access and thread-safe (pread on one descriptor). A header that is not a
// cine throws InputError "FILE: not a Phantom .cine file (...)", one whose redundant fields
// disagree (biSizeImage, the setup's image size, a packed file's biBitCount) "FILE: corrupt
// .cine header: ...". An offset table or image that lies past the end of the file (a truncated
// copy), an offset that does not follow the one before, an ImageSize that is not the image's
// size or an image that overruns the next frame's offset makes only those frames unusable, each
// with a one-line reason; nothing is read outside the file.
#include <memory>
#include <string>

#include "tracking/io/frame.h"

namespace dimer::tracking {

std::unique_ptr<FrameSource> OpenCine(const std::string& path);

}  // namespace dimer::tracking
