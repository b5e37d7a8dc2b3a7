#pragma once
// Byte layout of a Phantom .cine file (Vision Research's public "Cine file format" description),
// shared by the reader (cine_source.cc) and the writer (cine_writer.cc). Every multi-byte field
// is little-endian; the structures are packed (1-byte alignment).
//
//   CINEFILEHEADER (44 bytes at 0)  ->  OffImageHeader: BITMAPINFOHEADER (40 bytes)
//                                       OffSetup:       SETUP (Length bytes, "ST" marker)
//                                       OffImageOffsets: ImageCount int64 file offsets
//                                       tagged blocks: from OffSetup + Length to OffImageOffsets
//   at each image offset: AnnotationSize (uint32, includes itself and ImageSize), annotation
//   bytes, ImageSize (uint32, the last 4 bytes of the annotation block), then the pixels.
//
// Only the fields dimerlab uses are listed. SETUP offsets were counted from the published field
// list (fields before FrameRate have not moved since the 2001 layouts).
#include <cstdint>

namespace dimer::tracking::cine {

// CINEFILEHEADER
inline constexpr uint16_t kTypeCI = 0x4943;  // the bytes 'C','I'
inline constexpr int kFileHeaderSize = 44;
inline constexpr int kHType = 0, kHHeaderSize = 2, kHCompression = 4, kHVersion = 6,
                     kHFirstMovieImage = 8, kHTotalImageCount = 12, kHFirstImageNo = 16,
                     kHImageCount = 20, kHOffImageHeader = 24, kHOffSetup = 28,
                     kHOffImageOffsets = 32, kHTriggerFractions = 36, kHTriggerSeconds = 40;
inline constexpr uint16_t kCompressionGray = 0;  // CC_RGB: grey (or interpolated colour) pixels
inline constexpr uint16_t kCompressionJpeg = 1;  // CC_LEAD: (M)JPEG-compressed images
inline constexpr uint16_t kCompressionRawColour = 2;  // CC_UNINT: a colour sensor's raw mosaic

// BITMAPINFOHEADER
inline constexpr int kBitmapHeaderSize = 40;
inline constexpr int kBSize = 0, kBWidth = 4, kBHeight = 8, kBPlanes = 12, kBBitCount = 14,
                     kBCompression = 16, kBSizeImage = 20;
inline constexpr uint32_t kBiRgb = 0;        // uncompressed 8 or 16 bits per pixel
inline constexpr uint32_t kBiPacked10 = 256; // 10 bits per pixel, 4 pixels in 5 bytes

// SETUP
inline constexpr int kSFrameRate16 = 0, kSShutter16 = 2, kSMark = 140, kSLength = 142,
                     kSImWidth = 737, kSImHeight = 739, kSFlipH = 756, kSFlipV = 760,
                     kSFrameRate = 768, kSShutterUs = 772,
                     kSCfa = 808, kSRealBpp = 896, kSShutterNs = 1568, kSDescription = 1596;
inline constexpr uint16_t kSetupMarkST = 0x5453;  // the bytes 'S','T'
// SETUP.CFA: the colour filter array's code in the low byte (0: grey sensor; 1-6: Bayer layouts,
// described ambiguously); the high bits mark the grey heads of some multi-head cameras.
inline constexpr uint32_t kCfaCodeMask = 0xFF;
// Length of SETUP as written by dimerlab: up to WhiteLevel (software version 671, 2009), the
// length most files of the cameras in use carry. Readers need only up to ShutterNs.
inline constexpr uint16_t kSetupLengthWritten = 5740;
inline constexpr int kSetupMinRead = kSRealBpp + 4;  // what the reader needs at the least

// Tagged information blocks (between SETUP and the offset table): uint32 BlockSize (the whole
// block), uint16 Type, uint16 Reserved, then the data. TIME_ONLY holds one TIME64 per image (the
// image's own time stamp); RANGE_DATA ends the list (readers stop there, as the description says).
inline constexpr int kTagHeaderSize = 8;
inline constexpr uint16_t kTagTimeOnly = 1002, kTagRangeData = 1004;

}  // namespace dimer::tracking::cine
