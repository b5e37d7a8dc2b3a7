#include "common/heap_policy.h"

#include <cstdlib>
#include <cstring>

#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace dimer {

void KeepFreedMemoryForReuse() {
  const char* heap = std::getenv("DIMERLAB_HEAP");
  if (heap != nullptr && std::strcmp(heap, "glibc") == 0) return;
#if defined(__GLIBC__) && defined(M_TOP_PAD)
  // Set by mallopt, any of these fixes glibc's otherwise adaptive mmap and trim thresholds at
  // their initial 128 KiB, and a frame-sized buffer would then be mapped and unmapped at every
  // use: all three are set. The mmap threshold is the largest the adaptive rule reaches (32 MiB
  // on 64-bit).
  mallopt(M_MMAP_THRESHOLD, kHeapMmapThresholdBytes);
  mallopt(M_TRIM_THRESHOLD, kHeapTrimThresholdBytes);
  mallopt(M_TOP_PAD, kHeapTopPadBytes);
#endif
}

}  // namespace dimer
