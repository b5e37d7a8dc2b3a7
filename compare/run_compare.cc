#include "compare/run_compare.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "compare/compare_file.h"
#include "compare/comparison.h"
#include "compare/report.h"
#include "compare/tilt_notes.h"
#include "sim/sim_file.h"

namespace dimer::compare {
namespace {

std::string JoinErrors(const std::vector<std::string>& e) {
  std::string s;
  for (size_t i = 0; i < e.size(); ++i) s += (i ? "; " : "") + e[i];
  return s;
}

void Say(bool quiet, const std::string& line) {
  if (!quiet) std::fprintf(stderr, "compare: %s\n", line.c_str());
}

// The simulation beside the track: from --sim, or simulated here (written as sim.h5 in `dir`).
// It is analysed as the camera saw the track (SeenAsTrack), as the fit sees its trials: each
// sphere's contact threshold at least the track's (4 sigma of its gap noise) and the track's
// slip filter. Otherwise the two slips are read over different frames: the drift's resting end
// lifts by up to 84 um at fixed plate phases, within a track's threshold (~140 um at 0.4 mm/px)
// and outside the simulation's own (0.01 d, 95 um), and the slip before the impact read off
// POV-Ray films was 2.7-3.7 mm/s against the simulation's 2.30 (the POV-Ray films of bench/povray_film.sh).
Analysis SimulationFor(const CompareArgs& args, const Analysis& track, const std::string& dir,
                       std::vector<std::string>* notes) {
  const AnalysisOptions seen = SeenAsTrack(track, args.analysis);
  if (!args.sim_path.empty()) {
    Say(args.quiet, "analysing the simulation " + args.sim_path);
    return Analyze(LoadSampledRun(args.sim_path), seen);
  }
  const sim::SimOptions o = SceneFromTrack(track, args.scene, args.transient_periods, notes);
  ProgressMeter meter("simulate", "periods", o.cycles, !args.quiet);
  sim::RunControls controls;
  controls.progress = [&](double done, double) { meter.Update(done); };
  controls.should_stop = [] { return InterruptRequested(); };
  sim::SimResult r;
  Analysis a = SimulateAndAnalyze(o, seen, "sim.h5", &r, controls);
  meter.Finish(static_cast<double>(r.periods.size()));
  if (r.interrupted) throw Interrupted();
  sim::WriteSimFile(dir + "/sim.h5", false, o, r);
  return a;
}

AttrList Parameters(const CompareArgs& a) {
  return {{"sim", a.sim_path},
          {"simulate", int64_t{a.simulate}},
          {"fit", int64_t{a.fit}},
          {"frames", a.frames_dir},
          {"mode_window", int64_t{a.analysis.window_periods}},
          {"phase_bins", int64_t{a.analysis.phase_bins}},
          {"option_freq", a.analysis.freq_hz},
          {"option_gamma", a.analysis.gamma},
          {"transient_periods", int64_t{a.transient_periods}},
          {"scene_tilt_deg", a.scene.tilt_deg},
          {"scene_eps", a.scene.eps},
          {"scene_mu", a.scene.mu},
          {"scene_mu_s", a.scene.mu_s},
          {"scene_mu_hat", a.scene.mu_hat},
          {"scene_mu_hat_s", a.scene.mu_hat_s}};
}

void PrintHeadline(const std::string& report, const Analysis& a, const FitResult* fit) {
  const ModeSummary& ms = a.periods.settled.summary;
  std::printf("%s/summary.md: %s mode", report.c_str(), ms.label.c_str());
  if (ms.bouncing_sphere >= 0) std::printf(" (bouncing %s end)", ms.bouncing_sphere ? "right" : "left");
  std::printf(" over the last %d periods; f = %.4f Hz, Gamma = %.4f", ms.window_periods, a.plate.freq_hz,
              a.plate.gamma);
  if (ms.label == "drift") {
    if (a.drift.periods < 2) {  // one period: no scatter to estimate an error from
      std::printf("; <u> = %.3f mm/s +- n/a (one period), <u> f/g = %.5f", a.drift.speed * 1e3, a.drift.scaled);
    } else {
      std::printf("; <u> = %.3f +- %.3f mm/s, <u> f/g = %.5f", a.drift.speed * 1e3, a.drift.speed_err * 1e3,
                  a.drift.scaled);
    }
  }
  if (fit && !fit->acceptable) {
    std::printf("; no acceptable fit (chi2/dof %.3g, p %.2g)", fit->chi2 / fit->dof, fit->p_value);
  } else if (fit) {
    for (const FitParameter& p : fit->params) {
      if (p.status == "constrained") std::printf("; %s = %.4f +- %.4f", p.name.c_str(), p.value, p.err);
      else std::printf("; %s %s", p.name.c_str(), p.status.c_str());
    }
  }
  std::printf("\n");
}

// Everything of `compare` into the existing folder `dir`; `final_dir` names it in messages.
void CompareInto(const CompareArgs& args, const std::string& dir, const std::string& final_dir,
                 const std::string& input_label) {
  SampledRun run = LoadSampledRun(args.input);
  run.path = input_label;
  Say(args.quiet, "analysing " + input_label + " (" + std::to_string(run.n) + " frames)");
  const Analysis track = Analyze(run, args.analysis);
  std::vector<std::string> notes;
  Comparison comparison;
  const bool compared = args.simulate || !args.sim_path.empty();
  if (compared) comparison = CompareWithSimulation(track, SimulationFor(args, track, dir, &notes));
  for (const std::string& n : TiltNotes(track, compared ? comparison.sim.run.sim_tilt_deg : kNaN)) {
    Say(args.quiet, "note: " + n);
    notes.push_back(n);
  }
  FitResult fit;
  if (args.fit) {
    ProgressMeter meter("fit", "simulations", args.fit_options.EstimatedSimulations(), !args.quiet);
    FitOptions fo = args.fit_options;
    fo.progress = [&](int done) { meter.Update(done); };
    fit = FitCoefficients(track, args.scene, fo);
    meter.Finish(fit.evaluations);
    Say(args.quiet, "fit done: " + std::to_string(fit.evaluations) + " simulations in " +
                        std::to_string(static_cast<int>(std::lround(fit.seconds))) + " s");
  }
  WriteCompareFile(dir + "/compare.h5", track, compared ? &comparison : nullptr, args.fit ? &fit : nullptr,
                   Parameters(args));
  ReportInputs in;
  in.track = &track;
  in.comparison = compared ? &comparison : nullptr;
  in.fit = args.fit ? &fit : nullptr;
  in.commands = args.commands;
  in.extra_warnings = notes;
  WriteReport(dir, in);
  if (!args.frames_dir.empty()) {
    OverlayOptions o = args.overlay;
    o.frames_dir = args.frames_dir;
    o.quiet = args.quiet;
    WriteOverlay(dir, track, compared ? &comparison : nullptr, o);
  }
  PrintHeadline(final_dir, track, args.fit ? &fit : nullptr);
}

}  // namespace

void CompareArgs::Check() const {
  std::vector<std::string> e = analysis.Check();
  if (output.empty()) e.push_back("-o/--output: the report folder is required");
  if (!sim_path.empty() && simulate) e.push_back("--sim and --simulate: give one of them");
  if (fit_options.max_evaluations < 1)
    e.push_back("--fit-evaluations: " + std::to_string(fit_options.max_evaluations) + ": expected >= 1");
  if (fit_options.global_evaluations < 0)
    e.push_back("--fit-global-evaluations: " + std::to_string(fit_options.global_evaluations) + ": expected >= 0");
  if (transient_periods < 0) e.push_back("--transient: " + std::to_string(transient_periods) + ": expected >= 0");
  const std::vector<std::string> s = scene.Check();
  e.insert(e.end(), s.begin(), s.end());
  if (!frames_dir.empty()) {
    OverlayOptions ov = overlay;
    ov.frames_dir = frames_dir;
    const std::vector<std::string> o = ov.Check();
    e.insert(e.end(), o.begin(), o.end());
  }
  if (!e.empty()) throw UsageError("invalid compare options: " + JoinErrors(e));
}

int RunCompare(const CompareArgs& args) {
  args.Check();
  CheckCanWrite(args.output, args.force, AtomicOutput::Kind::kDirectory);
  AtomicOutput out(args.output, args.force, AtomicOutput::Kind::kDirectory);
  CompareInto(args, out.temp_path(), args.output, args.input);
  out.Commit();
  return 0;
}

int RunAnalyze(const AnalyzeArgs& args) {
  args.compare.Check();
  CheckCanWrite(args.compare.output, args.compare.force, AtomicOutput::Kind::kDirectory);
  AtomicOutput out(args.compare.output, args.compare.force, AtomicOutput::Kind::kDirectory);
  tracking::TrackArgs t = args.track;
  t.output = out.temp_path() + "/track.h5";
  t.output_label = args.compare.output + "/track.h5";
  t.force = false;
  t.quiet = args.compare.quiet;
  tracking::RunTrack(t);
  CompareArgs c = args.compare;
  c.input = t.output;
  if (c.frames_dir.empty()) c.frames_dir = args.track.input;
  CompareInto(c, out.temp_path(), c.output, c.output + "/track.h5");
  out.Commit();
  return 0;
}

}  // namespace dimer::compare
