// dimerlab: one binary, one subcommand per verb (docs/FORMATS.md). main() only parses and
// catches: every error reaches the user as one line "dimerlab: error: ..." and a non-zero exit.
#include <cstdio>
#include <exception>
#include <string>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/usage.h"
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
  dimer::app::RegisterSweep(app);
  dimer::app::RegisterMerge(app);
  dimer::app::RegisterRender(app);
  dimer::app::RegisterTrack(app);
#ifdef DIMERLAB_HAVE_COMPARE
  dimer::app::RegisterCompare(app);
  dimer::app::RegisterAnalyze(app);
#endif
  dimer::InstallInterruptHandler();
  // Exit codes: docs/DESIGN.md, "Errors and exit codes" (the README's table).
  namespace cli = dimer::app;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (auto bad = cli::CheckSubcommand(app, args)) return cli::ReportError(cli::kExitUsage, *bad);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    return cli::ReportError(cli::kExitUsage, cli::ExtrasMessage(app, args, e.what()));
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive here too, with CLI11's success code.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    return cli::ReportError(cli::kExitUsage, e.what());
  } catch (const dimer::Interrupted&) {
    std::fprintf(stderr, "\ndimerlab: interrupted; partial output (if any) is complete and valid\n");
    return cli::kExitInterrupted;
  } catch (const dimer::UsageError& e) {
    return cli::ReportError(cli::kExitUsage, e.what());
  } catch (const std::exception& e) {
    return cli::ReportError(cli::kExitFailure, e.what());
  }
  return cli::kExitSuccess;
}
