// `dimerlab sim`: flags of docs/FORMATS.md, registered once; a scene file (--scene) holds the same
// options in CLI11's config format and the command line overrides it.
#include <map>
#include <memory>

#include "app/commands.h"
#include "app/scene_file.h"
#include "sim/run_sim.h"

namespace dimer::app {
namespace {

struct SimCli {
  sim::SimRunArgs args;
  std::string init = "drift";
  std::string restitution = "capped";
  std::string init_state;
  std::string scene;
  bool quiet = false;
};

void AddSimOptions(CLI::App* c, SimCli* a) {
  sim::SimOptions& o = a->args.options;
  c->add_option("--ar", o.ar, "aspect ratio A_r = length / diameter")->capture_default_str();
  c->add_option("--diameter", o.diameter_m, "sphere diameter, m")->capture_default_str();
  c->add_option("--freq", o.freq_hz, "plate frequency, Hz")->capture_default_str();
  c->add_option("--gamma", o.gamma, "Gamma = 4 pi^2 a f^2 / g")->capture_default_str();
  c->add_option("--tilt-deg", o.tilt_deg, "plate tilt, degrees (> 0 rises toward +x)")
      ->capture_default_str();
  c->add_option("--plate-phase", o.plate_phase, "plate phase at t = 0, fraction of a period")
      ->capture_default_str();
  c->add_option("--eps", o.eps, "coefficient of restitution")->capture_default_str();
  c->add_option("--mu", o.mu, "sliding friction, persistent contact")->capture_default_str();
  c->add_option("--mu-s", o.mu_s, "static friction, persistent contact")->capture_default_str();
  c->add_option("--mu-hat", o.mu_hat, "sliding friction, impacts")->capture_default_str();
  c->add_option("--mu-hat-s", o.mu_hat_s, "static friction, impacts")->capture_default_str();
  c->add_option("--restitution", a->restitution,
                "impact restitution law: capped (Newton, scaled down where it would create "
                "energy) or newton (plain)")
      ->check(CLI::IsMember(std::vector<std::string>{"capped", "newton"}))
      ->capture_default_str();
  std::vector<std::string> inits;
  for (const auto& [name, kind] : sim::InitKindNames()) inits.push_back(name);
  c->add_option("--init", a->init, "initial condition")
      ->check(CLI::IsMember(inits))
      ->capture_default_str();
  c->add_option("--lift", o.lift,
                "drift release: lift of one end, fraction of d (default 0.3 at 25 Hz, scaled "
                "by (25 Hz/f)^2)");
  c->add_option("--release-phase", o.release_phase,
                "drift release: plate phase, fraction of a period (0.25: plate at its top)")
      ->capture_default_str();
  c->add_option("--init-state", a->init_state,
                "exact lab state \"x,z,theta,u,v,omega\" at t = 0 (overrides --init)");
  c->add_option("--cycles", o.cycles, "plate periods to simulate")->capture_default_str();
  c->add_option("--duration", o.duration_s, "duration, s (overrides --cycles)");
  c->add_option("--fps", o.fps, "output samples per second (0: events only)")
      ->capture_default_str();
  c->add_option("--collapse-vc", o.collapse_rel,
                "inelastic collapse threshold v_c, in units of g/f")
      ->capture_default_str();
  c->add_option("--contact-tol", o.contact_tol, "persistent-contact integration tolerance")
      ->capture_default_str();
  c->add_option("--gap-tol", o.gap_tol,
                "impact-location tolerance: deepest allowed penetration, m")
      ->capture_default_str();
  c->add_option("--max-events-per-period", o.max_events_per_period,
                "stop with an error above this many events in one period")
      ->capture_default_str();
  c->add_option("-o,--output", a->args.output, "output sim.h5")->required();
  c->add_flag("--force", a->args.force, "replace an existing output");
  c->add_flag("-q,--quiet", a->quiet, "no progress on stderr");
}

}  // namespace

void RegisterSim(CLI::App& app) {
  // Owned by the callback (and so by the app), as the options are bound to its fields.
  auto cli = std::make_shared<SimCli>();
  CLI::App* c = app.add_subcommand("sim", "event-driven simulation of the dimer -> sim.h5");
  c->add_option("--scene", cli->scene,
                 "scene file: the same options, one `name = value` per line (see samples/)");
  AddSimOptions(c, cli.get());
  c->callback([cli, c] {
    if (!cli->scene.empty()) ApplySceneFile(c, cli->scene);
    for (const auto& [name, kind] : sim::InitKindNames()) {
      if (name == cli->init) cli->args.options.init = kind;
    }
    for (const auto& [name, law] : sim::RestitutionLawNames()) {
      if (name == cli->restitution) cli->args.options.restitution = law;
    }
    if (!cli->init_state.empty()) {
      cli->args.options.init_state = sim::ParseInitState(cli->init_state);
    }
    cli->args.progress = !cli->quiet;
    const int code = sim::RunSim(cli->args);
    if (code != 0) std::exit(code);
  });
}

}  // namespace dimer::app
