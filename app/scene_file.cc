#include "app/scene_file.h"

#include <fstream>
#include <map>

#include "common/error.h"
#include "common/trim.h"

namespace dimer::app {
namespace {

using dimer::Trim;

std::string Unquote(const std::string& s) {
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) {
    return s.substr(1, s.size() - 2);
  }
  return s;
}

}  // namespace

void ApplySceneFile(CLI::App* cmd, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read scene file");
  std::map<std::string, int> line_of;  // option (long name) -> the line that set it
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string where = path + ":" + std::to_string(n) + ": ";
    const size_t hash = line.find('#');
    line = Trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (line.empty() || (line.front() == '[' && line.back() == ']')) continue;
    const size_t eq = line.find('=');
    if (eq == std::string::npos) throw InputError(where + "expected `name = value`");
    std::string name = Trim(line.substr(0, eq));
    const std::string value = Unquote(Trim(line.substr(eq + 1)));
    if (name.rfind("--", 0) == 0) name = name.substr(2);
    const std::string prefix = cmd->get_name() + ".";  // CLI11's `sim.ar = ...` form
    if (name.rfind(prefix, 0) == 0) name = name.substr(prefix.size());
    CLI::Option* opt = nullptr;
    try {
      opt = cmd->get_option("--" + name);
    } catch (const CLI::OptionNotFound&) {
      throw InputError(where + "unknown option `" + name + "` for `dimerlab " + cmd->get_name() +
                       "`");
    }
    // A setting named twice is an error, whichever value would win (ScenesTest.RepeatedSetting).
    const auto [it, first] = line_of.emplace(opt->get_name(), n);
    if (!first) {
      throw InputError(where + name + " is set again (first at line " +
                       std::to_string(it->second) + ")");
    }
    if (opt->count() > 0) continue;  // the command line overrides the scene
    try {
      opt->add_result(value);
      opt->run_callback();
    } catch (const CLI::Error& e) {
      throw InputError(where + name + " = " + value + ": " + e.what());
    }
  }
}

}  // namespace dimer::app
