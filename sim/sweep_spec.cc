#include "sim/sweep_spec.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/trim.h"
#include "sim/constants.h"

namespace dimer::sim {

const std::vector<SweepParamInfo>& SweepParams() {
  static const std::vector<SweepParamInfo> kParams = {
      {"ar", "--ar", "1", &SimOptions::ar},
      {"freq", "--freq", "Hz", &SimOptions::freq_hz},
      {"gamma", "--gamma", "1", &SimOptions::gamma},
      {"tilt_deg", "--tilt-deg", "deg", &SimOptions::tilt_deg},
      {"eps", "--eps", "1", &SimOptions::eps},
      {"mu", "--mu", "1", &SimOptions::mu},
      {"mu_s", "--mu-s", "1", &SimOptions::mu_s},
      {"mu_hat", "--mu-hat", "1", &SimOptions::mu_hat},
      {"mu_hat_s", "--mu-hat-s", "1", &SimOptions::mu_hat_s},
      {"diameter", "--diameter", "m", &SimOptions::diameter_m},
  };
  return kParams;
}

const std::vector<std::pair<std::string, SweepInit>>& SweepInitNames() {
  static const std::vector<std::pair<std::string, SweepInit>> kNames = {
      {"drift", SweepInit::kDrift}, {"jump", SweepInit::kJump}, {"flutter", SweepInit::kFlutter},
      {"rest", SweepInit::kRest},   {"drop", SweepInit::kDrop}};
  return kNames;
}

namespace {

// A double as %.17g: read back, the same double.
std::string ExactNum(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

double ParseNumber(const std::string& flag, const std::string& whole, const std::string& item) {
  const char* s = item.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(s, &end);
  if (item.empty() || end == s || *end != '\0' || !std::isfinite(x) || errno == ERANGE) {
    throw UsageError(flag + ": \"" + whole + "\": \"" + item +
                     "\" is not a finite number (expected a value, a list v1,v2,... or a range "
                     "a:b:step)");
  }
  return x;
}

std::vector<std::string> Split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string item;
  std::stringstream ss(text);
  while (std::getline(ss, item, sep)) out.push_back(item);
  if (!text.empty() && text.back() == sep) out.push_back("");
  return out;
}

// splitmix64 (Steele, Lea, Flood 2014): a fixed, portable generator, so a drop state depends on
// (seed, index) alone and not on the standard library's distributions.
uint64_t SplitMix(uint64_t& s) {
  uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
double Uniform(uint64_t& s, double lo, double hi) {
  const double u = static_cast<double>(SplitMix(s) >> 11) * 0x1.0p-53;  // [0, 1)
  return lo + (hi - lo) * u;
}

}  // namespace

std::vector<double> ParseAxisValues(const std::string& flag, const std::string& text) {
  std::vector<double> values;
  if (text.find(':') != std::string::npos) {
    const std::vector<std::string> parts = Split(text, ':');
    if (parts.size() != 3) {
      throw UsageError(flag + ": \"" + text + "\": a range is a:b:step (three numbers)");
    }
    const double a = ParseNumber(flag, text, parts[0]);
    const double b = ParseNumber(flag, text, parts[1]);
    const double step = ParseNumber(flag, text, parts[2]);
    if (step == 0) throw UsageError(flag + ": \"" + text + "\": step 0 (expected a step != 0)");
    if ((b - a) / step < 0) {
      throw UsageError(flag + ": \"" + text + "\": empty range (" + parts[1] +
                       " cannot be reached from " + parts[0] + " by steps of " + parts[2] + ")");
    }
    // The end is included when (b - a)/step is whole up to rounding (3:4:0.1 has 11 values).
    const double count = std::floor((b - a) / step + 1e-9) + 1;
    if (!(count <= static_cast<double>(kMaxSweepPoints))) {
      throw UsageError(flag + ": \"" + text + "\": more than " + std::to_string(kMaxSweepPoints) +
                       " values");
    }
    for (long k = 0; k < static_cast<long>(count); ++k) values.push_back(a + k * step);
    return values;
  }
  for (const std::string& item : Split(text, ',')) values.push_back(ParseNumber(flag, text, item));
  if (values.empty()) throw UsageError(flag + ": empty value list");
  return values;
}

Shard ParseShard(const std::string& text) {
  Shard s;
  const std::vector<std::string> parts = Split(text, '/');
  auto whole = [&](const std::string& p, long* out) {
    char* end = nullptr;
    errno = 0;
    *out = std::strtol(p.c_str(), &end, 10);
    return !p.empty() && *end == '\0' && errno == 0;
  };
  if (parts.size() != 2 || !whole(parts[0], &s.k) || !whole(parts[1], &s.n) || s.n < 1 ||
      s.k < 1 || s.k > s.n) {
    throw UsageError("--shard: \"" + text + "\": expected K/N with 1 <= K <= N (shard K of N)");
  }
  return s;
}

size_t SweepSpec::PointCount() const {
  size_t n = 1;
  for (const SweepAxis& a : axes) n *= a.values.size();
  return n;
}

std::vector<double> SweepSpec::PointValues(size_t i) const {
  std::vector<double> v(axes.size());
  for (size_t k = axes.size(); k-- > 0;) {  // the last axis varies fastest
    const size_t n = axes[k].values.size();
    v[k] = axes[k].values[i % n];
    i /= n;
  }
  return v;
}

std::array<double, 6> SweepSpec::DropState(size_t i) const {
  // Released at rest-ish from a random height and angle: the lower sphere 0.1 .. 1 d above the
  // plate's highest position, |theta| <= 0.5 rad, velocities up to 0.05 g/f and a spin up to
  // 0.5 (g/f)/(half length). Drawn from (seed, i) only.
  const SimOptions o = PointOptionsNoInit(i);
  const Model m = Model::FromOptions(o);
  uint64_t s = seed ^ (0x5851f42d4c957f2dULL * (i + 1));
  const double vs = m.vel_scale;
  const double th = Uniform(s, -0.5, 0.5);
  const double gap = Uniform(s, 0.1, 1.0) * o.diameter_m;
  // Above the plate's highest point under the dimer: on a tilted plate the surface rises by
  // |tan alpha| per unit of x within the dimer's reach, and the stroke along the normal is
  // amp / cos alpha high (both 0 and amp on a level plate, so level drops are unchanged).
  const double reach = m.A * m.R * std::abs(std::cos(th)) + m.R;
  const double tilt_rise = reach * std::abs(m.sin_a / m.cos_a) + m.amp * (1 / m.cos_a - 1);
  const double z = m.R + m.A * m.R * std::abs(std::sin(th)) + m.amp + tilt_rise + gap;
  const double u = Uniform(s, -0.05, 0.05) * vs;
  const double v = Uniform(s, -0.05, 0.05) * vs;
  const double w = Uniform(s, -0.5, 0.5) * vs / (m.A * m.R);
  return {0.0, z, th, u, v, w};
}

SimOptions SweepSpec::PointOptionsNoInit(size_t i) const {
  SimOptions o = base;
  const std::vector<double> v = PointValues(i);
  for (size_t k = 0; k < axes.size(); ++k) {
    for (const SweepParamInfo& p : SweepParams()) {
      if (axes[k].name == p.name) o.*(p.field) = v[k];
    }
  }
  if (diameter_scales_with_f) {
    const double r = kDefaultLiftFreqHz / o.freq_hz;
    o.diameter_m *= r * r;
    if (std::isnan(o.lift)) o.lift = kDefaultLift;
  }
  o.cycles = static_cast<double>(transient + periods);
  o.duration_s = 0;
  o.fps = o.freq_hz;  // one sample per period: the state at the window's end
  return o;
}

SimOptions SweepSpec::PointOptions(size_t i) const {
  SimOptions o = PointOptionsNoInit(i);
  switch (init) {
    case SweepInit::kDrift: o.init = InitKind::kDrift; break;
    case SweepInit::kJump: o.init = InitKind::kJump; break;
    case SweepInit::kFlutter: o.init = InitKind::kFlutter; break;
    case SweepInit::kRest: o.init = InitKind::kRest; break;
    case SweepInit::kDrop: o.init_state = DropState(i); break;
  }
  return o;
}

void SweepSpec::Check() const {
  if (periods < 1 || periods > kMaxPeriods) {
    throw UsageError("--periods: " + std::to_string(periods) + ": expected 1 to 1e9");
  }
  if (transient < 0 || transient > kMaxPeriods) {
    throw UsageError("--transient: " + std::to_string(transient) + ": expected 0 to 1e9");
  }
  const size_t n = PointCount();
  if (n == 0) throw UsageError("sweep: the grid has no point");
  if (n > kMaxSweepPoints) {
    throw UsageError("sweep: " + std::to_string(n) + " points; at most " +
                     std::to_string(kMaxSweepPoints));
  }
  for (size_t i = 0; i < n; ++i) {
    const std::vector<std::string> errors = PointOptionsNoInit(i).Check();
    if (errors.empty()) continue;
    std::string msg = "invalid sweep settings: ";  // every point shares them: no axis varies
    if (!axes.empty()) {
      msg = "invalid sweep point " + std::to_string(i) + " (";
      const std::vector<double> v = PointValues(i);
      for (size_t k = 0; k < axes.size(); ++k) {
        msg += (k ? " " : "") + axes[k].name + "=" + ExactNum(v[k]);
      }
      msg += "): ";
    }
    for (size_t k = 0; k < errors.size(); ++k) msg += (k ? "; " : "") + errors[k];
    throw UsageError(msg);
  }
}

std::string SweepSpec::Canonical() const {
  std::ostringstream s;
  for (const SweepParamInfo& p : SweepParams()) {
    s << p.name << " = ";
    const SweepAxis* axis = nullptr;
    for (const SweepAxis& a : axes) {
      if (a.name == p.name) axis = &a;
    }
    if (axis) {
      for (size_t k = 0; k < axis->values.size(); ++k) s << (k ? "," : "") << ExactNum(axis->values[k]);
    } else {
      s << ExactNum(base.*(p.field));
    }
    s << "\n";
  }
  s << "periods = " << periods << "\n";
  s << "transient = " << transient << "\n";
  std::string init_name;
  for (const auto& [name, kind] : SweepInitNames()) {
    if (kind == init) init_name = name;
  }
  s << "init = " << init_name << "\n";
  if (init == SweepInit::kDrop) s << "seed = " << seed << "\n";
  if (init == SweepInit::kDrift) {
    s << "lift = " << (std::isnan(base.lift) ? "default" : ExactNum(base.lift)) << "\n";
    s << "release_phase = " << ExactNum(base.release_phase) << "\n";
  }
  s << "diameter_scaling = " << (diameter_scales_with_f ? "inverse_f2" : "fixed") << "\n";
  s << "plate_phase = " << ExactNum(base.plate_phase) << "\n";
  s << "restitution = " << (base.restitution == RestitutionLaw::kNewton ? "newton" : "capped")
    << "\n";
  s << "collapse_vc = " << ExactNum(base.collapse_rel) << "\n";
  s << "contact_tol = " << ExactNum(base.contact_tol) << "\n";
  s << "gap_tol = " << ExactNum(base.gap_tol) << "\n";
  s << "max_events_per_period = " << ExactNum(base.max_events_per_period) << "\n";
  return s.str();
}

}  // namespace dimer::sim

namespace dimer::sim {
namespace {

using dimer::Trim;

// "--tilt-deg" and "tilt-deg" -> "tilt_deg".
std::string Normalise(std::string name) {
  while (!name.empty() && name[0] == '-') name.erase(0, 1);
  for (char& c : name) {
    if (c == '-') c = '_';
  }
  return name;
}

long ParseWhole(const std::string& where, const std::string& name, const std::string& value) {
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || errno != 0) {
    throw UsageError(where + name + ": \"" + value + "\": expected a whole number");
  }
  return x;
}

double ParseOne(const std::string& where, const std::string& name, const std::string& value) {
  const std::vector<double> v = ParseAxisValues(where + name, value);
  if (v.size() != 1) throw UsageError(where + name + ": \"" + value + "\": expected one number");
  return v[0];
}

}  // namespace

std::vector<std::string> SpecSettingNames() {
  std::vector<std::string> names;
  for (const SweepParamInfo& p : SweepParams()) names.push_back(p.name);
  for (const char* n : {"periods", "transient", "init", "seed", "lift", "release_phase",
                        "diameter_scaling", "plate_phase", "restitution", "collapse_vc",
                        "contact_tol", "gap_tol", "max_events_per_period"}) {
    names.push_back(n);
  }
  return names;
}

void SetSpecValue(SweepSpec* spec, const std::string& raw_name, const std::string& raw_value,
                  const std::string& where) {
  const std::string name = Normalise(Trim(raw_name));
  const std::string value = Trim(raw_value);
  for (const SweepParamInfo& p : SweepParams()) {
    if (name != p.name) continue;
    std::vector<double> values = ParseAxisValues(where + p.flag, value);
    auto it = spec->axes.begin();
    for (; it != spec->axes.end(); ++it) {
      if (it->name == name) break;
    }
    if (values.size() == 1) {  // a fixed value, not an axis
      if (it != spec->axes.end()) spec->axes.erase(it);
      spec->base.*(p.field) = values[0];
      return;
    }
    if (it != spec->axes.end()) {
      it->values = std::move(values);
      return;
    }
    spec->axes.push_back({p.name, std::move(values)});
    // Keep SweepParams() order whatever the order of the settings.
    std::vector<SweepAxis> ordered;
    for (const SweepParamInfo& q : SweepParams()) {
      for (const SweepAxis& a : spec->axes) {
        if (a.name == q.name) ordered.push_back(a);
      }
    }
    spec->axes = std::move(ordered);
    return;
  }
  if (name == "periods") {
    spec->periods = ParseWhole(where, "--periods", value);
  } else if (name == "transient") {
    spec->transient = ParseWhole(where, "--transient", value);
  } else if (name == "seed") {
    char* end = nullptr;
    errno = 0;
    const unsigned long long s = std::strtoull(value.c_str(), &end, 10);
    if (value.empty() || value[0] == '-' || *end != '\0' || errno != 0) {
      throw UsageError(where + "--seed: \"" + value + "\": expected a whole number >= 0");
    }
    spec->seed = s;
  } else if (name == "init") {
    std::string known;
    for (const auto& [n, kind] : SweepInitNames()) {
      if (n == value) {
        spec->init = kind;
        return;
      }
      known += (known.empty() ? "" : ", ") + n;
    }
    throw UsageError(where + "--init: \"" + value + "\": expected one of " + known);
  } else if (name == "lift") {
    spec->base.lift = value == "default" ? std::numeric_limits<double>::quiet_NaN()
                                         : ParseOne(where, "--lift", value);
  } else if (name == "release_phase") {
    spec->base.release_phase = ParseOne(where, "--release-phase", value);
  } else if (name == "diameter_scaling") {
    if (value != "fixed" && value != "inverse_f2") {
      throw UsageError(where + "--diameter-scaling: \"" + value +
                       "\": expected fixed or inverse_f2");
    }
    spec->diameter_scales_with_f = value == "inverse_f2";
  } else if (name == "plate_phase") {
    spec->base.plate_phase = ParseOne(where, "--plate-phase", value);
  } else if (name == "restitution") {
    bool found = false;
    for (const auto& [n, law] : RestitutionLawNames()) {
      if (n == value) {
        spec->base.restitution = law;
        found = true;
      }
    }
    if (!found) {
      throw UsageError(where + "--restitution: \"" + value + "\": expected capped or newton");
    }
  } else if (name == "collapse_vc") {
    spec->base.collapse_rel = ParseOne(where, "--collapse-vc", value);
  } else if (name == "contact_tol") {
    spec->base.contact_tol = ParseOne(where, "--contact-tol", value);
  } else if (name == "gap_tol") {
    spec->base.gap_tol = ParseOne(where, "--gap-tol", value);
  } else if (name == "max_events_per_period") {
    spec->base.max_events_per_period = ParseOne(where, "--max-events-per-period", value);
  } else {
    std::string known;
    for (const std::string& n : SpecSettingNames()) known += (known.empty() ? "" : ", ") + n;
    throw UsageError(where + "unknown sweep parameter \"" + Trim(raw_name) + "\" (known: " +
                     known + ")");
  }
}

SweepSpec ParseSweepSpec(const std::string& text, const std::string& source) {
  SweepSpec spec;
  std::stringstream ss(text);
  std::string line;
  int number = 0;
  while (std::getline(ss, line)) {
    ++number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    line = Trim(line);
    if (line.empty() || line == "[sweep]") continue;
    const std::string where = source + ":" + std::to_string(number) + ": ";
    const size_t eq = line.find('=');
    if (eq == std::string::npos) {
      throw UsageError(where + "\"" + line + "\": expected name = value");
    }
    SetSpecValue(&spec, line.substr(0, eq), line.substr(eq + 1), where);
  }
  return spec;
}

SweepSpec ReadSweepSpecFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path + ": cannot read the sweep spec: " + std::strerror(errno));
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  std::fclose(f);
  return ParseSweepSpec(text, path);
}

}  // namespace dimer::sim
