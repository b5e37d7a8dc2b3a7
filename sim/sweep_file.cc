#include "sim/sweep_file.h"

#include <cmath>
#include <cstdio>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/h5_file.h"
#include "common/provenance.h"

namespace dimer::sim {
namespace {

constexpr const char* kModeDescription =
    "mode over the measured window (common/modes.h): rest, drift, jump, flutter or irregular";

std::vector<double> Column(const std::vector<PointResult>& rows, double PointResult::*f) {
  std::vector<double> v;
  for (const PointResult& p : rows) v.push_back(p.*f);
  return v;
}

void Doubles(H5Writer& w, const std::string& name, const std::vector<double>& v,
             const std::string& units, const std::string& description) {
  w.WriteDoubles(name, v, {v.size()}, units);
  w.SetAttr(name, "description", description);
}

void Strings(H5Writer& w, const std::string& name, const std::vector<std::string>& v,
             const std::string& description) {
  w.WriteStrings(name, v);
  w.SetAttr(name, "description", description);
}

}  // namespace

void WriteSweepFile(const std::string& path, bool force, const SweepSpec& spec,
                    const Shard& shard, const std::vector<PointResult>& rows) {
  AtomicOutput out(path, force);
  {
    H5Writer w(out.temp_path());
    WriteProvenance(w, "sweep",
                    {{"spec", spec.Canonical()},
                     {"shard", shard.ToString()},
                     {"point_count", static_cast<int64_t>(spec.PointCount())},
                     {"rows", static_cast<int64_t>(rows.size())},
                     {"periods", static_cast<int64_t>(spec.periods)},
                     {"transient", static_cast<int64_t>(spec.transient)}},
                    {{"point_count", "1"}, {"rows", "1"}, {"periods", "period"},
                     {"transient", "period"}});
    const hsize_t n = rows.size();
    std::vector<int64_t> index;
    for (const PointResult& p : rows) index.push_back(p.index);
    w.WriteInt64("/points/index", index, {n});
    w.SetAttr("/points/index", "description",
              "grid index of the row (the last swept parameter varies fastest)");
    w.SetAttr("/points/index", "units", "1");
    // Every parameter of SweepParams() at every row, as the simulator used it (the diameter
    // after --diameter-scaling).
    std::vector<SimOptions> opts;
    for (const PointResult& p : rows) opts.push_back(spec.PointOptionsNoInit(p.index));
    for (const SweepParamInfo& info : SweepParams()) {
      std::vector<double> v;
      for (const SimOptions& o : opts) v.push_back(o.*(info.field));
      bool swept = false;
      for (const SweepAxis& a : spec.axes) swept = swept || a.name == info.name;
      Doubles(w, std::string("/points/") + info.name, v, info.units,
              std::string("the simulator's ") + info.flag + " at this point (" +
                  (swept ? "swept" : "fixed") + ")");
    }
    std::vector<std::string> mode, impact_type, error;
    std::vector<int8_t> bouncing, survived, orbit;
    std::vector<double> ipp, rest;
    for (const PointResult& p : rows) {
      mode.push_back(p.mode);
      impact_type.push_back(p.impact_type);
      error.push_back(p.error);
      bouncing.push_back(p.bouncing_sphere);
      survived.push_back(p.drift_survived);
      orbit.push_back(p.orbit_periods);
      ipp.insert(ipp.end(), p.impacts_per_period.begin(), p.impacts_per_period.end());
      rest.insert(rest.end(), p.rest_fraction.begin(), p.rest_fraction.end());
    }
    Strings(w, "/results/mode", mode, kModeDescription);
    w.WriteInt8("/results/bouncing_sphere", bouncing, {n});
    w.SetAttr("/results/bouncing_sphere", "description", "drift: the sphere that bounces");
    w.SetAttr("/results/bouncing_sphere", "codes", "-1=none,0=left,1=right");
    Doubles(w, "/results/drift_speed", Column(rows, &PointResult::drift_speed), "m/s",
            "mean CM velocity over the window, positive toward the bouncing end in drift");
    Doubles(w, "/results/drift_speed_err", Column(rows, &PointResult::drift_speed_err), "m/s",
            "standard error of drift_speed from the period-to-period scatter");
    Doubles(w, "/results/drift_scaled", Column(rows, &PointResult::drift_scaled), "1",
            "<u> f / g");
    Doubles(w, "/results/drift_scaled_err", Column(rows, &PointResult::drift_scaled_err), "1",
            "standard error of drift_scaled");
    w.WriteInt8("/results/drift_survived", survived, {n});
    w.SetAttr("/results/drift_survived", "description",
              "drift release: whether the released (right) end still drifts over the window");
    w.SetAttr("/results/drift_survived", "codes",
              "-1=not a drift release,0=drift lost,1=drift survived");
    w.WriteInt8("/results/orbit_periods", orbit, {n});
    w.SetAttr("/results/orbit_periods", "description",
              "the orbit's period over the window in plate periods (1..4; 0: none up to 4 repeats)");
    w.SetAttr("/results/orbit_periods", "units", "periods");
    Doubles(w, "/results/events_per_period", Column(rows, &PointResult::events_per_period),
            "1/period", "simulator events per period over the window");
    w.WriteDoubles("/results/impacts_per_period", ipp, {n, 2}, "1/period", "left,right");
    w.SetAttr("/results/impacts_per_period", "description",
              "significant impacts per period of each sphere over the window");
    w.WriteDoubles("/results/rest_fraction", rest, {n, 2}, "1", "left,right");
    w.SetAttr("/results/rest_fraction", "description",
              "fraction of the window each sphere rested on the plate");
    Strings(w, "/results/impact_type", impact_type,
            "the bouncing end's (drift; both ends otherwise) most frequent impact outcome: "
            "continuous_slide, slip_stick, slip_reversal, or none");
    Doubles(w, "/results/impact_type_fraction",
            Column(rows, &PointResult::impact_type_fraction), "1",
            "share of the window's impacts of that end with that outcome");
    Strings(w, "/results/error", error,
            "why the point's run stopped early (event storm); empty when it completed");
    w.Close();
  }
  out.Commit();
}

SweepFileContent ReadSweepFile(const std::string& path) {
  H5Reader r(path);
  const auto kind = r.AttrString("/", "kind");
  if (!kind || *kind != "sweep") {
    throw InputError(path + ": not a sweep file (kind " + (kind ? *kind : "missing") + ")");
  }
  SweepFileContent c;
  const auto spec = r.AttrString("/", "spec");
  const auto shard = r.AttrString("/", "shard");
  const auto count = r.AttrDouble("/", "point_count");
  if (!spec || !shard || !count) throw InputError(path + ": sweep file without spec/shard");
  c.spec = *spec;
  try {
    c.shard = ParseShard(*shard);
  } catch (const InputError&) {
    throw InputError(path + ": bad shard attribute \"" + *shard + "\"");
  }
  c.point_count = static_cast<long>(*count);
  const std::vector<int64_t> index = r.ReadInt64("/points/index");
  const size_t n = index.size();
  const auto mode = r.ReadStrings("/results/mode");
  const auto bouncing = r.ReadInt8("/results/bouncing_sphere");
  const auto ds = r.ReadDoubles("/results/drift_speed");
  const auto dse = r.ReadDoubles("/results/drift_speed_err");
  const auto sc = r.ReadDoubles("/results/drift_scaled");
  const auto sce = r.ReadDoubles("/results/drift_scaled_err");
  const auto surv = r.ReadInt8("/results/drift_survived");
  const auto orbit = r.ReadInt8("/results/orbit_periods");
  const auto epp = r.ReadDoubles("/results/events_per_period");
  const auto ipp = r.ReadDoubles("/results/impacts_per_period");
  const auto rest = r.ReadDoubles("/results/rest_fraction");
  const auto it = r.ReadStrings("/results/impact_type");
  const auto itf = r.ReadDoubles("/results/impact_type_fraction");
  const auto err = r.ReadStrings("/results/error");
  for (size_t len : {mode.size(), bouncing.size(), ds.size(), dse.size(), sc.size(), sce.size(),
                     surv.size(), orbit.size(), epp.size(), it.size(), itf.size(), err.size(), ipp.size() / 2,
                     rest.size() / 2}) {
    if (len != n) throw InputError(path + ": sweep datasets of different lengths");
  }
  for (size_t i = 0; i < n; ++i) {
    PointResult p;
    p.index = index[i];
    p.mode = mode[i];
    p.bouncing_sphere = bouncing[i];
    p.drift_speed = ds[i];
    p.drift_speed_err = dse[i];
    p.drift_scaled = sc[i];
    p.drift_scaled_err = sce[i];
    p.drift_survived = surv[i];
    p.orbit_periods = orbit[i];
    p.events_per_period = epp[i];
    p.impacts_per_period = {ipp[2 * i], ipp[2 * i + 1]};
    p.rest_fraction = {rest[2 * i], rest[2 * i + 1]};
    p.impact_type = it[i];
    p.impact_type_fraction = itf[i];
    p.error = err[i];
    c.rows.push_back(std::move(p));
  }
  return c;
}

void WriteSweepTsv(const std::string& path, bool force, const SweepSpec& spec,
                   const std::vector<PointResult>& rows) {
  AtomicOutput out(path, force);
  std::FILE* f = std::fopen(out.temp_path().c_str(), "w");
  if (!f) throw InputError(path + ": cannot write");
  std::fprintf(f, "# dimerlab sweep, %zu points; spec:", spec.PointCount());
  std::string canon = spec.Canonical();
  for (char& ch : canon) {
    if (ch == '\n') ch = ';';
  }
  std::fprintf(f, " %s\n#", canon.c_str());
  for (const SweepParamInfo& info : SweepParams()) std::fprintf(f, " %s[%s]", info.name, info.units);
  std::fprintf(f,
               " index mode bouncing_sphere drift_speed[m/s] drift_speed_err[m/s] drift_scaled "
               "drift_scaled_err drift_survived events_per_period[1/period] impacts_left "
               "impacts_right rest_left rest_right impact_type impact_type_fraction "
               "orbit_periods[periods]\n");
  for (const PointResult& p : rows) {
    const SimOptions o = spec.PointOptionsNoInit(p.index);
    for (const SweepParamInfo& info : SweepParams()) std::fprintf(f, "%.10g\t", o.*(info.field));
    std::fprintf(f, "%lld\t%s\t%d\t%.10g\t%.10g\t%.10g\t%.10g\t%d\t%.10g\t%.6g\t%.6g\t%.6g\t%.6g\t%s\t%.6g\t%d\n",
                 static_cast<long long>(p.index), p.mode.c_str(), p.bouncing_sphere,
                 p.drift_speed, p.drift_speed_err, p.drift_scaled, p.drift_scaled_err,
                 p.drift_survived, p.events_per_period, p.impacts_per_period[0],
                 p.impacts_per_period[1], p.rest_fraction[0], p.rest_fraction[1],
                 p.impact_type.c_str(), p.impact_type_fraction, p.orbit_periods);
  }
  if (std::fclose(f) != 0) throw InputError(path + ": cannot write");
  out.Commit();
}

}  // namespace dimer::sim
