// libFuzzer target: the Phantom .cine reader (tracking/io/cine_source.h) on any bytes. A bad
// header is an InputError; a bad frame has its reason; nothing else (no crash, no read outside
// the file, no allocation a header's number can blow up).
#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "tests/fuzz/fuzz_input_file.h"
#include "tracking/io/cine_source.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = dimer::fuzz::InputFile(data, size, ".cine");
  try {
    auto source = dimer::tracking::OpenCine(path);
    (void)source->recording();
    for (size_t i = 0; i < source->size() && i < 8; ++i) (void)source->Read(i);
  } catch (const dimer::InputError&) {
  }
  return 0;
}
