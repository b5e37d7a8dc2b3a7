#pragma once
// Each subcommand registers itself on the CLI11 app: it parses into a typed args struct and calls
// the library's Run function. Subcommands stay thin: no physics or image code here.
#include <CLI/CLI.hpp>
#include <string>

namespace dimer::app {

void RegisterSim(CLI::App& app);
void RegisterRender(CLI::App& app);
void RegisterTrack(CLI::App& app);
void RegisterCompare(CLI::App& app);
void RegisterAnalyze(CLI::App& app);
void RegisterSweep(CLI::App& app);
void RegisterMerge(CLI::App& app);

// The command line as typed (quoted in reports), set once by main().
const std::string& CommandLine();

}  // namespace dimer::app
