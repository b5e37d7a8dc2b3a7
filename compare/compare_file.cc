#include "compare/compare_file.h"

#include <cmath>
#include <type_traits>

#include "common/h5_file.h"

namespace dimer::compare {
namespace {

using Rows = std::vector<double>;

// Every dataset says what it is (docs/FORMATS.md, "Self-description").
class Out {
 public:
  explicit Out(H5Writer& w) : w_(w) {}
  void Doubles(const std::string& name, const Rows& v, const Dims& dims, const std::string& units,
               const std::string& description, const std::string& columns = "") {
    w_.WriteDoubles(name, v, dims, units, columns);
    w_.SetAttr(name, "description", description);
  }
  template <typename T>
  void Ints(const std::string& name, const std::vector<T>& v, const Dims& dims, const std::string& units,
            const std::string& codes, const std::string& description, const std::string& columns = "") {
    if constexpr (std::is_same_v<T, uint8_t>) w_.WriteUint8(name, v, dims);
    else if constexpr (std::is_same_v<T, int8_t>) w_.WriteInt8(name, v, dims);
    else w_.WriteInt64(name, v, dims);
    if (!units.empty()) w_.SetAttr(name, "units", units);
    if (!codes.empty()) w_.SetAttr(name, "codes", codes);
    if (!columns.empty()) w_.SetAttr(name, "columns", columns);
    w_.SetAttr(name, "description", description);
  }
  void Strings(const std::string& name, const std::vector<std::string>& v, const std::string& description,
               const std::string& codes = "") {
    w_.WriteStrings(name, v);
    if (!codes.empty()) w_.SetAttr(name, "codes", codes);
    w_.SetAttr(name, "description", description);
  }
  H5Writer& w() { return w_; }

