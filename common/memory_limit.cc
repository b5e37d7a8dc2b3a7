#include "common/memory_limit.h"

#include <unistd.h>

#include <cstdio>

#include "common/error.h"

namespace dimer {

double RunMemoryLimitBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 8.0 * (1L << 30);
  return 0.5 * static_cast<double>(pages) * static_cast<double>(page);
}

void CheckRunMemory(double estimated_bytes, const std::string& what_to_do) {
  const double limit = RunMemoryLimitBytes();
  if (!(estimated_bytes > limit)) return;
  char msg[160];
  std::snprintf(msg, sizeof msg, "the run needs about %.3g GB, more than the %.3g GB allowed "
                "(half of this machine's memory); ", estimated_bytes / 1e9, limit / 1e9);
  throw UsageError(msg + what_to_do);
}

}  // namespace dimer
