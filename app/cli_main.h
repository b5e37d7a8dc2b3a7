#pragma once
// The main() shared by both binaries (app/main.cc, app/main_full.cc): parse the command line
// with the subcommands `register_commands` adds, run, and turn every error into one line
// "dimerlab: error: ..." and the exit code of exit_codes.h.
#include <CLI/CLI.hpp>
#include <functional>

namespace dimer::app {

int RunCli(int argc, char** argv, const std::function<void(CLI::App&)>& register_commands);

}  // namespace dimer::app
