#pragma once
// How a dimerlab process keeps the memory it frees. The tracker, the renderer and the simulator
// allocate and free frame-sized buffers (OpenCV images, HDF5 chunks) thousands of times a run;
// with glibc's defaults most frees that leave a few hundred KiB free at the heap's top hand it
// back to the system (brk, madvise), and the next allocation faults every page in again: those
// page faults were a fifth of `dimerlab track`'s CPU on the reference machine (perf). Kept for
// reuse, the default method tracks bench_track_e2e's 2,000 frames 24-29 % faster and the
// centroid 21-24 %, with a third of the page faults, for 2-4 MB more peak memory (its last
// row runs with DIMERLAB_HEAP=glibc). The tracks are identical: only where freed memory waits
// changes.

namespace dimer {

// Free memory at the heap's top beyond this is handed back to the system.
inline constexpr int kHeapTrimThresholdBytes = 64 << 20;
// What is kept at the top when it is trimmed, and taken beyond each request when it grows.
inline constexpr int kHeapTopPadBytes = 16 << 20;
// Buffers above this are mapped from the system on their own and unmapped when freed.
inline constexpr int kHeapMmapThresholdBytes = 32 << 20;

// Sets the process's heap policy (once, before the work starts). A no-op where the C library
// is not glibc, and where the environment holds DIMERLAB_HEAP=glibc (glibc's own defaults: the
// baseline bench_track_e2e measures this policy against in the same run).
void KeepFreedMemoryForReuse();

}  // namespace dimer
