#include "tracking/io/png_check.h"

#include <zlib.h>

#include <cstring>

namespace dimer::tracking {
namespace {

constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr size_t kChunkOverhead = 12;  // length (4), type (4), CRC (4)

uint32_t BigEndian32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

// Chunk type as text; '?' for bytes that are not letters (a corrupt length or type).
std::string TypeName(const uint8_t* p) {
  std::string name(4, '?');
  for (int i = 0; i < 4; ++i) {
    const bool letter = (p[i] >= 'A' && p[i] <= 'Z') || (p[i] >= 'a' && p[i] <= 'z');
    if (letter) name[i] = static_cast<char>(p[i]);
  }
  return name;
}

}  // namespace

bool LooksLikePng(const uint8_t* data, size_t size) {
  return size >= sizeof kSignature && std::memcmp(data, kSignature, sizeof kSignature) == 0;
}

std::string PngStructureProblem(const uint8_t* data, size_t size) {
  if (!LooksLikePng(data, size)) return "not a PNG (no PNG signature)";
  size_t at = sizeof kSignature;
  bool first = true;
  while (true) {
    if (size - at < kChunkOverhead) return "truncated: the file ends before its IEND chunk";
    const uint32_t length = BigEndian32(data + at);
    const std::string type = TypeName(data + at + 4);
    if (first && type != "IHDR") return "corrupt: the first chunk is not IHDR";
    first = false;
    if (length > size - at - kChunkOverhead) {
      return "truncated: chunk " + type + " runs past the end of the file";
    }
    // The CRC covers the type and the data.
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), data + at + 4, static_cast<uInt>(length + 4));
    if (crc != BigEndian32(data + at + 8 + length)) {
      return "corrupt: chunk " + type + " fails its CRC";
    }
    at += kChunkOverhead + length;
    if (type == "IEND") return "";
  }
}

}  // namespace dimer::tracking
