#pragma once
// Clean interruption of long work: the first Ctrl-C (SIGINT) or SIGTERM sets a flag that loops
// poll; they stop, write a valid partial output and exit non-zero. A second Ctrl-C kills at once.
namespace dimer {

void InstallInterruptHandler();
bool InterruptRequested();
// For tests: set or clear the flag directly.
void SetInterruptRequested(bool value);

}  // namespace dimer
