#include "common/interrupt.h"

#include <atomic>
#include <csignal>

namespace dimer {
namespace {
std::atomic<bool> g_interrupt{false};

extern "C" void OnSignal(int sig) {
  if (g_interrupt.exchange(true)) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}
}  // namespace

void InstallInterruptHandler() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}
bool InterruptRequested() { return g_interrupt.load(std::memory_order_relaxed); }
void SetInterruptRequested(bool value) { g_interrupt.store(value); }

}  // namespace dimer
