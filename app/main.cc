// dimerlab: one binary, one subcommand per verb (docs/FORMATS.md). main() only parses and
// catches: every error reaches the user as one line "dimerlab: error: ..." and one of the exit
// codes of the README's table (docs/DESIGN.md, "Errors and exit codes"):
//   0 success, 1 bad input or failed run, 2 usage error, 130 interrupted.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/usage.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/provenance.h"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
constexpr int kExitInterrupted = 130;

int Fail(int code, const std::string& message) {
  std::fprintf(stderr, "dimerlab: error: %s\n", message.c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dimerlab: bouncing-dimer experiments into physics (simulate, render, track)"};
  app.set_version_flag("--version", dimer::DimerlabVersion());
  app.require_subcommand(1);
  dimer::app::RegisterSim(app);
  dimer::app::RegisterRender(app);
  dimer::app::RegisterTrack(app);
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (auto bad = dimer::app::CheckSubcommand(app, args)) return Fail(kExitUsage, *bad);
  dimer::InstallInterruptHandler();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    return Fail(kExitUsage, dimer::app::ExtrasMessage(app, args, e.what()));
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive here too, with CLI11's success code.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    return Fail(kExitUsage, e.what());
  } catch (const dimer::Interrupted&) {
    std::fprintf(stderr, "\ndimerlab: interrupted; partial output (if any) is complete and valid\n");
    return kExitInterrupted;
  } catch (const dimer::UsageError& e) {
    return Fail(kExitUsage, e.what());
  } catch (const std::exception& e) {
    return Fail(kExitFailure, e.what());
  }
  return 0;
}
