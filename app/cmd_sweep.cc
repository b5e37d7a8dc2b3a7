// `dimerlab sweep` and `dimerlab merge` (docs/FORMATS.md, "Sweeps"): parse into a SweepSpec
// (a spec file first, then the flags given on the command line) and call sim::RunSweep /
// sim::RunMerge. Every setting is a string handed to sim::SetSpecValue, so a flag and a spec
// file line mean exactly the same thing.
#include <cstdio>
#include <memory>
#include <utility>

#include "app/commands.h"
#include "sim/sweep_run.h"

namespace dimer::app {
namespace {

struct SweepCli {
  std::string spec_file;
  std::vector<std::pair<std::string, CLI::Option*>> settings;  // spec name -> its flag
  std::vector<std::unique_ptr<std::string>> values;
  std::string shard = "1/1";
  sim::SweepRunArgs args;
  bool quiet = false;
};

void AddSetting(CLI::App* c, SweepCli* a, const std::string& name, const std::string& flag,
                const std::string& help) {
  a->values.push_back(std::make_unique<std::string>());
  a->settings.emplace_back(name, c->add_option(flag, *a->values.back(), help));
}

}  // namespace

void RegisterSweep(CLI::App& app) {
  auto cli = std::make_shared<SweepCli>();
  CLI::App* c = app.add_subcommand(
      "sweep", "simulate a grid of parameters (ranges a:b:step, lists a,b,c) -> sweep.h5");
  c->add_option("--spec", cli->spec_file,
                "sweep spec file: `name = value` lines (see samples/sweeps/); flags win over it");
  for (const sim::SweepParamInfo& p : sim::SweepParams()) {
    AddSetting(c, cli.get(), p.name, p.flag,
               std::string("value, list v1,v2,... or range a:b:step (") + p.units + ")");
  }
  AddSetting(c, cli.get(), "periods", "--periods", "periods measured per point (default 100)");
  AddSetting(c, cli.get(), "transient", "--transient",
             "periods simulated first and discarded (default 50)");
  AddSetting(c, cli.get(), "init", "--init",
             "initial condition: drift (release), jump, flutter, rest, drop (random, --seed)");
  AddSetting(c, cli.get(), "seed", "--seed", "drop: seed of the random initial states");
  AddSetting(c, cli.get(), "lift", "--lift", "drift release: lift, fraction of d");
  AddSetting(c, cli.get(), "release_phase", "--release-phase",
             "drift release: plate phase, fraction of a period");
  AddSetting(c, cli.get(), "diameter_scaling", "--diameter-scaling",
             "fixed, or inverse_f2: d x (25 Hz / f)^2 (lengths scale as g T^2)");
  AddSetting(c, cli.get(), "restitution", "--restitution", "capped or newton");
  c->add_option("--shard", cli->shard, "run shard K of N (points i with i mod N = K-1)")
      ->capture_default_str();
  c->add_option("--threads", cli->args.threads, "worker threads (0: every core)")
      ->capture_default_str();
  c->add_option("-o,--output", cli->args.output, "output sweep.h5 (journal: OUTPUT.journal)")
      ->required();
  c->add_option("--tsv", cli->args.tsv, "also write the rows as a tab-separated table");
  c->add_flag("--force", cli->args.force, "replace an existing output");
  c->add_flag("-q,--quiet", cli->quiet, "no progress on stderr");
  c->add_flag("--verbose", cli->args.verbose, "one stderr line per finished point");
  c->callback([cli] {
    sim::SweepSpec spec;
    if (!cli->spec_file.empty()) spec = sim::ReadSweepSpecFile(cli->spec_file);
    for (size_t k = 0; k < cli->settings.size(); ++k) {
      if (cli->settings[k].second->count() > 0) {
        sim::SetSpecValue(&spec, cli->settings[k].first, *cli->values[k], "");
      }
    }
    cli->args.spec = spec;
    cli->args.shard = sim::ParseShard(cli->shard);
    cli->args.progress = !cli->quiet;
    const sim::SweepRunStats s = sim::RunSweep(cli->args);
    std::printf("%s: %ld points (shard %s of %zu), %ld from the journal, %ld computed in %.1f s "
                "(%.1f points/s, %.0f periods/s); %ld in drift, %ld failed\n",
                cli->args.output.c_str(), s.shard_points, cli->args.shard.ToString().c_str(),
                spec.PointCount(), s.recovered, s.computed, s.seconds,
                s.seconds > 0 ? s.computed / s.seconds : 0.0,
                s.seconds > 0 ? s.periods / s.seconds : 0.0, s.drift, s.failed);
  });
}

void RegisterMerge(CLI::App& app) {
  auto args = std::make_shared<sim::MergeArgs>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* c = app.add_subcommand(
      "merge", "join the shard files of one sweep into the file the unsharded sweep writes");
  c->add_option("inputs", args->inputs, "shard files (sweep.h5 written with --shard K/N)")
      ->required();
  c->add_option("-o,--output", args->output, "output sweep.h5")->required();
  c->add_option("--tsv", args->tsv, "also write the rows as a tab-separated table");
  c->add_flag("--force", args->force, "replace an existing output");
  c->add_flag("-q,--quiet", *quiet, "accepted for symmetry (merge prints no progress)");
  c->callback([args] {
    const long n = sim::RunMerge(*args);
    std::printf("%s: %ld points merged from %zu files\n", args->output.c_str(), n,
                args->inputs.size());
  });
}

}  // namespace dimer::app
