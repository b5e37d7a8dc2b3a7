#pragma once
// Writes Phantom .cine files (layout: cine_layout.h) for the tests and the benchmarks: grey
// frames stored as 8-bit, 16-bit or 10-bit packed pixels, with a frame rate, an exposure and a
// trigger time in the header; as a colour camera stores them, a raw colour mosaic (the same
// pixels, Compression 2 and a CFA code) or interpolated colour (BGR, 24 or 48 bits a pixel).
// Frames are streamed: memory does not grow with the sequence.
#include <opencv2/core.hpp>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace dimer::tracking {

enum class CinePixels { k8Bit, k16Bit, k10BitPacked };

struct CineWriteOptions {
  CinePixels pixels = CinePixels::k8Bit;
  uint32_t frame_rate = 2000;       // frames/s (SETUP.FrameRate is an integer)
  uint32_t exposure_ns = 100000;    // SETUP.ShutterNs
  uint32_t trigger_seconds = 0;     // TriggerTime: seconds since 1970-01-01 UTC
  uint32_t trigger_fraction = 0;    // TriggerTime: fraction of a second, units of 2^-32 s
  int32_t first_image_no = 0;       // camera number of the first stored image (0 = trigger)
  uint32_t real_bpp = 0;            // SETUP.RealBPP; 0: 8, 16 or 10 from `pixels`
  bool top_down = false;            // 8/16-bit: rows top first with a negative biHeight
  uint32_t annotation_size = 8;     // AnnotationSize of each image (>= 8, a multiple of 4)
  // SETUP.CFA. Not 0 with single-channel frames: a colour camera's raw mosaic (the header's
  // Compression 2, uninterpolated); the frames are the sensor's pixels as given.
  uint32_t cfa = 0;
  // 3: interpolated colour, frames CV_8UC3 / CV_16UC3 in OpenCV's BGR order, stored as 24- or
  // 48-bit pixels (blue first); `cfa` is then the camera's code (the file says so; the pixels
  // are already colour). 10-bit packed files are single-channel.
  int channels = 1;
  // Not 0: a TIME_ONLY tagged block (between SETUP and the offset table, as Phantom's software
  // writes it) with image i's time stamp at TriggerTime + i / time_stamp_rate s, as a camera
  // saving with a decimation has them (the header's frame_rate then says the recording's rate).
  double time_stamp_rate = 0;
};

class CineWriter {
 public:
  // Creates `path` for `frames` frames of width x height (10-bit packed: width*height a
  // multiple of 4). Throws InputError when the file cannot be created.
  CineWriter(const std::string& path, int width, int height, size_t frames,
             const CineWriteOptions& options);
  ~CineWriter();
  CineWriter(const CineWriter&) = delete;
  CineWriter& operator=(const CineWriter&) = delete;

  // Appends one frame: CV_8U for 8-bit files, CV_16U for 16-bit and 10-bit packed ones (values
  // above 1023 are an error for packed files), with options.channels channels. Throws
  // std::invalid_argument on a wrong frame.
  void Add(const cv::Mat& frame);
  // Writes the image offset table; throws std::logic_error when fewer frames were added.
  void Close();

 private:
  void Put(const void* data, size_t n);
  std::string path_;
  FILE* file_ = nullptr;
  int width_, height_;
  CineWriteOptions options_;
  std::vector<int64_t> offsets_;
  int64_t table_at_ = 0;  // where the offset table goes
  size_t frames_ = 0;
  int64_t position_ = 0;
  std::vector<uint8_t> buffer_;
};

// All of `frames` in one call.
void WriteCine(const std::string& path, const std::vector<cv::Mat>& frames,
               const CineWriteOptions& options);

// 10-bit packing, 4 pixels in 5 bytes, most significant bit first (the bit stream of pixel
// values is big-endian: pixel 0's bits 9..2 are byte 0, its bits 1..0 open byte 1). `count` is
// a multiple of 4. Shared with the reader's tests.
void Pack10(const uint16_t* pixels, size_t count, uint8_t* out);
void Unpack10(const uint8_t* in, size_t count, uint16_t* pixels);

}  // namespace dimer::tracking
