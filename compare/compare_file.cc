#include "compare/compare_file.h"

#include <cmath>

#include "common/h5_file.h"

namespace dimer::compare {
namespace {

using Rows = std::vector<double>;

void WriteModes(H5Writer& w, const Periods& p) {
  const hsize_t k = p.timeline.size();
  Rows t0, t1, ipp, rf, drift;
  std::vector<std::string> label;
  std::vector<int8_t> bouncing;
  for (const ModeWindow& m : p.timeline) {
    t0.push_back(m.t_start);
    t1.push_back(m.t_end);
    label.push_back(m.summary.label);
    bouncing.push_back(static_cast<int8_t>(m.summary.bouncing_sphere));
    for (int s = 0; s < 2; ++s) {
      ipp.push_back(m.summary.impacts_per_period[s]);
      rf.push_back(m.summary.rest_fraction[s]);
    }
    drift.push_back(m.summary.drift_speed);
  }
  w.WriteDoubles("/modes/t_start", t0, {k}, "s");
  w.WriteDoubles("/modes/t_end", t1, {k}, "s");
  w.WriteStrings("/modes/label", label);
  w.WriteInt8("/modes/bouncing_sphere", bouncing, {k});
  w.SetAttr("/modes/bouncing_sphere", "codes", "-1 none, 0 left, 1 right");
  w.WriteDoubles("/modes/impacts_per_period", ipp, {k, 2}, "1/period");
  w.SetAttr("/modes/impacts_per_period", "columns", "left,right");
  w.WriteDoubles("/modes/rest_fraction", rf, {k, 2}, "1");
  w.SetAttr("/modes/rest_fraction", "columns", "left,right");
  w.WriteDoubles("/modes/drift_speed", drift, {k}, "m/s");
}

void WritePeriods(H5Writer& w, const Periods& p) {
  const hsize_t k = p.rows.size();
  Rows t0, x0, rest, elev, energy, missing;
  std::vector<int64_t> impacts;
  std::vector<uint8_t> complete;
  for (const PeriodRow& r : p.rows) {
    t0.push_back(r.t_start);
    x0.push_back(r.stats.x_start);
    energy.push_back(r.energy_gT2);
    missing.push_back(r.missing_fraction);
    complete.push_back(r.complete);
    for (int s = 0; s < 2; ++s) {
      impacts.push_back(r.stats.impacts[s]);
      rest.push_back(r.stats.rest_time[s]);
      elev.push_back(r.elevation_m[s]);
    }
  }
  w.WriteDoubles("/periods/t_start", t0, {k}, "s");
  w.WriteDoubles("/periods/x_start", x0, {k}, "m");
  w.WriteInt64("/periods/impacts", impacts, {k, 2});
  w.SetAttr("/periods/impacts", "columns", "left,right");
  w.WriteDoubles("/periods/rest_time", rest, {k, 2}, "s");
  w.SetAttr("/periods/rest_time", "columns", "left,right");
  w.WriteDoubles("/periods/elevation", elev, {k, 2}, "m");
  w.SetAttr("/periods/elevation", "columns", "left,right");
  w.WriteDoubles("/periods/energy", energy, {k}, "g T^2");
  w.WriteDoubles("/periods/missing_fraction", missing, {k}, "1");
  w.WriteUint8("/periods/complete", complete, {k});
}

void WriteContacts(H5Writer& w, const Analysis& a) {
  const hsize_t n = a.run.n;
  Rows gap(2 * n);
  std::vector<uint8_t> resting(2 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int s = 0; s < 2; ++s) {
      gap[2 * i + s] = a.contacts.sphere[s].gap[i];
      resting[2 * i + s] = a.contacts.sphere[s].resting[i];
    }
  }
  Rows t(n);
  for (size_t i = 0; i < n; ++i) t[i] = a.run.Time(i);
  w.WriteDoubles("/contacts/t", t, {n}, "s");
  w.WriteDoubles("/contacts/gap", gap, {n, 2}, "m");
  w.SetAttr("/contacts/gap", "columns", "left,right");
  w.WriteUint8("/contacts/resting", resting, {n, 2});
  w.SetAttr("/contacts/resting", "columns", "left,right");
  for (int s = 0; s < 2; ++s) {
    const std::string side = s ? "right" : "left";
    w.SetAttr("/contacts/gap", "level_" + side, a.contacts.sphere[s].level_m);
    w.SetAttr("/contacts/gap", "threshold_" + side, a.contacts.sphere[s].threshold_m);
    w.SetAttr("/contacts/gap", "noise_" + side, a.contacts.sphere[s].noise_m);
  }
  const std::vector<Impact> imps = a.contacts.AllImpacts();
  const hsize_t m = imps.size();
  Rows it, ph, vb, va, lvl;
  std::vector<int8_t> sph;
  std::vector<uint8_t> bounce;
  for (const Impact& i : imps) {
    it.push_back(i.t);
    ph.push_back(i.plate_phase);
    vb.push_back(i.v_before);
    va.push_back(i.v_after);
    lvl.push_back(i.level_m);
    sph.push_back(static_cast<int8_t>(i.sphere));
    bounce.push_back(i.bounce);
  }
  w.WriteDoubles("/impacts/t", it, {m}, "s");
  w.WriteInt8("/impacts/sphere", sph, {m});
  w.SetAttr("/impacts/sphere", "codes", "0 left, 1 right");
  w.WriteDoubles("/impacts/plate_phase", ph, {m}, "period");
  w.WriteDoubles("/impacts/v_before", vb, {m}, "m/s");
  w.WriteDoubles("/impacts/v_after", va, {m}, "m/s");
  w.WriteDoubles("/impacts/level", lvl, {m}, "m");
  w.WriteUint8("/impacts/bounce", bounce, {m});
  w.SetAttr("/impacts/bounce", "codes", "1 bounce (flight after), 0 landing to rest");
}

void WriteSlip(H5Writer& w, const SlipResult& s, const SampledRun& run) {
  const hsize_t n = run.n, k = s.phase.size();
  Rows t(n);
  for (size_t i = 0; i < n; ++i) t[i] = run.Time(i);
  w.WriteDoubles("/slip/t", t, {n}, "s");
  w.WriteDoubles("/slip/U", s.U, {n}, "m/s");
  w.SetAttr("/slip/U", "sign", "positive toward the bouncing end");
  w.SetAttr("/slip/U", "resting_sphere", int64_t{s.resting_sphere});
  w.SetAttr("/slip/U", "half_window_frames", int64_t{s.half_window});
  w.WriteDoubles("/slip/phase", s.phase, {k}, "period");
  w.WriteDoubles("/slip/profile", s.profile, {k}, "m/s");
  w.WriteDoubles("/slip/profile_err", s.profile_err, {k}, "m/s");
  std::vector<int64_t> count(s.profile_count.begin(), s.profile_count.end());
  w.WriteInt64("/slip/profile_count", count, {k});
}

void WriteComparison(H5Writer& w, const Comparison& c) {
  const hsize_t n = c.t.size();
  w.WriteDoubles("/comparison/t", c.t, {n}, "s");
  for (int s = 0; s < 2; ++s) {
    const std::string side = s ? "right" : "left";
    Rows sim(2 * n), res(2 * n);
    for (size_t i = 0; i < n; ++i) {
      sim[2 * i] = c.sim_x[s][i], sim[2 * i + 1] = c.sim_z[s][i];
      res[2 * i] = c.res_x[s][i], res[2 * i + 1] = c.res_z[s][i];
    }
    w.WriteDoubles("/comparison/sim_tips/" + side, sim, {n, 2}, "m");
    w.SetAttr("/comparison/sim_tips/" + side, "columns", "x,z");
    w.WriteDoubles("/comparison/residual/" + side, res, {n, 2}, "m");
    w.SetAttr("/comparison/residual/" + side, "columns", "x,z");
  }
  const SlipResult& ss = c.sim.slip;
  w.WriteDoubles("/comparison/sim_slip_profile", ss.profile, {ss.profile.size()}, "m/s");
  w.SetAttr("/comparison/t", "sim", c.sim_path);
  w.SetAttr("/comparison/t", "time_offset", c.time_offset_s);
  w.SetAttr("/comparison/t", "x_offset", c.x_offset_m);
  w.SetAttr("/comparison/t", "mirrored", int64_t{c.mirrored});
}

void WriteFit(H5Writer& w, const FitResult& f) {
  std::vector<std::string> names, status;
  Rows value, err, lo, hi, rlo, rhi;
  for (const FitParameter& p : f.params) {
    names.push_back(p.name);
    status.push_back(p.status);
    value.push_back(p.status == "constrained" ? p.value : kNaN);
    err.push_back(p.status == "constrained" ? p.err : kNaN);
    lo.push_back(p.lo), hi.push_back(p.hi), rlo.push_back(p.range_lo), rhi.push_back(p.range_hi);
    w.WriteDoubles("/fit/slices/" + p.name + "/x", p.slice_x, {p.slice_x.size()}, "1");
    w.WriteDoubles("/fit/slices/" + p.name + "/chi2", p.slice_chi2, {p.slice_chi2.size()}, "1");
  }
  const hsize_t k = names.size();
  w.WriteStrings("/fit/name", names);
  w.WriteStrings("/fit/status", status);
  w.WriteDoubles("/fit/value", value, {k}, "1");
  w.WriteDoubles("/fit/err", err, {k}, "1");
  w.WriteDoubles("/fit/bound_lo", lo, {k}, "1");
  w.WriteDoubles("/fit/bound_hi", hi, {k}, "1");
  w.WriteDoubles("/fit/range_lo", rlo, {k}, "1");
  w.WriteDoubles("/fit/range_hi", rhi, {k}, "1");
  const hsize_t m = f.observable_names.size();
  w.WriteStrings("/fit/observables/name", f.observable_names);
  w.WriteDoubles("/fit/observables/observed", f.observed, {m}, "mixed");
  w.WriteDoubles("/fit/observables/observed_err", f.observed_err, {m}, "mixed");
  w.WriteDoubles("/fit/observables/simulated", f.simulated, {m}, "mixed");
  w.SetAttr("/fit/name", "chi2", f.chi2);
  w.SetAttr("/fit/name", "dof", int64_t{f.dof});
  w.SetAttr("/fit/name", "threshold", f.threshold);
  w.SetAttr("/fit/name", "evaluations", int64_t{f.evaluations});
}

AttrList Headline(const Analysis& a, const Comparison* c) {
  const ModeSummary& ms = a.periods.settled.summary;
  const PlateDrive& p = a.plate;
  AttrList h = {
      {"input", a.run.path},
      {"input_kind", a.run.kind},
      {"settled_mode", ms.label},
      {"bouncing_sphere", int64_t{ms.bouncing_sphere}},
      {"mode_window_periods", int64_t{ms.window_periods}},
      {"drift_speed", a.drift.speed},
      {"drift_speed_err", a.drift.speed_err},
      {"drift_scaled", a.drift.scaled},
      {"drift_scaled_err", a.drift.scaled_err},
      {"travel_mm", a.drift.travel_mm},
      {"travel_time", a.drift.travel_time_s},
      {"freq", p.freq_hz},
      {"freq_err", p.freq_err},
      {"gamma", p.gamma},
      {"gamma_err", p.gamma_err},
      {"plate_amplitude", p.amp_m},
      {"plate_phase", p.phase_rad},
      {"plate_phase_err", p.phase_err},
      {"plate_source", p.source},
      {"plate_residual_rms", p.residual_rms_m},
      {"ar_measured", a.run.ar},
      {"diameter", a.run.diameter_m},
      {"fps", a.run.fps()},
      {"g_fit", a.free_fall.g_fit},
      {"g_fit_err", a.free_fall.g_fit_err},
      {"slip_after", a.slip.after},
      {"slip_after_err", a.slip.after_err},
      {"slip_before", a.slip.before},
      {"slip_before_err", a.slip.before_err},
  };
  if (c) {
    h.push_back({"sim_settled_mode", c->sim.periods.settled.summary.label});
    h.push_back({"sim_drift_speed", c->sim.drift.speed});
    h.push_back({"modes_agree", int64_t{c->modes_agree}});
  }
  return h;
}

}  // namespace

void WriteCompareFile(const std::string& path, const Analysis& a, const Comparison* comparison,
                      const FitResult* fit, const AttrList& params) {
  H5Writer w(path);
  AttrList attrs = Headline(a, comparison);
  attrs.insert(attrs.end(), params.begin(), params.end());
  WriteProvenance(w, "compare", attrs);
  WriteModes(w, a.periods);
  WritePeriods(w, a.periods);
  WriteContacts(w, a);
  WriteSlip(w, a.slip, a.run);
  if (comparison) WriteComparison(w, *comparison);
  if (fit) WriteFit(w, *fit);
  w.Close();
}

}  // namespace dimer::compare
