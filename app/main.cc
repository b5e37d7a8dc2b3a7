// dimerlab: one binary, one subcommand per verb (FORMATS.md). main() only parses and catches:
// every error reaches the user as one line "dimerlab: error: ..." and a non-zero exit.
#include <cstdio>
#include <exception>
#include <string>

#include "app/commands.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/provenance.h"

namespace {
std::string g_command_line;
}  // namespace

const std::string& dimer::app::CommandLine() { return g_command_line; }

int main(int argc, char** argv) {
  g_command_line = "dimerlab";
  for (int i = 1; i < argc; ++i) g_command_line += std::string(" ") + argv[i];
  CLI::App app{"dimerlab: bouncing-dimer experiments into physics (simulate, render, track, compare)"};
  app.set_version_flag("--version", dimer::DimerlabVersion());
  app.require_subcommand(1);
  dimer::app::RegisterSim(app);
  dimer::app::RegisterRender(app);
  dimer::app::RegisterTrack(app);
#ifdef DIMERLAB_HAVE_COMPARE
  dimer::app::RegisterCompare(app);
  dimer::app::RegisterAnalyze(app);
#endif
  dimer::InstallInterruptHandler();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const dimer::Interrupted&) {
    std::fprintf(stderr, "\ndimerlab: interrupted; partial output (if any) is complete and valid\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dimerlab: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
