// `dimerlab compare TRAJ.h5 -o REPORT` and `dimerlab analyze FRAMES -o REPORT`: flags of
// docs/FORMATS.md, parsed into compare::CompareArgs / AnalyzeArgs; the work is in compare/.
#include <memory>

#include "app/commands.h"
#include "app/usage.h"
#include "app/scene_file.h"
#include "app/track_messages.h"
#include "compare/run_compare.h"

namespace dimer::app {
namespace {

struct CompareCli {
  compare::AnalyzeArgs args;  // compare-only commands use args.compare
  std::string scene;
  bool no_simulate = false;
};

// Options shared by compare and analyze: analysis, simulation beside it, fit, report.
void AddCompareOptions(CLI::App* c, CompareCli* cli) {
  compare::CompareArgs& a = cli->args.compare;
  c->add_option("-o,--output", a.output, "report folder to create")->required();
  c->add_flag("--force", a.force, "replace an existing report folder");
  c->add_flag("--fit", a.fit, "fit eps, mu_hat, mu_hat_s, mu, mu_s by simulation");
  c->add_option("--freq", a.analysis.freq_hz, "drive frequency, Hz (needed when no plate is visible)");
  c->add_option("--gamma", a.analysis.gamma, "drive Gamma, e.g. from an accelerometer: needed when no plate is visible; with a visible "
                "plate it replaces the Gamma read off the plate's motion (both reported)");
  c->add_option("--mode-window", a.analysis.window_periods, "periods per window of the mode timeline")
      ->capture_default_str();
  c->add_option("--phase-bins", a.analysis.phase_bins, "bins of the phase-averaged slip")
      ->capture_default_str();
  c->add_option("--travel-mm", a.analysis.travel_mm, "travel distance of the paper's drift timing, mm")
      ->capture_default_str();
  c->add_option("--transient", a.transient_periods, "simulated periods before the compared part")
      ->capture_default_str();
  c->add_option("--tilt-deg", a.scene.tilt_deg,
                "plate tilt for --simulate and --fit, degrees (> 0 rises toward +x); tracks and simulations are "
                "compared in the plate's frame")
      ->capture_default_str();
  c->add_option("--eps", a.scene.eps, "restitution for --simulate, start of --fit")->capture_default_str();
  c->add_option("--mu", a.scene.mu, "sliding friction, persistent contact")->capture_default_str();
  c->add_option("--mu-s", a.scene.mu_s, "static friction, persistent contact")->capture_default_str();
  c->add_option("--mu-hat", a.scene.mu_hat, "sliding friction, impacts")->capture_default_str();
  c->add_option("--mu-hat-s", a.scene.mu_hat_s, "static friction, impacts")->capture_default_str();
  c->add_option("--fit-evaluations", a.fit_options.max_evaluations,
                "budget of each local search of the fit, simulations")
      ->capture_default_str();
  c->add_option("--fit-global-evaluations", a.fit_options.global_evaluations,
                "budget of the fit's multi-start search, simulations (0: local search only)")
      ->capture_default_str();
  c->add_option("--overlay-frames", a.overlay.max_frames, "frames in overlay.avi")->capture_default_str();
  c->add_option("--scene", cli->scene, "scene file: these options, one `name = value` per line");
  c->add_flag("-q,--quiet", a.quiet, "no progress on stderr");
}

}  // namespace

void RegisterCompare(CLI::App& app) {
  auto cli = std::make_shared<CompareCli>();
  CLI::App* c = app.add_subcommand(
      "compare", "modes, drift, slip, plate drive of a track or sim file; beside a simulation; fit");
  compare::CompareArgs& a = cli->args.compare;
  c->add_option("input", a.input, "trajectory file (track.h5 or sim.h5)")->required();
  c->add_option("--sim", a.sim_path, "a sim file to compare with");
  c->add_flag("--simulate", a.simulate, "simulate the scene the track shows and compare");
  c->add_option("--frames", a.frames_dir, "the recorded frames: overlay video and stills");
  AddCompareOptions(c, cli.get());
  c->callback([cli, c] {
    if (!cli->scene.empty()) ApplySceneFile(c, cli->scene);
    cli->args.compare.commands = {CommandLine()};
    compare::RunCompare(cli->args.compare);
  });
}

void RegisterAnalyze(CLI::App& app) {
  auto cli = std::make_shared<CompareCli>();
  CLI::App* c = app.add_subcommand(
      "analyze", "the whole pipeline on a recorded folder: track + compare --simulate");
  tracking::TrackArgs& t = cli->args.track;
  c->add_option("input", t.input, "folder of frames, multi-page TIFF, .cine or video")->required();
  c->add_option("--frames", t.frames, "track frames A..B-1 only (A:B, A: or :B; 0-based)");
  c->add_option("--fps", t.fps, "frame rate, frames/s [a .cine's time stamps or header, else 2000]")->check(FiniteNumber());
  c->add_option("--m-per-px", t.m_per_px, "metres per pixel [from --diameter]")->check(FiniteNumber());
  c->add_option("--diameter", t.diameter, "sphere diameter, m (calibrates m/px)")->check(FiniteNumber())->capture_default_str();
  c->add_option("--ar", t.ar,
                "the dimer's aspect ratio, length / diameter: m/px from its centre distance "
                "(A_r - 1) x diameter, tracked [not given: from the spheres' size]; with "
                "--m-per-px, a check")->check(FiniteNumber());
  c->add_option("--row0", t.row0, "row of z = 0, px [median plate row]")->check(FiniteNumber());
  c->add_option("--plate-m-per-px", t.plate_m_per_px,
                "metres per pixel at the plate edge seen; needs --m-per-px or --ar [the dimer plane's]")->check(FiniteNumber());
  c->add_option("--lens", t.lens,
                "the lens's calibration (OpenCV YAML/XML: camera_matrix, "
                "distortion_coefficients): frames undistorted before tracking [as recorded]");
  c->add_option_function<std::string>(
       "--method", [&t](const std::string& s) { t.method = tracking::ParseMethod(s, "--method"); },
       "tracking method: auto | centroid | discfit | template")
      ->default_str(tracking::ToString(t.method));
  c->add_option_function<std::string>(
       "--polarity", [&t](const std::string& s) { t.polarity = tracking::ParsePolarity(s); },
       "auto | bright | dark")
      ->default_str(tracking::ToString(t.polarity));
  c->add_option("--bits", t.sequence.camera_bits,
                "the camera's bits per pixel in 16-bit frames (8-16; 16: as stored) "
                "[a .cine's RealBPP, else as stored]");
  c->add_option("--threads", t.sequence.threads, "tracking threads (0: all cores)");
  c->add_flag("--no-simulate", cli->no_simulate, "analyse the track only, no simulation beside it");
  AddCompareOptions(c, cli.get());
  c->callback([cli, c] {
    if (!cli->scene.empty()) ApplySceneFile(c, cli->scene);
    cli->args.compare.simulate = !cli->no_simulate;
    cli->args.compare.commands = {CommandLine()};
    // RunAnalyze tracks with the compare options' --quiet.
    cli->args.track.on_diagnostic = PrintTrackDiagnostics(cli->args.compare.quiet);
    cli->args.track.on_summary = PrintSummaryLine;
    compare::RunAnalyze(cli->args);
  });
}

}  // namespace dimer::app
