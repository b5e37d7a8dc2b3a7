// Built only when the tracking library is absent from the tree: render/track are not offered.
#include "app/commands.h"

namespace dimer::app {
void RegisterRender(CLI::App&) {}
void RegisterTrack(CLI::App&) {}
}  // namespace dimer::app
