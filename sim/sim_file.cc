#include "sim/sim_file.h"

#include "common/atomic_output.h"
#include "common/h5_file.h"
#include "common/trajectory_io.h"
#include "sim/event_rows.h"
#include "sim/initial_conditions.h"
#include "sim/sample_rows.h"

namespace dimer::sim {

namespace {
std::string RestitutionName(RestitutionLaw law);

constexpr const char* kStateUnits = "m,m,rad,m/s,m/s,rad/s";
constexpr const char* kStateColumnNames = "x,z,theta,u,v,omega";
constexpr const char* kEventKindCodes =
    "impact=one sphere hits the plate,"
    "double_impact=both spheres in one impact (or one hits while the other rests),"
    "collapse=an impact slower than v_c: the sphere stays on the plate,"
    "liftoff=a resting sphere leaves the plate,"
    "stick=a resting sphere stops sliding,"
    "slip=a resting sphere starts sliding,"
    "painleve=an impact without collision resolving a Painleve configuration";
}  // namespace

AttrList SimParameters(const SimOptions& o) {
  AttrList a = {{"ar", o.ar},
                {"diameter", o.diameter_m},
                {"freq", o.freq_hz},
                {"gamma", o.gamma},
                {"tilt_deg", o.tilt_deg},
                {"plate_phase", o.plate_phase},
                {"eps", o.eps},
                {"mu", o.mu},
                {"mu_s", o.mu_s},
                {"mu_hat", o.mu_hat},
                {"mu_hat_s", o.mu_hat_s},
                {"restitution", RestitutionName(o.restitution)},
                {"init", ToString(o.init)},
                {"lift", o.EffectiveLift()},
                {"release_phase", o.release_phase},
                {"cycles", o.cycles},
                {"duration", o.Duration()},
                {"fps", o.fps},
                {"collapse_vc", o.collapse_rel},
                {"contact_tol", o.contact_tol},
                {"gap_tol", o.gap_tol},
                {"max_events_per_period", o.max_events_per_period}};
  if (o.init_state) {
    std::string s;
    for (double x : *o.init_state) s += (s.empty() ? "" : ",") + std::to_string(x);
    a.emplace_back("init_state", s);
  }
  return a;
}

namespace {

std::string RestitutionName(RestitutionLaw law) {
  for (const auto& [name, l] : RestitutionLawNames()) {
    if (l == law) return name;
  }
  return "?";
}

// The numeric columns come from row functions (event_rows.h), made on the compressing threads
// or taken from RunSim's chunks filtered during the run; the strings are short and cheap.
void WriteEvents(H5Writer& w, const Model& m, const std::vector<EventRecord>& ev) {
  const hsize_t n = ev.size();
  std::vector<std::string> kind, detail;
  std::vector<int8_t> sphere;
  for (const EventRecord& e : ev) {
    kind.push_back(ToString(e.kind));
    detail.push_back(e.detail);
    sphere.push_back(e.sphere);
  }
  const EventLogRows rows = EventLogFills(m, &ev);
  w.WriteDoubleRows("/events/t", {n}, rows.t, "s");
  w.SetAttr("/events/t", "description", "time of each event");
  w.WriteStrings("/events/kind", kind);
  w.SetAttr("/events/kind", "description", "what happened");
  w.SetAttr("/events/kind", "codes", kEventKindCodes);
  w.WriteStrings("/events/detail", detail);
  w.SetAttr("/events/detail", "description",
            "impacts: how the slip evolved, per sphere (continuous_slide | slip_stick | "
            "slip_reversal); empty for other events");
  w.WriteInt8("/events/sphere", sphere, {n});
  w.SetAttr("/events/sphere", "description", "the sphere(s) of the event");
  w.SetAttr("/events/sphere", "codes", "0=left,1=right,2=both");
  w.WriteDoubleRows("/events/before", {n, kLabStateColumns}, rows.before, kStateUnits,
                    kStateColumnNames);
  w.SetAttr("/events/before", "description", "lab-frame state just before the event");
  w.WriteDoubleRows("/events/after", {n, kLabStateColumns}, rows.after, kStateUnits,
                    kStateColumnNames);
  w.SetAttr("/events/after", "description", "lab-frame state just after the event");
}

// Units of the root attributes: every parameter and every result.
AttrUnits SimAttrUnits() {
  return {{"ar", "1"}, {"diameter", "m"}, {"freq", "Hz"}, {"gamma", "1"}, {"tilt_deg", "deg"},
          {"plate_phase", "period"}, {"eps", "1"}, {"mu", "1"}, {"mu_s", "1"}, {"mu_hat", "1"},
          {"mu_hat_s", "1"}, {"lift", "d"}, {"release_phase", "period"}, {"cycles", "period"},
          {"duration", "s"}, {"fps", "1/s"}, {"collapse_vc", "g/f"}, {"contact_tol", "1"},
          {"gap_tol", "m"}, {"max_events_per_period", "1/period"}, {"t_start", "s"},
          {"t_end", "s"}, {"drift_speed", "m/s"}, {"drift_speed_err", "m/s"},
          {"drift_scaled", "1"}, {"mode_window_periods", "period"},
          {"mode_impacts_per_period_left", "1/period"},
          {"mode_impacts_per_period_right", "1/period"}, {"mode_rest_fraction_left", "1"},
          {"mode_rest_fraction_right", "1"}, {"events_per_period", "1/period"},
          {"max_events_in_period", "1"}, {"max_penetration_m", "m"}, {"impact_failures", "1"},
          {"capped_searches", "1"}, {"step_underflows", "1"}, {"painleve_events", "1"},
          {"newton_energy_gain_impacts", "1"}, {"newton_max_relative_gain", "1"}};
}

AttrCodes SimAttrCodes() {
  return {{"bouncing_sphere", "-1=none (not in drift mode),0=left,1=right"},
          {"interrupted", "0=complete run,1=stopped early (Ctrl-C): t_end is the last time "
                          "reached"}};
}

}  // namespace

void WriteSimFile(const std::string& path, bool force, const SimOptions& o, const SimResult& r,
                  const H5WriteOptions& storage) {
  AtomicOutput out(path, force);
  {
    H5Writer w(out.temp_path(), storage);
    const Model& m = r.model;
    const SampleArrays samples{r.t.data(), r.lab.data()};
    const hsize_t n = r.t.size();
    WriteTrajectory(w, n, SampleTrajectoryRows(m, &samples));
    w.WriteDoubleRows("/state", {n, kLabStateColumns}, StateRowFill(&samples), kStateUnits,
                      kStateColumnNames);
    w.SetAttr("/state", "description",
              "lab-frame state at each sample: centre of mass (x, z), axis angle theta, their "
              "rates (u, v, omega)");
    WriteEvents(w, m, r.events);
    AttrList attrs = SimParameters(o);
    const SimDiagnostics& d = r.diag;
    const double periods = (r.t_end - r.t_start) / m.period;
    attrs.insert(attrs.end(),
                 {{"t_start", r.t_start},
                  {"t_end", r.t_end},
                  {"settled_mode", r.mode.label},
                  {"mode_note", ModeNote(o, r.mode.label, static_cast<long>(r.periods.size()))},
                  {"bouncing_sphere", int64_t{r.mode.bouncing_sphere}},
                  {"drift_speed", r.mode.drift_speed},
                  {"drift_speed_err", r.mode.drift_speed_err},
                  {"drift_scaled", r.mode.drift_speed * o.freq_hz / kGravity},
                  {"mode_window_periods", int64_t{r.mode.window_periods}},
                  {"mode_impacts_per_period_left", r.mode.impacts_per_period[0]},
                  {"mode_impacts_per_period_right", r.mode.impacts_per_period[1]},
                  {"mode_rest_fraction_left", r.mode.rest_fraction[0]},
                  {"mode_rest_fraction_right", r.mode.rest_fraction[1]},
                  {"events_per_period", d.events / periods},
                  {"max_events_in_period", int64_t{d.max_events_in_period}},
                  {"max_penetration_m", d.max_penetration_m},
                  {"impact_failures", int64_t{d.impact_failures}},
                  {"capped_searches", int64_t{d.capped_searches}},
                  {"step_underflows", int64_t{d.step_underflows}},
                  {"painleve_events", int64_t{d.painleve}},
                  {"newton_energy_gain_impacts", int64_t{d.energy_capped}},
                  {"newton_max_relative_gain", d.max_newton_gain},
                  {"interrupted", int64_t{r.interrupted}},
                  {"error", r.error}});
    WriteProvenance(w, "sim", attrs, SimAttrUnits(), SimAttrCodes());
    w.Close();
  }
  out.Commit();
}

}  // namespace dimer::sim
