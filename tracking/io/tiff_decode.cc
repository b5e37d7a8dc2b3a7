#include "tracking/io/tiff_decode.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <vector>

namespace dimer::tracking {
namespace {

uint16_t U16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }
uint32_t U32(const uint8_t* p) { return uint32_t(p[0]) | p[1] << 8 | p[2] << 16 | uint32_t(p[3]) << 24; }

// TIFF 6.0 tags and field types used here.
enum : uint16_t {
  kWidth = 256, kLength = 257, kBitsPerSample = 258, kCompression = 259, kPhotometric = 262,
  kFillOrder = 266, kStripOffsets = 273, kOrientation = 274, kSamplesPerPixel = 277,
  kRowsPerStrip = 278, kStripByteCounts = 279, kPlanarConfig = 284, kTileWidth = 322,
  kSampleFormat = 339
};
enum : uint16_t { kShort = 3, kLong = 4 };

struct Field {
  uint16_t type = 0;
  uint32_t count = 0;
  const uint8_t* value = nullptr;  // the 4-byte value field in the entry
};

// The one image file directory of a single-page little-endian TIFF: the tags used here.
struct Ifd {
  Field f[kSampleFormat + 1];
  bool seen[kSampleFormat + 1] = {};

  // One SHORT or LONG value held in the entry itself; `absent` without the tag, -1 otherwise.
  int64_t Single(uint16_t tag, uint32_t absent) const {
    if (!seen[tag]) return absent;
    if (f[tag].count != 1) return -1;
    return f[tag].type == kShort ? U16(f[tag].value) : f[tag].type == kLong ? U32(f[tag].value) : -1;
  }
};

bool ReadIfd(const uint8_t* b, size_t size, Ifd* d) {
  if (size < 8 || b[0] != 'I' || b[1] != 'I' || U16(b + 2) != 42) return false;
  const uint32_t ifd = U32(b + 4);
  if (ifd < 8 || ifd > size - 2) return false;
  const uint32_t entries = U16(b + ifd);
  if (size_t(ifd) + 2 + 12 * size_t(entries) + 4 > size) return false;
  if (U32(b + ifd + 2 + 12 * entries) != 0) return false;  // a second page: multi-page path
  for (uint32_t e = 0; e < entries; ++e) {
    const uint8_t* p = b + ifd + 2 + 12 * e;
    const uint16_t tag = U16(p);
    if (tag > kSampleFormat) continue;
    d->f[tag] = {U16(p + 2), U32(p + 4), p + 8};
    d->seen[tag] = true;
  }
  return true;
}

// An uncompressed grey image of 8 or 16 bits in strips, top row first.
struct PlainLayout {
  int64_t width = 0, height = 0, bits = 0, rows_per_strip = 0;
  uint32_t strips = 0;
};

bool PlainLayoutOf(const Ifd& d, PlainLayout* l) {
  l->width = d.Single(kWidth, 0);
  l->height = d.Single(kLength, 0);
  l->bits = d.Single(kBitsPerSample, 1);
  if (l->width < 1 || l->width > 65535 || l->height < 1 || l->height > 65535) return false;
  if (l->bits != 8 && l->bits != 16) return false;
  if (d.Single(kCompression, 1) != 1 || d.Single(kPhotometric, 99) != 1 ||
      d.Single(kSamplesPerPixel, 1) != 1 || d.Single(kPlanarConfig, 1) != 1 ||
      d.Single(kFillOrder, 1) != 1 || d.Single(kOrientation, 1) != 1 ||
      d.Single(kSampleFormat, 1) != 1 || d.seen[kTileWidth]) {
    return false;
  }
  l->rows_per_strip = std::min<int64_t>(d.Single(kRowsPerStrip, 0xFFFFFFFF), l->height);
  if (l->rows_per_strip < 1 || !d.seen[kStripOffsets] || !d.seen[kStripByteCounts]) return false;
  l->strips = uint32_t((l->height + l->rows_per_strip - 1) / l->rows_per_strip);
  return d.f[kStripOffsets].count == l->strips && d.f[kStripByteCounts].count == l->strips;
}

// Value i of a strip's offsets or counts: in the entry when they fit in 4 bytes, else in an
// array elsewhere in the file.
bool StripValue(const uint8_t* b, size_t size, const Field& fd, uint32_t i, uint64_t* out) {
  const size_t width_bytes = fd.type == kShort ? 2 : fd.type == kLong ? 4 : 0;
  if (width_bytes == 0) return false;
  const uint8_t* base = fd.value;
  if (size_t(fd.count) * width_bytes > 4) {
    const uint32_t at = U32(fd.value);
    if (at > size || size_t(fd.count) * width_bytes > size - at) return false;
    base = b + at;
  }
  *out = width_bytes == 2 ? U16(base + 2 * i) : U32(base + 4 * i);
  return true;
}

}  // namespace

bool DecodePlainTiff(const uint8_t* b, size_t size, cv::Mat* image) {
  Ifd d;
  PlainLayout l;
  if (!ReadIfd(b, size, &d) || !PlainLayoutOf(d, &l)) return false;
  const size_t row_bytes = size_t(l.width) * size_t(l.bits / 8);
  // Uncompressed: every pixel lies in the buffer, so an image larger than the file is refused
  // before it is allocated (a forged size asked for 8 GB; found by tests/fuzz/fuzz_tiff_decode).
  if (uint64_t(l.height) * row_bytes > size) return false;
  cv::Mat img(int(l.height), int(l.width), l.bits == 8 ? CV_8UC1 : CV_16UC1);
  for (uint32_t s = 0; s < l.strips; ++s) {
    uint64_t at = 0, count = 0;
    if (!StripValue(b, size, d.f[kStripOffsets], s, &at) ||
        !StripValue(b, size, d.f[kStripByteCounts], s, &count)) {
      return false;
    }
    const int64_t first = int64_t(s) * l.rows_per_strip;
    const int64_t rows = std::min<int64_t>(l.rows_per_strip, l.height - first);
    const uint64_t need = uint64_t(rows) * row_bytes;
    if (count < need || at > size || need > size - at) return false;
    std::memcpy(img.ptr(int(first)), b + at, need);  // rows are contiguous in a strip
  }
  *image = img;  // 16-bit samples are little-endian ("II"), as this host's
  return true;
}

bool TiffHasOnePage(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint8_t h[8];
  if (!in.read(reinterpret_cast<char*>(h), 8)) return false;
  const bool le = h[0] == 'I' && h[1] == 'I', be = h[0] == 'M' && h[1] == 'M';
  auto u16 = [&](const uint8_t* p) { return le ? uint16_t(p[0] | p[1] << 8) : uint16_t(p[0] << 8 | p[1]); };
  auto u32 = [&](const uint8_t* p) {
    return le ? U32(p) : uint32_t(p[0]) << 24 | p[1] << 16 | p[2] << 8 | uint32_t(p[3]);
  };
  if ((!le && !be) || u16(h + 2) != 42) return false;
  const uint32_t ifd = u32(h + 4);
  uint8_t n[2], next[4];
  if (!in.seekg(ifd) || !in.read(reinterpret_cast<char*>(n), 2)) return false;
  if (!in.seekg(std::streamoff(ifd) + 2 + 12 * std::streamoff(u16(n))) ||
      !in.read(reinterpret_cast<char*>(next), 4)) {
    return false;
  }
  return u32(next) == 0;
}

}  // namespace dimer::tracking
