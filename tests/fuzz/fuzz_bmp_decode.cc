// libFuzzer target: the direct grey BMP decoder (tracking/io/bmp_decode.h) on any bytes: it
// decodes or declines, never reads outside the buffer.
#include <cstddef>
#include <cstdint>

#include "tracking/io/bmp_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cv::Mat image;
  (void)dimer::tracking::DecodeGreyBmp(data, size, &image);
  return 0;
}
