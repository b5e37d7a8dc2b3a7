#pragma once
// Small helpers shared by the simulator tests: the paper's model with overrides, and the
// DIMERLAB_TEST_SCALE knob that shortens long property tests under sanitizers.
#include <cstdlib>
#include <string>

#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim::testing {

inline SimOptions PaperOptions() { return SimOptions{}; }

inline Model PaperModel(double ar = 3.9) {
  SimOptions o;
  o.ar = ar;
  return Model::FromOptions(o);
}

// 1 normally; < 1 under sanitizers (set by ./dimerlab.sh sanitize).
inline double TestScale() {
  const char* s = std::getenv("DIMERLAB_TEST_SCALE");
  return s ? std::atof(s) : 1.0;
}
inline long Scaled(long n) { return std::max(1L, static_cast<long>(n * TestScale())); }

inline double KineticEnergy(const Model& m, const State& q) {
  return 0.5 * (q.u * q.u + q.v * q.v + q.w * q.w / m.inv_I);
}

}  // namespace dimer::sim::testing
