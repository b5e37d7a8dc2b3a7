// libFuzzer target: the lens calibration reader (tracking/io/lens_undistortion.h) on any text:
// a bad file is an InputError naming it, never a crash or a huge allocation.
#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tracking/io/lens_undistortion.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = dimer::fuzz::InputFile(data, size, ".yml");
  try {
    (void)dimer::tracking::ReadLensCalibration(path);
  } catch (const dimer::InputError&) {
  }
  return 0;
}
