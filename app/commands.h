#pragma once
// Each subcommand registers itself on the CLI11 app: it parses into a typed args struct and calls
// the library's Run function. Subcommands stay thin: no physics or image code here.
#include <CLI/CLI.hpp>

namespace dimer::app {

void RegisterSim(CLI::App& app);
void RegisterRender(CLI::App& app);
void RegisterTrack(CLI::App& app);

}  // namespace dimer::app
