#include "tracking/io/bmp_decode.h"

#include <cstring>

namespace dimer::tracking {
namespace {

uint32_t U32(const uint8_t* p) { return uint32_t(p[0]) | p[1] << 8 | p[2] << 16 | uint32_t(p[3]) << 24; }
uint16_t U16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }

}  // namespace

bool DecodeGreyBmp(const uint8_t* b, size_t size, cv::Mat* image) {
  // BITMAPFILEHEADER (14 bytes) + BITMAPINFOHEADER (40 bytes or a later, longer version).
  if (size < 54 || b[0] != 'B' || b[1] != 'M') return false;
  const uint32_t pixels_at = U32(b + 10), info_size = U32(b + 14);
  const int32_t width = int32_t(U32(b + 18)), height = int32_t(U32(b + 22));
  if (info_size < 40 || info_size > size - 14) return false;
  if (U16(b + 26) != 1 || U16(b + 28) != 8 || U32(b + 30) != 0) return false;  // 8 bit, BI_RGB
  if (width < 1 || width > 65535 || height == 0 || height < -65535 || height > 65535) return false;
  const uint32_t colours = U32(b + 46) == 0 ? 256 : U32(b + 46);
  if (colours > 256) return false;
  const size_t palette_at = 14 + size_t(info_size);
  if (palette_at + 4 * size_t(colours) > size) return false;
  for (uint32_t i = 0; i < colours; ++i) {  // grey palette only: the pixel byte is the value
    const uint8_t* e = b + palette_at + 4 * i;
    if (e[0] != i || e[1] != i || e[2] != i) return false;
  }
  const int rows = height < 0 ? -height : height;
  const size_t stride = (size_t(width) + 3) / 4 * 4;
  if (pixels_at < palette_at || pixels_at > size || stride * size_t(rows) > size - pixels_at) {
    return false;
  }
  cv::Mat img(rows, width, CV_8UC1);
  for (int r = 0; r < rows; ++r) {
    const uint8_t* src = b + pixels_at + stride * size_t(height > 0 ? rows - 1 - r : r);
    if (colours < 256) {  // a value outside a short palette: let OpenCV decide what it means
      for (int c = 0; c < width; ++c) {
        if (src[c] >= colours) return false;
      }
    }
    std::memcpy(img.ptr(r), src, size_t(width));
  }
  *image = img;
  return true;
}

}  // namespace dimer::tracking
