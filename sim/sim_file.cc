#include "sim/sim_file.h"

#include "common/atomic_output.h"
#include "common/h5_file.h"
#include "common/trajectory_io.h"
#include "sim/frames.h"

namespace dimer::sim {

namespace {
std::string RestitutionName(RestitutionLaw law);
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

std::vector<double> StateRows(const std::vector<State>& states) {
  std::vector<double> out;
  out.reserve(6 * states.size());
  for (const State& q : states) out.insert(out.end(), {q.x, q.z, q.th, q.u, q.v, q.w});
  return out;
}

void WriteEvents(H5Writer& w, const Model& m, const std::vector<EventRecord>& ev) {
  const hsize_t n = ev.size();
  std::vector<double> t;
  std::vector<std::string> kind, detail;
  std::vector<int8_t> sphere;
  std::vector<State> before, after;
  for (const EventRecord& e : ev) {
    t.push_back(e.t);
    kind.push_back(ToString(e.kind));
    detail.push_back(e.detail);
    sphere.push_back(e.sphere);
    before.push_back(LabFromPlate(m, e.t_local, e.before));
    after.push_back(LabFromPlate(m, e.t_local, e.after));
  }
  w.WriteDoubles("/events/t", t, {n}, "s");
  w.WriteStrings("/events/kind", kind);
  w.WriteStrings("/events/detail", detail);
  w.WriteInt8("/events/sphere", sphere, {n});
  w.WriteDoubles("/events/before", StateRows(before), {n, 6}, "m,m,rad,m/s,m/s,rad/s");
  w.WriteDoubles("/events/after", StateRows(after), {n, 6}, "m,m,rad,m/s,m/s,rad/s");
}

}  // namespace

void WriteSimFile(const std::string& path, bool force, const SimOptions& o, const SimResult& r) {
  AtomicOutput out(path, force);
  {
    H5Writer w(out.temp_path());
    const Model& m = r.model;
    Trajectory traj;
    traj.Reserve(r.t.size());
    for (size_t i = 0; i < r.t.size(); ++i) {
      const State& q = r.lab[i];
      traj.Append(r.t[i], TipLab(m, q, kLeft), TipLab(m, q, kRight),
                  PlateSurfaceZ(m, r.t[i], q.x), q.th);
    }
    WriteTrajectory(w, traj);
    w.WriteDoubles("/state", StateRows(r.lab), {r.lab.size(), 6}, "m,m,rad,m/s,m/s,rad/s");
    WriteEvents(w, m, r.events);
    AttrList attrs = SimParameters(o);
    const SimDiagnostics& d = r.diag;
    const double periods = (r.t_end - r.t_start) / m.period;
    attrs.insert(attrs.end(),
                 {{"t_start", r.t_start},
                  {"t_end", r.t_end},
                  {"settled_mode", r.mode.label},
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
    WriteProvenance(w, "sim", attrs);
    w.Close();
  }
  out.Commit();
}

}  // namespace dimer::sim