 private:
  H5Writer& w_;
};

constexpr const char* kSphereCodes = "0=left,1=right";
constexpr const char* kModeCodes = "rest=both on the plate,drift=one end bounces once per period while the other "
                                   "rests,jump=both hit once per period,flutter=each hits every other period,"
                                   "irregular=none of these";

void WriteModes(Out& o, const Periods& p) {
  const hsize_t k = p.timeline.size();
  Rows t0, t1, ipp, rf, drift, err;
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
    err.push_back(m.summary.drift_speed_err);
  }
  o.Doubles("/modes/t_start", t0, {k}, "s", "start of each window of the mode timeline");
  o.Doubles("/modes/t_end", t1, {k}, "s", "end of each window");
  o.Strings("/modes/label", label, "mode of each window (the project's one definition, common/modes.h)", kModeCodes);
  o.Ints("/modes/bouncing_sphere", bouncing, {k}, "", "-1=none (not drift),0=left,1=right",
         "the bouncing end of each drift window");
  o.Doubles("/modes/impacts_per_period", ipp, {k, 2}, "1/period", "impacts per period of each sphere",
            "left,right");
  o.Doubles("/modes/rest_fraction", rf, {k, 2}, "1", "fraction of the window each sphere rests", "left,right");
  o.Doubles("/modes/drift_speed", drift, {k}, "m/s",
            "mean CM velocity over the window, positive toward the bouncing end in drift");
  o.Doubles("/modes/drift_speed_err", err, {k}, "m/s", "standard error of drift_speed (period scatter)");
}

void WritePeriods(Out& o, const Periods& p) {
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
  o.Doubles("/periods/t_start", t0, {k}, "s", "start of each whole plate period");
  o.Doubles("/periods/x_start", x0, {k}, "m", "CM lab x at the period start");
  o.Ints("/periods/impacts", impacts, {k, 2}, "1", "", "impacts of each sphere in the period", "left,right");
  o.Doubles("/periods/rest_time", rest, {k, 2}, "s", "time each sphere rests in the period", "left,right");
  o.Doubles("/periods/elevation", elev, {k, 2}, "m", "highest gap of each sphere above its contact level",
            "left,right");
  o.Doubles("/periods/energy", energy, {k}, "g T^2",
            "the paper's energy measure: sum of the two elevations, in units of g T^2");
  o.Doubles("/periods/missing_fraction", missing, {k}, "1", "fraction of the period's frames without both tips");
  o.Ints("/periods/complete", complete, {k}, "", "0=more than 5 % missing: not labelled,1=complete",
         "whether the period enters the mode windows");
}

void WriteContacts(Out& o, const Analysis& a) {
  const hsize_t n = a.run.n;
  Rows gap(2 * n), t(n);
  std::vector<uint8_t> resting(2 * n);
  for (size_t i = 0; i < n; ++i) {
    t[i] = a.run.Time(i);
    for (int s = 0; s < 2; ++s) {
      gap[2 * i + s] = a.contacts.sphere[s].gap[i];
      resting[2 * i + s] = a.contacts.sphere[s].resting[i];
    }
  }
  o.Doubles("/contacts/t", t, {n}, "s", "time of each frame of the analysis grid");
  o.Doubles("/contacts/gap", gap, {n, 2}, "m", "height of each sphere's lowest point above the plate",
            "left,right");
  o.Ints("/contacts/resting", resting, {n, 2}, "", "0=not resting,1=resting (3+ frames within thr of the level)",
         "whether each sphere rests on the plate", "left,right");
  Rows lvl, thr, noise;
  for (int s = 0; s < 2; ++s) {
    lvl.push_back(a.contacts.sphere[s].level_m);
    thr.push_back(a.contacts.sphere[s].threshold_m);
    noise.push_back(a.contacts.sphere[s].noise_m);
  }
  o.Doubles("/contacts/level", lvl, {2}, "m", "measured contact level of the gap, per sphere (left, right)");
  o.Doubles("/contacts/threshold", thr, {2}, "m", "contact threshold thr, per sphere (left, right)");
  o.Doubles("/contacts/noise", noise, {2}, "m", "position noise of the gap from the data, per sphere (left, right)");
  const std::vector<Impact> imps = a.contacts.AllImpacts();
  const hsize_t m = imps.size();
  Rows it, ph, vb, va, lv;
  std::vector<int8_t> sph;
  std::vector<uint8_t> bounce;
  for (const Impact& i : imps) {
    it.push_back(i.t);
    ph.push_back(i.plate_phase);
    vb.push_back(i.v_before);
    va.push_back(i.v_after);
    lv.push_back(i.level_m);
    sph.push_back(static_cast<int8_t>(i.sphere));
    bounce.push_back(i.bounce);
  }
  o.Doubles("/impacts/t", it, {m}, "s", "impact time (sub-frame: fitted approach and departure meet)");
  o.Ints("/impacts/sphere", sph, {m}, "", kSphereCodes, "the sphere that hit");
  o.Doubles("/impacts/plate_phase", ph, {m}, "period", "plate phase at the impact, 0..1 (0: mid-height rising)");
  o.Doubles("/impacts/v_before", vb, {m}, "m/s", "normal velocity relative to the plate before the impact");
  o.Doubles("/impacts/v_after", va, {m}, "m/s", "normal velocity relative to the plate after (NaN: landed)");
  o.Doubles("/impacts/level", lv, {m}, "m", "gap at the fitted impact point");
  o.Ints("/impacts/bounce", bounce, {m}, "", "0=landing to rest,1=bounce (flight after)", "how the impact ended");
}

void WriteSlip(Out& o, const SlipResult& s, const SampledRun& run) {
  const hsize_t n = run.n, k = s.phase.size();
  Rows t(n);
  for (size_t i = 0; i < n; ++i) t[i] = run.Time(i);
  o.Doubles("/slip/t", t, {n}, "s", "time of each frame");
  o.Doubles("/slip/U", s.U, {n}, "m/s",
            "slip velocity u - omega r_z of the resting sphere's contact point, positive toward the "
            "bouncing end (NaN where it does not rest)");
  o.Doubles("/slip/phase", s.phase, {k}, "period", "centre of each plate-phase bin, 0..1");
  o.Doubles("/slip/profile", s.profile, {k}, "m/s", "mean slip in each phase bin over the settled window");
  o.Doubles("/slip/profile_err", s.profile_err, {k}, "m/s", "standard error of the mean slip in each bin");
  std::vector<int64_t> count(s.profile_count.begin(), s.profile_count.end());
  o.Ints("/slip/profile_count", count, {k}, "1", "", "frames in each phase bin");
  o.Doubles("/slip/whole_profile", s.whole_profile, {k}, "m/s",
            "mean slip in each phase bin over the whole run, the release's transient included");
  o.Doubles("/slip/whole_profile_err", s.whole_profile_err, {k}, "m/s", "its standard error");
  std::vector<int64_t> whole(s.whole_profile_count.begin(), s.whole_profile_count.end());
  o.Ints("/slip/whole_profile_count", whole, {k}, "1", "", "frames in each phase bin, whole run");
}

void WriteComparison(Out& o, const Comparison& c) {
  const hsize_t n = c.t.size();
  o.Doubles("/comparison/t", c.t, {n}, "s", "track time of each compared frame");
  for (int s = 0; s < 2; ++s) {
    const std::string side = s ? "right" : "left";
    Rows sim(2 * n), res(2 * n);
    for (size_t i = 0; i < n; ++i) {
      sim[2 * i] = c.sim_x[s][i], sim[2 * i + 1] = c.sim_z[s][i];
      res[2 * i] = c.res_x[s][i], res[2 * i + 1] = c.res_z[s][i];
    }
    o.Doubles("/comparison/sim_tips/" + side, sim, {n, 2}, "m",
              "aligned simulated " + side + " tip in the track's frame", "x,z");
    o.Doubles("/comparison/residual/" + side, res, {n, 2}, "m", "track minus simulation, " + side + " tip", "x,z");
  }
  const SlipResult& ss = c.sim.slip;
  o.Doubles("/comparison/sim_slip_profile", ss.profile, {ss.profile.size()}, "m/s",
            "the simulation's phase-averaged slip, same bins as /slip/profile");
}

void WriteFit(Out& o, const FitResult& f) {
  std::vector<std::string> names, status;
  Rows value, err, lo, hi, rlo, rhi;
  for (const FitParameter& p : f.params) {
    names.push_back(p.name);
    status.push_back(p.status);
    value.push_back(p.status == "constrained" ? p.value : kNaN);
    err.push_back(p.status == "constrained" ? p.err : kNaN);
    lo.push_back(p.lo), hi.push_back(p.hi), rlo.push_back(p.range_lo), rhi.push_back(p.range_hi);
    o.Doubles("/fit/slices/" + p.name + "/x", p.slice_x, {p.slice_x.size()}, "1",
              "values of " + p.name + " along its chi2 slice through the optimum");
    o.Doubles("/fit/slices/" + p.name + "/chi2", p.slice_chi2, {p.slice_chi2.size()}, "1", "chi2 along the slice");
  }
  const hsize_t k = names.size();
  o.Strings("/fit/name", names, "fitted coefficient", "eps=restitution,mu_hat=impact sliding friction,"
            "mu_hat_s=impact static friction,mu=contact sliding friction,mu_s=contact static friction");
  o.Strings("/fit/status", status, "what the scene says of each coefficient",
            "constrained=value and error,bounded_below=only a lower bound (range_lo),bounded_above=only an "
            "upper bound (range_hi),unconstrained=no information in the searched bounds,no_acceptable_fit="
            "the best point fails the goodness of fit (p < 0.001): no value");
  o.Doubles("/fit/value", value, {k}, "1", "optimum (NaN unless constrained)");
  o.Doubles("/fit/err", err, {k}, "1", "half-width of the chi2 range (NaN unless constrained)");
  o.Doubles("/fit/bound_lo", lo, {k}, "1", "lower bound searched");
  o.Doubles("/fit/bound_hi", hi, {k}, "1", "upper bound searched");
  o.Doubles("/fit/range_lo", rlo, {k}, "1", "lowest value with chi2 within the threshold of the minimum");
  o.Doubles("/fit/range_hi", rhi, {k}, "1", "highest value with chi2 within the threshold of the minimum");
  if (f.correlation.size() == k * k) {
    std::string columns;  // rows and columns in /fit/name's order
    for (const std::string& n : names) columns += (columns.empty() ? "" : ",") + n;
    o.Doubles("/fit/correlation", f.correlation, {k, k}, "1",
              "correlation of each pair of constrained coefficients, from their chi2 profiles "
              "(NaN unless both are constrained)",
              columns);
  }
  const hsize_t m = f.observable_names.size();
  o.Strings("/fit/observables/name", f.observable_names, "observable compared (velocities in g/f, phases in periods)");
  o.Doubles("/fit/observables/observed", f.observed, {m}, "1", "the track's value (dimensionless)");
  o.Doubles("/fit/observables/observed_err", f.observed_err, {m}, "1", "its error, with the analysis floor as scaled and the locked error's share (/fit/locked_error)");
  o.Doubles("/fit/observables/simulated", f.simulated, {m}, "1", "the simulation's value at the optimum");
  Rows goodness = {f.chi2 / f.dof, f.p_value, f.acceptable ? 1.0 : 0.0};
  o.Doubles("/fit/goodness", goodness, {1, 3}, "1", "chi2/dof at the optimum, its p-value P(chi2 >= found), "
            "1 if acceptable (p >= 0.001) else 0", "chi2_per_dof,p_value,acceptable");
  Rows floors = {f.floor_scale, f.chi2_per_dof_at_floors, f.p_value_at_floors};
  o.Doubles("/fit/floors", floors, {1, 3}, "1", "the factor the analysis floors were scaled by so that an "
            "acceptable fit's chi2/dof is 1 (1: not scaled), and chi2/dof at the optimum and its p-value with the "
            "floors as set (the goodness test)", "floor_scale,chi2_per_dof_at_floors,p_value_at_floors");
  Rows locked = {f.locked.col_m, f.locked.row_m};
  o.Doubles("/fit/locked_error", locked, {1, 2}, "m", "the tracker's error that repeats with the drive's phase, "
            "per sphere's column and row (standard deviation over phase bins; compare/locked_error.h): from the "
            "dimer's length, and from the resting sphere's height above the plate (row_source); its covariance "
            "over the observables is in chi2", "col,row");
  Rows bins = {double(f.locked.phase_bins), double(f.locked.length_bins), double(f.locked.rest_bins)};
  o.Doubles("/fit/locked_error_bins", bins, {1, 3}, "1", "phase bins of the drive, and those the column and "
            "row estimates rest on (0: none)", "phase_bins,length_bins,rest_bins");
  o.Strings("/fit/locked_error_row_source", {f.locked.row_source.empty() ? std::string("none") : f.locked.row_source},
            "where the row estimate comes from: resting_height, length (the columns' figure) or none");
  // (No wall time: files are bit-identical on rerun; it is printed on stderr.)
  Rows summary = {f.chi2, static_cast<double>(f.dof), f.threshold, static_cast<double>(f.evaluations)};
  o.Doubles("/fit/summary", summary, {1, 4}, "1", "chi2 at the optimum, degrees of freedom, chi2 range "
            "threshold (rise above the minimum), simulations run", "chi2,dof,threshold,evaluations");
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
      {"orbit_periods", int64_t{ms.orbit_periods}},
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
      {"gamma_plate", p.gamma_plate},
      {"gamma_plate_err", p.gamma_plate_err},
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
      {"tilt_fit_deg", a.free_fall.tilt_deg},
      {"tilt_fit_deg_err", a.free_fall.tilt_deg_err},
      {"slip_window_t_start", a.slip.window_t_start},
      {"slip_window_t_end", a.slip.window_t_end},
      {"slip_after", a.slip.after},
      {"slip_after_err", a.slip.after_err},
      {"slip_before", a.slip.before},
      {"slip_before_err", a.slip.before_err},
      {"outliers", static_cast<int64_t>(a.outliers.size())},
  };
  if (c) {
    h.push_back({"sim_settled_mode", c->sim.periods.settled.summary.label});
    h.push_back({"sim_drift_speed", c->sim.drift.speed});
    h.push_back({"sim_slip_after", c->sim.slip.after});
    h.push_back({"sim_slip_after_err", c->sim.slip.after_err});
    h.push_back({"sim_slip_before", c->sim.slip.before});
    h.push_back({"sim_slip_before_err", c->sim.slip.before_err});
    h.push_back({"sim_tilt_deg", c->sim.run.sim_tilt_deg});
    h.push_back({"modes_agree", int64_t{c->modes_agree}});
    h.push_back({"time_offset", c->time_offset_s});
    h.push_back({"x_offset", c->x_offset_m});
    h.push_back({"mirrored", int64_t{c->mirrored}});
  }
  return h;
}

