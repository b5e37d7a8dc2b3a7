// One parse-and-catch for every dimerlab binary: every error reaches the user as one line
// "dimerlab: error: ..." and a non-zero exit (docs/DESIGN.md, "Errors and exit codes").
#include "app/cli_main.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/usage.h"
#include "common/error.h"
#include "common/heap_policy.h"
#include "common/interrupt.h"
#include "common/provenance.h"

namespace {
std::string g_command_line;
}  // namespace

const std::string& dimer::app::CommandLine() { return g_command_line; }

int dimer::app::RunCli(int argc, char** argv,
                       const std::function<void(CLI::App&)>& register_commands) {
  dimer::KeepFreedMemoryForReuse();
  g_command_line = "dimerlab";
  for (int i = 1; i < argc; ++i) g_command_line += std::string(" ") + argv[i];
  CLI::App app{"dimerlab: bouncing-dimer experiments into physics (simulate, render, track, compare)"};
  app.set_version_flag("--version", dimer::DimerlabVersion());
  app.require_subcommand(1);
  register_commands(app);
  dimer::InstallInterruptHandler();
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (auto bad = CheckSubcommand(app, args)) return ReportError(kExitUsage, *bad);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    return ReportError(kExitUsage, ExtrasMessage(app, args, e.what()));
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive here too, with CLI11's success code.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    return ReportError(kExitUsage, e.what());
  } catch (const dimer::Interrupted&) {
    std::fprintf(stderr, "\ndimerlab: interrupted; partial output (if any) is complete and valid\n");
    return kExitInterrupted;
  } catch (const dimer::UsageError& e) {
    return ReportError(kExitUsage, e.what());
  } catch (const std::exception& e) {
    return ReportError(kExitFailure, e.what());
  }
  return kExitSuccess;
}
