#include "tracking/io/cine_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "common/error.h"
#include "tracking/io/cine_layout.h"
#include "tracking/io/cine_time_stamps.h"
#include "tracking/io/cine_writer.h"
#include "tracking/io/mosaic_grey.h"

namespace dimer::tracking {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the .cine reader copies little-endian 16-bit pixels as they are");

template <typename T>
T Le(const uint8_t* p) {
  uint64_t v = 0;
  for (size_t k = 0; k < sizeof(T); ++k) v |= uint64_t(p[k]) << (8 * k);
  return T(v);
}

enum class Pixels { k8, k16, kPacked10 };

class CineSource : public FrameSource {
 public:
  explicit CineSource(const std::string& path)
      : path_(path), name_(std::filesystem::path(path).filename().string()) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
      ::close(fd_);
      throw InputError(path + ": cannot read its size");
    }
    size_ = int64_t(st.st_size);
    try {
      ParseHeaders();
    } catch (...) {
      ::close(fd_);
      throw;
    }
  }
  ~CineSource() override { ::close(fd_); }

  size_t size() const override { return count_; }
  bool random_access() const override { return true; }
  RecordingInfo recording() const override { return info_; }

  Frame Read(size_t index) const override {
    Frame f;
    f.index = index;
    f.name = name_ + "#" + std::to_string(index);
    f.error = ReadPixels(index, &f.image);
    if (f.error.empty()) f.image = Grey(f.image);
    if (!f.error.empty()) f.image = cv::Mat();
    return f;
  }
  bool Next(Frame* frame) override {
    if (next_ >= count_) return false;
    *frame = Read(next_++);
    return true;
  }

 private:
  [[noreturn]] void NotCine(const std::string& why) const {
    throw InputError(path_ + ": not a Phantom .cine file (" + why + ")");
  }
  // The header's redundant fields disagree: whichever is wrong, every frame would be misread.
  [[noreturn]] void Inconsistent(const std::string& why) const {
    throw InputError(path_ + ": corrupt .cine header: " + why);
  }

  // Reads exactly n bytes at `offset`; false when any of them lies outside the file.
  bool ReadAt(int64_t offset, void* dst, size_t n) const {
    if (offset < 0 || offset > size_ || int64_t(n) > size_ - offset) return false;
    auto* out = static_cast<uint8_t*>(dst);
    while (n > 0) {
      const ssize_t got = ::pread(fd_, out, n, offset);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;  // the file shrank since it was opened, or an I/O error
      out += got;
      offset += got;
      n -= size_t(got);
    }
    return true;
  }

  void ParseHeaders() {
    uint8_t h[cine::kFileHeaderSize];
    if (!ReadAt(0, h, sizeof h)) {
      NotCine(std::to_string(size_) + " bytes, shorter than the 44-byte file header");
    }
    using namespace cine;
    if (Le<uint16_t>(h + kHType) != kTypeCI) NotCine("no \"CI\" signature at the start");
    if (Le<uint16_t>(h + kHHeaderSize) < kFileHeaderSize) NotCine("file header size below 44");
    const uint16_t compression = Le<uint16_t>(h + kHCompression);
    const uint32_t off_bitmap = Le<uint32_t>(h + kHOffImageHeader);
    const uint32_t off_setup = Le<uint32_t>(h + kHOffSetup);
    const uint32_t off_offsets = Le<uint32_t>(h + kHOffImageOffsets);
    const uint32_t image_count = Le<uint32_t>(h + kHImageCount);

    uint8_t b[kBitmapHeaderSize];
    if (!ReadAt(off_bitmap, b, sizeof b)) {
      NotCine("image header offset " + std::to_string(off_bitmap) + " past the end of the file");
    }
    std::vector<uint8_t> s(kSetupMinRead);
    if (!ReadAt(off_setup, s.data(), s.size())) {
      NotCine("setup offset " + std::to_string(off_setup) + " past the end of the file");
    }
    if (Le<uint16_t>(s.data() + kSMark) != kSetupMarkST) NotCine("no \"ST\" setup marker");
    const int32_t w = Le<int32_t>(b + kBWidth), hgt = Le<int32_t>(b + kBHeight);
    if (w < 1 || w > 65535 || hgt == 0 || hgt < -65535 || hgt > 65535) {
      NotCine("absurd image size " + std::to_string(w) + "x" + std::to_string(hgt));
    }
    width_ = w;
    height_ = std::abs(hgt);
    bottom_up_ = hgt > 0;
    const uint16_t bits = Le<uint16_t>(b + kBBitCount);
    const uint32_t bi_compression = Le<uint32_t>(b + kBCompression);
    CheckCompression(compression);
    // A colour camera's raw mosaic (Compression 2) is single-channel: its pixels are read as
    // grey ones are and turned grey by mosaic_grey.h; interpolated colour (Compression 0, 24 or
    // 48 bits a pixel) is BGR, turned grey as colour image files are (frame_source.cc).
    mosaic_ = compression == kCompressionRawColour;
    cfa_ = Le<uint32_t>(s.data() + kSCfa);
    ChoosePixelLayout(bits, bi_compression);
    CheckRedundantFields(b, s.data(), bits);
    if (image_count == 0) throw InputError(path_ + ": the .cine file holds no images");
    // Every image needs at least its 8-byte table entry: a larger count is not a cine's.
    if (image_count > uint64_t(size_) / 8) {
      NotCine("absurd image count " + std::to_string(image_count) + " for a file of " +
              std::to_string(size_) + " bytes");
    }
    count_ = image_count;

    ReadOffsetTable(off_offsets);
    ReadRecordingInfo(h, s, off_setup, off_offsets, bits);
    if (mosaic_) FindMosaicBalance();
  }

  void CheckCompression(uint16_t compression) const {
    using namespace cine;
    if (compression == kCompressionJpeg) {
      throw InputError(path_ + ": JPEG-compressed .cine (Compression 1) is not supported; "
                       "export it uncompressed");
    }
    if (compression > kCompressionRawColour) {
      throw InputError(path_ + ": .cine with Compression " + std::to_string(compression) +
                       " is not supported; export it uncompressed");
    }
  }

  // How an image's pixels are stored (depth, channels, packing) and its size in bytes.
  void ChoosePixelLayout(uint16_t bits, uint32_t bi_compression) {
    using namespace cine;
    const size_t pixels = size_t(width_) * size_t(height_);
    if (bi_compression == kBiRgb && (bits == 8 || bits == 16)) {
      pixels_ = bits == 8 ? Pixels::k8 : Pixels::k16;
      row_bytes_ = size_t(width_) * (bits / 8);
      image_bytes_ = row_bytes_ * size_t(height_);
    } else if (bi_compression == kBiRgb && (bits == 24 || bits == 48) && !mosaic_) {
      pixels_ = bits == 24 ? Pixels::k8 : Pixels::k16;
      channels_ = 3;
      row_bytes_ = size_t(width_) * (bits / 8);
      image_bytes_ = row_bytes_ * size_t(height_);
    } else if (bi_compression == kBiPacked10) {
      if (pixels % 4 != 0) NotCine("10-bit packed image of " + std::to_string(pixels) +
                                   " pixels, not a multiple of 4");
      pixels_ = Pixels::kPacked10;
      bottom_up_ = false;  // assumption: packed images are stored top row first (FORMATS.md)
      image_bytes_ = pixels / 4 * 5;
    } else {
      throw InputError(path_ + ": .cine with " + std::to_string(bits) + "-bit pixels (bitmap " +
                       "compression " + std::to_string(bi_compression) +
                       (mosaic_ ? ", raw colour" : "") +
                       ") is not supported: only 8-bit, 16-bit and 10-bit packed grey or raw "
                       "colour, and 24- or 48-bit colour");
    }
  }

  void ReadOffsetTable(uint32_t off_offsets) {
    // The offset table: the entries inside the file (a truncated file loses the rest; those
    // frames are reported unreadable, not the whole file).
    const int64_t room = off_offsets <= size_ ? (size_ - off_offsets) / 8 : 0;
    std::vector<uint8_t> table(8 * size_t(std::min<int64_t>(room, count_)));
    if (!table.empty() && !ReadAt(off_offsets, table.data(), table.size())) table.clear();
    offsets_.resize(table.size() / 8);
    for (size_t i = 0; i < offsets_.size(); ++i) offsets_[i] = Le<int64_t>(table.data() + 8 * i);
  }

  // The recording's rate, frame times, exposure, trigger and levels (RecordingInfo).
  void ReadRecordingInfo(const uint8_t* h, const std::vector<uint8_t>& s, uint32_t off_setup,
                         uint32_t off_offsets, uint16_t bits) {
    using namespace cine;
    info_.known = true;
    const uint32_t rate = Le<uint32_t>(s.data() + kSFrameRate);
    info_.fps = rate > 0 ? rate : Le<uint16_t>(s.data() + kSFrameRate16);
    const uint16_t setup_length = Le<uint16_t>(s.data() + kSLength);
    ReadFrameTimes(int64_t(off_setup) + setup_length, off_offsets);
    // bFlipV is recorded, not applied: the row order comes from biHeight alone. Evidence: pims'
    // reader (soft-matter/pims, cine.py) reads every unpacked image bottom row first and never
    // looks at bFlipV, and the 2019 Phantom film of tests/data/cine (bFlipV = 1, biHeight > 0)
    // read that way shows its two round objects standing on their stem. FFmpeg's demuxer
    // instead reads bFlipV = 1 files top row first, which shows that film upside down; Vision
    // Research's description says only "Flips image vertically" (a camera setting whose flip
    // is already in the stored pixels).
    info_.flip_v = Le<int32_t>(s.data() + kSFlipV) != 0;
    uint8_t ns[4];
    // ShutterNs exists from SETUP version 631 (2005) on; older files give microseconds only.
    const bool have_ns = setup_length >= kSShutterNs + 4 && ReadAt(off_setup + kSShutterNs, ns, 4);
    const uint32_t shutter_ns = have_ns ? Le<uint32_t>(ns) : 0;
    info_.exposure_ns = shutter_ns > 0 ? shutter_ns
                                       : int64_t(Le<uint32_t>(s.data() + kSShutterUs)) * 1000;
    info_.trigger_fraction = Le<uint32_t>(h + kHTriggerFractions);
    info_.trigger_seconds = Le<uint32_t>(h + kHTriggerSeconds);
    info_.first_image_no = Le<int32_t>(h + kHFirstImageNo);
    const uint32_t real_bpp = Le<uint32_t>(s.data() + kSRealBpp);
    info_.real_bpp = real_bpp > 0 && real_bpp <= 16 ? int(real_bpp)
                     : pixels_ == Pixels::kPacked10  ? 10
                                                     : bits / channels_;
    info_.colour = mosaic_ ? "mosaic" : channels_ == 3 ? "bgr" : "grey";
    info_.cfa = int64_t(cfa_);
  }

  // Cross-checks the bitmap header against itself and the setup (whole-file errors): biSizeImage
  // against the size and depth, the setup's image size against the bitmap's, a packed file's
  // biBitCount.
  void CheckRedundantFields(const uint8_t* b, const uint8_t* s, uint16_t bits) const {
    using namespace cine;
    const std::string size = std::to_string(width_) + "x" + std::to_string(height_);
    const uint32_t bi_size_image = Le<uint32_t>(b + kBSizeImage);
    const size_t padded = (row_bytes_ + 3) / 4 * 4 * size_t(height_);
    // 0 is the BMP rule's "not given" for uncompressed images.
    if (bi_size_image != 0 && bi_size_image != image_bytes_ &&
        (pixels_ == Pixels::kPacked10 || bi_size_image != padded)) {
      Inconsistent("biSizeImage " + std::to_string(bi_size_image) + " is not the " +
                   std::to_string(image_bytes_) + " bytes of a " + size + " image of " +
                   (pixels_ == Pixels::kPacked10 ? std::string("10-bit packed")
                                                 : std::to_string(bits) + "-bit") +
                   " pixels");
    }
    const uint16_t setup_w = Le<uint16_t>(s + kSImWidth), setup_h = Le<uint16_t>(s + kSImHeight);
    if ((setup_w != 0 || setup_h != 0) && (setup_w != width_ || setup_h != height_)) {
      Inconsistent("the setup's image size " + std::to_string(setup_w) + "x" +
                   std::to_string(setup_h) + " is not the bitmap header's " + size);
    }
    // FFmpeg's demuxer and dimerlab's writer give packed images biBitCount 16; 10 says the same.
    if (pixels_ == Pixels::kPacked10 && bits != 16 && bits != 10) {
      Inconsistent("10-bit packed images with biBitCount " + std::to_string(bits) +
                   " (10 or 16 expected)");
    }
  }

  // The frames' own time stamps, from the tagged blocks between the setup and the offset table
  // (cine_time_stamps.h); none when the file has no such blocks or they lie outside it.
  void ReadFrameTimes(int64_t from, int64_t to) {
    // A TIME_ONLY block takes 8 bytes an image; the other blocks are as small: a larger span is
    // not read (no allocation a header's number can blow up).
    constexpr int64_t most = int64_t{1} << 20;
    if (to <= from || to - from > most + 16 * int64_t(count_)) return;
    std::vector<uint8_t> blocks(size_t(to - from));
    if (!ReadAt(from, blocks.data(), blocks.size())) return;
    info_.frame_times = CineFrameTimes(blocks.data(), blocks.size(), count_);
  }

  std::string PastEnd(const std::string& what) const {
    return what + " past the end of the file (" + std::to_string(size_) +
           " bytes: truncated or corrupt)";
  }

  // Decodes image `index` into *out as stored (a mosaic or BGR for colour files); returns the
  // reason when it cannot.
  std::string ReadPixels(size_t index, cv::Mat* out) const {
    if (index >= count_) return "frame index past the last image";
    if (index >= offsets_.size()) return PastEnd("image offset table entry");
    const int64_t at = offsets_[index];
    // The table's offsets strictly increase: an entry that repeats or goes back (a duplicated
    // entry would make this frame a copy of another) is a damaged table, and this frame is not
    // trusted.
    if (index > 0 && at <= offsets_[index - 1]) {
      return "image offset " + std::to_string(at) + " does not follow frame " +
             std::to_string(index - 1) + "'s (" + std::to_string(offsets_[index - 1]) +
             "): corrupt offset table";
    }
    uint8_t word[4];
    if (!ReadAt(at, word, 4)) return PastEnd("image offset " + std::to_string(at));
    const uint32_t annotation = Le<uint32_t>(word);
    if (annotation < 8 || !ReadAt(at + annotation - 4, word, 4)) {
      return "corrupt annotation block (AnnotationSize " + std::to_string(annotation) +
             " at offset " + std::to_string(at) + ")";
    }
    const uint32_t image_size = Le<uint32_t>(word);
    const int64_t data = at + annotation;
    size_t stride = row_bytes_;
    size_t bytes = image_bytes_;
    // Assumption (FORMATS.md): rows are not padded; a file whose ImageSize says rows padded to
    // 4 bytes (the BMP rule) is read with that stride.
    const size_t padded = (row_bytes_ + 3) / 4 * 4;
    if (pixels_ != Pixels::kPacked10 && padded != row_bytes_ &&
        image_size == padded * size_t(height_)) {
      stride = padded;
      bytes = image_size;
    }
    // ImageSize repeats what the header says: when it does not, the annotation block's size is
    // wrong (a changed AnnotationSize shifts every pixel) and the pixels are not where it says.
    if (image_size != bytes) {
      return "ImageSize " + std::to_string(image_size) + " at the end of the annotation block " +
             "(AnnotationSize " + std::to_string(annotation) + ") is not the image's " +
             std::to_string(bytes) + " bytes: corrupt annotation block";
    }
    if (data > size_ || int64_t(bytes) > size_ - data) {
      const int64_t present = std::max<int64_t>(0, size_ - data);
      return "image data past the end of the file (" + std::to_string(present) + " of " +
             std::to_string(bytes) + " bytes present: truncated)";
    }
    // The annotation and the image fit before the next frame's offset.
    if (index + 1 < offsets_.size() && offsets_[index + 1] > at &&
        int64_t(bytes) > offsets_[index + 1] - data) {
      return "annotation block (AnnotationSize " + std::to_string(annotation) + ") and image (" +
             std::to_string(bytes) + " bytes) at offset " + std::to_string(at) +
             " overrun the next frame's offset " + std::to_string(offsets_[index + 1]) +
             ": corrupt annotation block";
    }
    const int type = CV_MAKETYPE(pixels_ == Pixels::k8 ? CV_8U : CV_16U, channels_);
    cv::Mat img(height_, width_, type);
    const bool direct = pixels_ != Pixels::kPacked10 && !bottom_up_ && stride == row_bytes_;
    if (direct) {  // the file's bytes are the frame's: one read, no copy
      if (!ReadAt(data, img.data, bytes)) return "read error";
      *out = img;
      return "";
    }
    thread_local std::vector<uint8_t> raw;
    raw.resize(bytes);
    if (!ReadAt(data, raw.data(), bytes)) return "read error";
    if (pixels_ == Pixels::kPacked10) {
      Unpack10(raw.data(), size_t(width_) * size_t(height_), img.ptr<uint16_t>(0));
    } else {
      for (int r = 0; r < height_; ++r) {
        const int src = bottom_up_ ? height_ - 1 - r : r;
        std::memcpy(img.ptr(r), raw.data() + size_t(src) * stride, row_bytes_);
      }
    }
    *out = img;
    return "";
  }

  // The four mosaic phases' white balance, once per file, from the first readable frame (of the
  // first kBalanceFramesTried) with enough bright unsaturated cells (mosaic_grey.h).
  void FindMosaicBalance() {
    const double saturation =
        pixels_ == Pixels::kPacked10 ? 1023.0
        : pixels_ == Pixels::k8     ? 255.0
                                    : double((1u << std::clamp(info_.real_bpp, 9, 16)) - 1u);
    constexpr size_t kBalanceFramesTried = 16;
    for (size_t i = 0; i < std::min(count_, kBalanceFramesTried); ++i) {
      cv::Mat raw;
      if (!ReadPixels(i, &raw).empty()) continue;
      balance_ = EstimateMosaicBalance(raw, saturation);
      if (balance_.found()) break;
    }
    char text[160];
    std::snprintf(text, sizeof text, "%.4f %.4f %.4f %.4f (phases 00 01 10 11, %zu cells)",
                  balance_.ratio[0], balance_.ratio[1], balance_.ratio[2], balance_.ratio[3],
                  balance_.cells);
    info_.mosaic_balance = text;
  }

  // The frame the tracker sees: grey pixels as they are, colour ones made grey.
  cv::Mat Grey(const cv::Mat& img) const {
    if (mosaic_) return MosaicToGrey(img, balance_);
    if (channels_ == 3) {
      cv::Mat grey;
      cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
      return grey;
    }
    return img;
  }

  std::string path_, name_;
  int fd_ = -1;
  int64_t size_ = 0;
  int width_ = 0, height_ = 0;
  bool bottom_up_ = true;
  Pixels pixels_ = Pixels::k8;
  int channels_ = 1;      // 3: interpolated colour (BGR)
  bool mosaic_ = false;   // a colour sensor's raw mosaic
  uint32_t cfa_ = 0;      // SETUP.CFA as stored
  MosaicBalance balance_; // the mosaic's phases' white balance (mosaic_grey.h)
  size_t row_bytes_ = 0, image_bytes_ = 0, count_ = 0, next_ = 0;
  std::vector<int64_t> offsets_;
  RecordingInfo info_;
};

}  // namespace

std::unique_ptr<FrameSource> OpenCine(const std::string& path) {
  return std::make_unique<CineSource>(path);
}

}  // namespace dimer::tracking
