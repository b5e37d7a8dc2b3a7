#include "compare/simulate.h"

#include <cmath>
#include <utility>

#include "common/error.h"
#include "common/plate_frame.h"
#include "compare/text.h"
#include "sim/reference_frames.h"

namespace dimer::compare {
sim::SimOptions SceneFromTrack(const Analysis& track, const sim::SimOptions& given,
                               int transient_periods, std::vector<std::string>* notes) {
  sim::SimOptions o = given;
  o.ar = track.run.ar;
  o.diameter_m = track.run.diameter_m;
  o.freq_hz = track.plate.freq_hz;
  o.gamma = track.plate.gamma;
  o.plate_phase = 0;
  o.fps = track.run.fps();
  o.duration_s = 0;
  const double periods = (track.run.Time(track.run.n - 1) - track.run.t0) * o.freq_hz;
  o.cycles = std::ceil(periods) + transient_periods;
  const std::string mode = track.periods.settled.summary.label;
  o.init = mode == "jump" ? sim::InitKind::kJump
           : mode == "flutter" ? sim::InitKind::kFlutter
           : mode == "rest" ? sim::InitKind::kRest
                            : sim::InitKind::kDrift;
  o.init_state.reset();
  if (notes) {
    const char* ar_from = track.run.scale_source == "--ar" ? " (track --ar)" : " (measured)";
    notes->push_back("simulated scene: A_r " + Num(o.ar) + ar_from + ", d " +
                     Num(o.diameter_m * 1e3) + " mm (file), f " + Num(o.freq_hz) +
                     " Hz and Gamma " + Num(o.gamma) + " (" +
                     track.plate.source +
                     (std::isfinite(track.plate.gamma_plate) ? ", Gamma from --gamma" : "") +
                     "), init " + sim::ToString(o.init) + " (observed " + mode +
                     "), " + Num(o.cycles) + " periods of which " + std::to_string(transient_periods) +
                     " transient; tilt " + Num(o.tilt_deg) + " deg" +
                     (o.tilt_deg != 0 ? " (compared in the plate's frame)" : "") + "; eps " +
                     Num(o.eps) + ", mu " + Num(o.mu) + ", mu_s " + Num(o.mu_s) +
                     ", mu_hat " + Num(o.mu_hat) + ", mu_hat_s " + Num(o.mu_hat_s));
  }
  return o;
}

Analysis SimulateAndAnalyze(const sim::SimOptions& options, const AnalysisOptions& analysis,
                            const std::string& label, sim::SimResult* result,
                            const sim::RunControls& controls) {
  sim::SimResult r = sim::RunSimulation(options, controls);
  if (!r.error.empty()) throw InputError(label + ": the simulation stopped: " + r.error);
  const sim::Model& m = r.model;
  Trajectory traj;
  traj.Reserve(r.t.size());
  for (size_t i = 0; i < r.t.size(); ++i) {
    const sim::State& q = r.lab[i];
    traj.Append(r.t[i], sim::TipLab(m, q, sim::kLeft), sim::TipLab(m, q, sim::kRight),
                sim::PlateSurfaceZ(m, r.t[i], q.x), q.th);
  }
  // A tilted plate's run is analysed in the plate's frame, as its track would be.
  SampledRun run = SampleTrajectory(InPlateFrame(std::move(traj), options.tilt_deg), options.fps,
                                    options.diameter_m, label, "sim");
  run.sim_tilt_deg = options.tilt_deg;
  run.sim_freq_hz = options.freq_hz;
  run.sim_gamma = options.gamma;
  run.sim_plate_phase = options.plate_phase;
  run.sim_t_start = r.t_start;
  run.sim_settled_mode = r.mode.label;
  for (const sim::EventRecord& e : r.events) {
    if (e.kind == sim::EventKind::kImpact || e.kind == sim::EventKind::kDoubleImpact) {
      run.sim_impact_t.push_back(e.t);
      run.sim_impact_sphere.push_back(e.sphere);
    }
  }
  Analysis a = Analyze(run, analysis);
  if (result) *result = std::move(r);
  return a;
}

}  // namespace dimer::compare
