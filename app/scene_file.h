#pragma once
// Scene files (docs/FORMATS.md, "Scene files"): the options of a subcommand in a file, one `name = value` per line
// (`#` comments, an optional `[sim]` section header, names with or without the leading --).
// Values given on the command line win over the scene.
#include <CLI/CLI.hpp>
#include <string>

namespace dimer::app {

// Applies every `name = value` of `path` to the options of `cmd` not given on the command
// line. InputError naming the file and line for a missing file, a malformed line, an unknown
// option or a value the option rejects.
void ApplySceneFile(CLI::App* cmd, const std::string& path);

}  // namespace dimer::app
