// libFuzzer target: sweep spec text (ParseSweepSpec, then the checks a sweep runs before any
// work). A UsageError or InputError is the expected answer to bad text; anything else (another
// exception, a crash, a sanitizer report, a check that never ends) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "sim/sweep_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const dimer::sim::SweepSpec spec = dimer::sim::ParseSweepSpec(text, "fuzz.sweep");
    spec.Check();  // every point's options: bounded by kMaxSweepPoints
    (void)spec.Canonical();
    if (spec.PointCount() > 0) (void)spec.PointOptions(spec.PointCount() - 1);
  } catch (const dimer::UsageError&) {
  } catch (const dimer::InputError&) {
  }
  return 0;
}
