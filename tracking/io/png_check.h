#pragma once
// A PNG's structure, checked before decoding: the signature, every chunk wholly inside the file
// with a correct CRC-32, IHDR first and IEND at the end. Given a truncated or corrupt PNG, libpng
// prints its own message on stderr before failing; checking first lets the tracker skip the
// frame with one line of its own that says what is wrong. Costs one CRC pass over the file
// (zlib's crc32, a few GB/s), small beside decoding it.
#include <cstddef>
#include <cstdint>
#include <string>

namespace dimer::tracking {

// True when the bytes start with the PNG signature.
bool LooksLikePng(const uint8_t* data, size_t size);

// "" when the structure is sound; otherwise what is wrong ("truncated: chunk IDAT runs past the
// end of the file", "chunk IDAT fails its CRC (corrupt data)", ...).
std::string PngStructureProblem(const uint8_t* data, size_t size);

}  // namespace dimer::tracking
