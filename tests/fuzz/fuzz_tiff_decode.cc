// libFuzzer target: the direct plain-TIFF decoder (tracking/io/tiff_decode.h) on any bytes: it
// decodes or declines, never reads outside the buffer.
#include <cstddef>
#include <cstdint>

#include "tracking/io/tiff_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cv::Mat image;
  (void)dimer::tracking::DecodePlainTiff(data, size, &image);
  return 0;
}
