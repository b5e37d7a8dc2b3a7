// libFuzzer target: the numbers a user types (--init-state, and a sweep's axis values: lists and
// ranges). UsageError is the expected answer to bad text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "sim/run_sim.h"
#include "sim/sweep_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)dimer::sim::ParseInitState(text);
  } catch (const dimer::UsageError&) {
  }
  try {
    (void)dimer::sim::ParseAxisValues("--ar", text);
  } catch (const dimer::UsageError&) {
  }
  return 0;
}
