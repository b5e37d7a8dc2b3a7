#pragma once
// A parameter sweep's grid (docs/FORMATS.md, "Sweeps"): which simulator parameters vary over
// which values, what is held fixed, how long each point runs and how it starts. A spec is
// parsed once, checked point by point before any work, and has one canonical text form: the
// sweep file stores it, the resume journal and `dimerlab merge` compare it, so "the same sweep"
// means "the same canonical text".
//
// Grid order: the axes in the fixed order of SweepParams() (ar first, diameter last), the last
// axis varying fastest (row-major). Point i of the grid is the same point whatever the shard,
// thread count or machine.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/model.h"

namespace dimer::sim {

// A parameter a sweep can vary: its name in specs and files, its flag, unit and SimOptions field.
struct SweepParamInfo {
  const char* name;   // "ar", "tilt_deg", ... (the sim file's attribute name)
  const char* flag;   // "--ar", "--tilt-deg", ...
  const char* units;  // as in sim files
  double SimOptions::*field;
};
const std::vector<SweepParamInfo>& SweepParams();

// How each point starts: the simulator's --init kinds, or `drop`: released from a random lab
// state drawn from (seed, point index) alone (SweepSpec::DropState), so any shard reproduces it.
enum class SweepInit { kDrift, kJump, kFlutter, kRest, kDrop };
const std::vector<std::pair<std::string, SweepInit>>& SweepInitNames();

struct SweepAxis {
  std::string name;            // a SweepParams() name
  std::vector<double> values;  // in order; at least one
};

// Values of one axis from "a:b:step" (a, a+step, ... up to b inclusive, each computed as
// a + k step, never accumulated), "v1,v2,..." or "v". UsageError naming `flag` for an empty
// range, a zero or wrong-signed step, a non-number, or more than kMaxSweepPoints values.
std::vector<double> ParseAxisValues(const std::string& flag, const std::string& text);
// A million points of 300 periods is ~2 h of CPU (bench_sweep: 8 ms a point). The spec's checks
// and its canonical text visit every point: ten million took 14 s under the fuzzer's sanitizers,
// past its 10 s limit (fuzz_sweep_spec; SweepSpec.BadSpecsAreRejectedWithOneClearLine).
inline constexpr size_t kMaxSweepPoints = 1'000'000;

struct SweepSpec {
  SimOptions base;              // the fixed parameters (every field an axis does not set)
  std::vector<SweepAxis> axes;  // in SweepParams() order, each name at most once
  long periods = 100;           // periods measured per point (the mode window)
  long transient = 50;          // periods simulated first and discarded
  SweepInit init = SweepInit::kDrift;
  uint64_t seed = 1;            // drop: the random initial states
  // d ∝ 1/f²: each point's diameter is (its diameter) x (25 Hz / f)², with the drift release's
  // lift held at kDefaultLift d unless given, so every length scales as g T² and ⟨u⟩ f/g must
  // not depend on f (docs/MODEL.md, check 7).
  bool diameter_scales_with_f = false;

  size_t PointCount() const;
  // The values of every axis at point i (axes order).
  std::vector<double> PointValues(size_t i) const;
  // The simulator's options at point i: base + axis values, cycles = transient + periods,
  // one output sample per period (the window's end state), the initial condition.
  SimOptions PointOptions(size_t i) const;
  // The same without the initial condition (what Check() and DropState() look at).
  SimOptions PointOptionsNoInit(size_t i) const;
  // Every point's options checked (SimOptions::Check): UsageError naming the first bad point
  // and its values; also periods >= 1, transient >= 0, at least one point.
  void Check() const;
  // One `name = value` line per setting, in a fixed order, numbers as %.17g: the identity of the
  // sweep (shards and journals must carry the same text).
  std::string Canonical() const;
  // The lab state x, z, theta, u, v, omega of a drop at point i (SweepInit::kDrop).
  std::array<double, 6> DropState(size_t i) const;
};

// Sets one setting of a spec from its text form, as written in spec files and by Canonical():
// a parameter of SweepParams() (a value, list or range; names with '-' or '_', with or without
// the leading --), periods, transient, init, seed, lift ("default" or a number),
// release_phase, diameter_scaling (fixed | inverse_f2), plate_phase, restitution (capped |
// newton), collapse_vc, contact_tol, gap_tol, max_events_per_period. UsageError prefixed with
// `where` (a file and line, or a flag) for an unknown name or a bad value.
void SetSpecValue(SweepSpec* spec, const std::string& name, const std::string& value,
                  const std::string& where);
// The names SetSpecValue accepts, in Canonical() order (for messages and the CLI).
std::vector<std::string> SpecSettingNames();
// A whole spec file (or Canonical() text): `name = value` lines, `#` comments, blank lines, an
// optional `[sweep]` header. Errors name `source` and the line.
SweepSpec ParseSweepSpec(const std::string& text, const std::string& source);
// Reads and parses a spec file; InputError naming it when it cannot be read.
SweepSpec ReadSweepSpecFile(const std::string& path);

// Shard K of N (1-based): the points i with i mod N == K - 1, in grid order.
struct Shard {
  long k = 1, n = 1;
  bool Contains(size_t i) const { return static_cast<long>(i % n) == k - 1; }
  std::string ToString() const { return std::to_string(k) + "/" + std::to_string(n); }
};
// "K/N" with 1 <= K <= N; UsageError naming --shard otherwise.
Shard ParseShard(const std::string& text);

}  // namespace dimer::sim
