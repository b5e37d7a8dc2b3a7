#include "tracking/io/bmp_decode.h"

#include <cstring>

namespace dimer::tracking {
namespace {

uint32_t U32(const uint8_t* p) { return uint32_t(p[0]) | p[1] << 8 | p[2] << 16 | uint32_t(p[3]) << 24; }
uint16_t U16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }

// What the headers say of an 8-bit grey BMP's pixels.
struct GreyBmpLayout {
  uint32_t pixels_at = 0;
  int32_t width = 0, height = 0;  // height > 0: the bottom row first
  uint32_t colours = 0;
  size_t palette_at = 0;
};

// BITMAPFILEHEADER (14 bytes) + BITMAPINFOHEADER (40 bytes or a later, longer version) of an
// uncompressed 8-bit image; false for anything else.
bool ReadHeaders(const uint8_t* b, size_t size, GreyBmpLayout* l) {
  if (size < 54 || b[0] != 'B' || b[1] != 'M') return false;
  l->pixels_at = U32(b + 10);
  const uint32_t info_size = U32(b + 14);
  l->width = int32_t(U32(b + 18));
  l->height = int32_t(U32(b + 22));
  if (info_size < 40 || info_size > size - 14) return false;
  if (U16(b + 26) != 1 || U16(b + 28) != 8 || U32(b + 30) != 0) return false;  // 8 bit, BI_RGB
  const int32_t w = l->width, h = l->height;
  if (w < 1 || w > 65535 || h == 0 || h < -65535 || h > 65535) return false;
  l->colours = U32(b + 46) == 0 ? 256 : U32(b + 46);
  l->palette_at = 14 + size_t(info_size);
  return l->colours <= 256 && l->palette_at + 4 * size_t(l->colours) <= size;
}

// A grey palette only: the pixel byte is the value.
bool GreyPalette(const uint8_t* b, const GreyBmpLayout& l) {
  for (uint32_t i = 0; i < l.colours; ++i) {
    const uint8_t* e = b + l.palette_at + 4 * i;
    if (e[0] != i || e[1] != i || e[2] != i) return false;
  }
  return true;
}

}  // namespace

bool DecodeGreyBmp(const uint8_t* b, size_t size, cv::Mat* image) {
  GreyBmpLayout l;
  if (!ReadHeaders(b, size, &l) || !GreyPalette(b, l)) return false;
  const int32_t width = l.width, height = l.height;
  const int rows = height < 0 ? -height : height;
  const size_t stride = (size_t(width) + 3) / 4 * 4;
  if (l.pixels_at < l.palette_at || l.pixels_at > size ||
      stride * size_t(rows) > size - l.pixels_at) {
    return false;
  }
  cv::Mat img(rows, width, CV_8UC1);
  for (int r = 0; r < rows; ++r) {
    const uint8_t* src = b + l.pixels_at + stride * size_t(height > 0 ? rows - 1 - r : r);
    if (l.colours < 256) {  // a value outside a short palette: let OpenCV decide what it means
      for (int c = 0; c < width; ++c) {
        if (src[c] >= l.colours) return false;
      }
    }
    std::memcpy(img.ptr(r), src, size_t(width));
  }
  *image = img;
  return true;
}

}  // namespace dimer::tracking
