// dimerlab: one binary, one subcommand per verb (FORMATS.md). main() only parses and catches:
// every error reaches the user as one line "dimerlab: error: ..." and a non-zero exit.
#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/provenance.h"

int main(int argc, char** argv) {
  CLI::App app{"dimerlab: bouncing-dimer experiments into physics (simulate, render, track)"};
  app.set_version_flag("--version", dimer::DimerlabVersion());
  app.require_subcommand(1);
  dimer::app::RegisterSim(app);
  dimer::app::RegisterRender(app);
  dimer::app::RegisterTrack(app);
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