AttrUnits HeadlineUnits() {
  return {{"mode_window_periods", "periods"}, {"orbit_periods", "periods"}, {"drift_speed", "m/s"}, {"drift_speed_err", "m/s"},
          {"drift_scaled", "1"}, {"drift_scaled_err", "1"}, {"travel_mm", "mm"}, {"travel_time", "s"},
          {"freq", "Hz"}, {"freq_err", "Hz"}, {"gamma", "1"}, {"gamma_err", "1"}, {"gamma_plate", "1"}, {"gamma_plate_err", "1"},
          {"plate_amplitude", "m"},
          {"plate_phase", "rad"}, {"plate_phase_err", "rad"}, {"plate_residual_rms", "m"}, {"ar_measured", "1"},
          {"diameter", "m"}, {"fps", "1/s"}, {"g_fit", "m/s^2"}, {"g_fit_err", "m/s^2"}, {"tilt_fit_deg", "deg"},
          {"tilt_fit_deg_err", "deg"}, {"slip_window_t_start", "s"}, {"slip_window_t_end", "s"}, {"slip_after", "m/s"},
          {"slip_after_err", "m/s"}, {"slip_before", "m/s"}, {"slip_before_err", "m/s"}, {"outliers", "1"},
          {"sim_drift_speed", "m/s"}, {"sim_slip_after", "m/s"}, {"sim_slip_after_err", "m/s"},
          {"sim_slip_before", "m/s"}, {"sim_slip_before_err", "m/s"}, {"sim_tilt_deg", "deg"}, {"time_offset", "s"}, {"x_offset", "m"},
          // parameters (run_compare.cc)
          {"mode_window", "periods"}, {"phase_bins", "1"}, {"option_freq", "Hz"}, {"option_gamma", "1"},
          {"transient_periods", "periods"}, {"scene_tilt_deg", "deg"}, {"scene_eps", "1"}, {"scene_mu", "1"}, {"scene_mu_s", "1"},
          {"scene_mu_hat", "1"}, {"scene_mu_hat_s", "1"}};
}

AttrCodes HeadlineCodes() {
  return {{"bouncing_sphere", "-1=none (not in drift mode),0=left,1=right"},
          {"modes_agree", "0=the settled modes differ,1=equal"},
          {"mirrored", "0=no,1=simulation mirrored (x -> -x, left <-> right)"},
          {"simulate", "0=no,1=the scene was simulated (--simulate)"},
          {"fit", "0=no,1=coefficients fitted (--fit)"}};
}

}  // namespace

void WriteCompareFile(const std::string& path, const Analysis& a, const Comparison* comparison,
                      const FitResult* fit, const AttrList& params) {
  H5Writer w(path);
  AttrList attrs = Headline(a, comparison);
  attrs.insert(attrs.end(), params.begin(), params.end());
  WriteProvenance(w, "compare", attrs, HeadlineUnits(), HeadlineCodes());
  Out o(w);
  WriteModes(o, a.periods);
  WritePeriods(o, a.periods);
  WriteContacts(o, a);
  WriteSlip(o, a.slip, a.run);
  if (comparison) WriteComparison(o, *comparison);
  if (fit) WriteFit(o, *fit);
  w.Close();
}

}  // namespace dimer::compare
