#pragma once
// The memory a run may plan to take: half of the machine's physical memory, so that a run whose
// results cannot fit is refused before it starts (a one-line error) instead of ending in
// bad_alloc, and the machine keeps room for the file's writing and everything else.
#include <string>

namespace dimer {

// Half the physical memory in bytes (sysconf), or 8 GiB where it cannot be read.
double RunMemoryLimitBytes();

// Throws UsageError "FLAG...: the run needs about X GB, more than the Y GB allowed (half of this
// machine's memory); WHAT" when estimated_bytes is above the limit.
void CheckRunMemory(double estimated_bytes, const std::string& what_to_do);

}  // namespace dimer
