#include "app/commands.h"
namespace dimer::app {
void RegisterSim(CLI::App&) {}
}  // namespace dimer::app
