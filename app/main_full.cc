// dimerlab-full: every subcommand (docs/FORMATS.md), OpenCV linked. Users run `dimerlab`, which
// hands every command line it does not run itself to this binary (app/main.cc).
#include "app/cli_main.h"
#include "app/commands.h"

int main(int argc, char** argv) {
  return dimer::app::RunCli(argc, argv, [](CLI::App& app) {
    dimer::app::RegisterSim(app);
    dimer::app::RegisterRender(app);
    dimer::app::RegisterTrack(app);
#ifdef DIMERLAB_HAVE_COMPARE
    dimer::app::RegisterCompare(app);
    dimer::app::RegisterAnalyze(app);
#endif
  });
}
