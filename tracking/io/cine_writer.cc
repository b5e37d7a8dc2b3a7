#include "tracking/io/cine_writer.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/error.h"
#include "tracking/io/cine_layout.h"

namespace dimer::tracking {
namespace {

template <typename T>
void Set(std::vector<uint8_t>* b, size_t at, T value) {  // little-endian, any host
  for (size_t k = 0; k < sizeof(T); ++k) (*b)[at + k] = uint8_t(uint64_t(value) >> (8 * k));
}

size_t BytesPerImage(CinePixels p, int channels, int w, int h) {
  const size_t n = size_t(w) * size_t(h) * size_t(channels);
  return p == CinePixels::k8Bit ? n : p == CinePixels::k16Bit ? 2 * n : n / 4 * 5;
}

}  // namespace

void Pack10(const uint16_t* pixels, size_t count, uint8_t* out) {
  for (size_t i = 0; i + 3 < count; i += 4, out += 5) {
    const uint16_t a = pixels[i] & 0x3FF, b = pixels[i + 1] & 0x3FF, c = pixels[i + 2] & 0x3FF,
                   d = pixels[i + 3] & 0x3FF;
    out[0] = uint8_t(a >> 2);
    out[1] = uint8_t((a & 0x3) << 6 | b >> 4);
    out[2] = uint8_t((b & 0xF) << 4 | c >> 6);
    out[3] = uint8_t((c & 0x3F) << 2 | d >> 8);
    out[4] = uint8_t(d & 0xFF);
  }
}

void Unpack10(const uint8_t* in, size_t count, uint16_t* pixels) {
  for (size_t i = 0; i + 3 < count; i += 4, in += 5) {
    pixels[i] = uint16_t(in[0] << 2 | in[1] >> 6);
    pixels[i + 1] = uint16_t((in[1] & 0x3F) << 4 | in[2] >> 4);
    pixels[i + 2] = uint16_t((in[2] & 0xF) << 6 | in[3] >> 2);
    pixels[i + 3] = uint16_t((in[3] & 0x3) << 8 | in[4]);
  }
}

namespace {

void CheckWriterOptions(int width, int height, const CineWriteOptions& options) {
  if (width < 1 || height < 1) throw std::invalid_argument("cine writer: empty frame size");
  if (options.pixels == CinePixels::k10BitPacked && (size_t(width) * height) % 4 != 0) {
    throw std::invalid_argument("cine writer: 10-bit packed needs width*height a multiple of 4");
  }
  if (options.channels != 1 &&
      (options.channels != 3 || options.pixels == CinePixels::k10BitPacked)) {
    throw std::invalid_argument("cine writer: 1 channel, or 3 (BGR) with 8 or 16 bits");
  }
  if (options.annotation_size < 8 || options.annotation_size % 4 != 0) {
    throw std::invalid_argument("cine writer: AnnotationSize must be >= 8 and a multiple of 4");
  }
}

// Where the headers put each part of a file of `frames` images.
struct CineParts {
  uint32_t tagged = 0;  // the time-stamp block's size, 0 without one
  uint32_t bitmap = 0, setup = 0, offsets = 0;
};

CineParts PartsOf(size_t frames, const CineWriteOptions& options) {
  using namespace cine;
  CineParts p;
  p.tagged = options.time_stamp_rate > 0 ? uint32_t(kTagHeaderSize + 8 * frames) : 0;
  p.bitmap = kFileHeaderSize;
  p.setup = p.bitmap + kBitmapHeaderSize;
  p.offsets = p.setup + kSetupLengthWritten + p.tagged;
  return p;
}

void SetFileHeader(const CineParts& at, size_t frames, const CineWriteOptions& options,
                   std::vector<uint8_t>* h) {
  using namespace cine;
  Set<uint16_t>(h, kHType, kTypeCI);
  Set<uint16_t>(h, kHHeaderSize, kFileHeaderSize);
  const bool mosaic = options.cfa != 0 && options.channels == 1;
  Set<uint16_t>(h, kHCompression, mosaic ? kCompressionRawColour : kCompressionGray);
  Set<uint16_t>(h, kHVersion, 1);
  Set<int32_t>(h, kHFirstMovieImage, options.first_image_no);
  Set<uint32_t>(h, kHTotalImageCount, uint32_t(frames));
  Set<int32_t>(h, kHFirstImageNo, options.first_image_no);
  Set<uint32_t>(h, kHImageCount, uint32_t(frames));
  Set<uint32_t>(h, kHOffImageHeader, at.bitmap);
  Set<uint32_t>(h, kHOffSetup, at.setup);
  Set<uint32_t>(h, kHOffImageOffsets, at.offsets);
  Set<uint32_t>(h, kHTriggerFractions, options.trigger_fraction);
  Set<uint32_t>(h, kHTriggerSeconds, options.trigger_seconds);
}

void SetBitmapHeader(uint32_t at, int width, int height, const CineWriteOptions& options,
                     std::vector<uint8_t>* h) {
  using namespace cine;
  const bool packed = options.pixels == CinePixels::k10BitPacked;
  const size_t image_bytes = BytesPerImage(options.pixels, options.channels, width, height);
  Set<uint32_t>(h, at + kBSize, kBitmapHeaderSize);
  Set<int32_t>(h, at + kBWidth, width);
  Set<int32_t>(h, at + kBHeight, options.top_down && !packed ? -height : height);
  Set<uint16_t>(h, at + kBPlanes, 1);
  Set<uint16_t>(h, at + kBBitCount,
                uint16_t((options.pixels == CinePixels::k8Bit ? 8 : 16) * options.channels));
  Set<uint32_t>(h, at + kBCompression, packed ? kBiPacked10 : kBiRgb);
  Set<uint32_t>(h, at + kBSizeImage, uint32_t(image_bytes));
}

void SetSetup(uint32_t at, int width, int height, const CineWriteOptions& options,
              std::vector<uint8_t>* h) {
  using namespace cine;
  const uint32_t bpp = options.real_bpp ? options.real_bpp
                       : options.pixels == CinePixels::k8Bit  ? 8
                       : options.pixels == CinePixels::k16Bit ? 16
                                                               : 10;
  const uint32_t us = options.exposure_ns / 1000;
  Set<uint16_t>(h, at + kSFrameRate16, uint16_t(std::min<uint32_t>(options.frame_rate, 65535)));
  Set<uint16_t>(h, at + kSShutter16, uint16_t(std::min<uint32_t>(us, 65535)));
  Set<uint16_t>(h, at + kSMark, kSetupMarkST);
  Set<uint16_t>(h, at + kSLength, kSetupLengthWritten);
  Set<uint16_t>(h, at + kSImWidth, uint16_t(width));
  Set<uint16_t>(h, at + kSImHeight, uint16_t(height));
  Set<uint32_t>(h, at + kSFrameRate, options.frame_rate);
  Set<uint32_t>(h, at + kSShutterUs, us);
  Set<uint32_t>(h, at + kSRealBpp, bpp);
  Set<uint32_t>(h, at + kSCfa, options.cfa);
  Set<uint32_t>(h, at + kSShutterNs, options.exposure_ns);
  // Part of every .cine written, so kept byte for byte as first written (the file it names has
  // moved to tracking/io/): renders stay bit-identical across versions.
  const char kDescription[] = "written by dimerlab (tracking/cine_writer.cc)";
  std::memcpy(h->data() + at + kSDescription, kDescription, sizeof kDescription);
}

// The tagged block of frame times after the setup: frame i at i / time_stamp_rate after the
// trigger, in 32.32 fixed-point seconds.
void SetTimeStamps(uint32_t block, uint32_t tagged, size_t frames, const CineWriteOptions& options,
                   std::vector<uint8_t>* h) {
  using namespace cine;
  Set<uint32_t>(h, block, tagged);
  Set<uint16_t>(h, block + 4, kTagTimeOnly);
  const uint64_t trigger = uint64_t(options.trigger_seconds) << 32 | options.trigger_fraction;
  for (size_t i = 0; i < frames; ++i) {
    const uint64_t t = trigger + uint64_t(std::llround(double(i) / options.time_stamp_rate *
                                                       4294967296.0));
    Set<uint32_t>(h, block + kTagHeaderSize + 8 * i, uint32_t(t));
    Set<uint32_t>(h, block + kTagHeaderSize + 8 * i + 4, uint32_t(t >> 32));
  }
}

}  // namespace

CineWriter::CineWriter(const std::string& path, int width, int height, size_t frames,
                       const CineWriteOptions& options)
    : path_(path), width_(width), height_(height), options_(options), frames_(frames) {
  CheckWriterOptions(width, height, options);
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw InputError(path + ": cannot create the .cine file");
  const CineParts at = PartsOf(frames, options);
  table_at_ = at.offsets;
  std::vector<uint8_t> h(at.offsets, 0);
  SetFileHeader(at, frames, options, &h);
  SetBitmapHeader(at.bitmap, width, height, options, &h);
  SetSetup(at.setup, width, height, options, &h);
  if (at.tagged > 0) {
    SetTimeStamps(at.setup + cine::kSetupLengthWritten, at.tagged, frames, options, &h);
  }
  Put(h.data(), h.size());
  // The offset table is written last (Close), its place reserved here, before the images, where
  // the cameras' own software puts it.
  std::vector<uint8_t> table(8 * frames, 0);
  Put(table.data(), table.size());
}

CineWriter::~CineWriter() {
  if (file_) std::fclose(file_);
}

void CineWriter::Put(const void* data, size_t n) {
  if (n && std::fwrite(data, 1, n, file_) != n) throw InputError(path_ + ": write failed");
  position_ += int64_t(n);
}

void CineWriter::Add(const cv::Mat& frame) {
  const CinePixels p = options_.pixels;
  const int want = CV_MAKETYPE(p == CinePixels::k8Bit ? CV_8U : CV_16U, options_.channels);
  if (frame.type() != want || frame.cols != width_ || frame.rows != height_) {
    throw std::invalid_argument("cine writer: frame of the wrong size or pixel type");
  }
  if (offsets_.size() >= frames_) throw std::logic_error("cine writer: more frames than declared");
  offsets_.push_back(position_);
  std::vector<uint8_t> annotation(options_.annotation_size, 0);
  const size_t bytes = BytesPerImage(p, options_.channels, width_, height_);
  Set<uint32_t>(&annotation, 0, options_.annotation_size);
  for (size_t k = 4; k + 4 < annotation.size(); ++k) annotation[k] = uint8_t('a' + k % 26);
  Set<uint32_t>(&annotation, annotation.size() - 4, uint32_t(bytes));
  Put(annotation.data(), annotation.size());
  buffer_.resize(bytes);
  const size_t row_bytes = size_t(width_) * frame.elemSize();
  if (p == CinePixels::k10BitPacked) {  // top row first (see cine_source.h)
    cv::Mat c = frame.isContinuous() ? frame : frame.clone();
    const uint16_t* px = c.ptr<uint16_t>(0);
    for (size_t i = 0; i < size_t(width_) * height_; ++i) {
      if (px[i] > 1023) throw std::invalid_argument("cine writer: 10-bit value above 1023");
    }
    Pack10(px, size_t(width_) * height_, buffer_.data());
  } else {
    for (int r = 0; r < height_; ++r) {  // bottom row first unless top_down (BMP convention)
      const int src = options_.top_down ? r : height_ - 1 - r;
      std::memcpy(buffer_.data() + size_t(r) * row_bytes, frame.ptr(src), row_bytes);
    }
    // 16-bit pixels are little-endian in the file; this writer runs on little-endian hosts.
  }
  Put(buffer_.data(), buffer_.size());
}

void CineWriter::Close() {
  if (!file_) return;
  if (offsets_.size() != frames_) throw std::logic_error("cine writer: fewer frames than declared");
  std::vector<uint8_t> table(8 * frames_);
  for (size_t i = 0; i < frames_; ++i) Set<int64_t>(&table, 8 * i, offsets_[i]);
  if (std::fseek(file_, long(table_at_), SEEK_SET) != 0 ||
      std::fwrite(table.data(), 1, table.size(), file_) != table.size() ||
      std::fclose(file_) != 0) {
    file_ = nullptr;
    throw InputError(path_ + ": write failed");
  }
  file_ = nullptr;
}

void WriteCine(const std::string& path, const std::vector<cv::Mat>& frames,
               const CineWriteOptions& options) {
  if (frames.empty()) throw std::invalid_argument("cine writer: no frames");
  CineWriter w(path, frames[0].cols, frames[0].rows, frames.size(), options);
  for (const cv::Mat& f : frames) w.Add(f);
  w.Close();
}

}  // namespace dimer::tracking
