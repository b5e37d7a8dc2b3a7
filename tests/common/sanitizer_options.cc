// Sanitizer settings of dimer_common_test, read by the sanitizer runtimes at start (no effect in
// a build without them). libhdf5 1.10 (Debian 12) keeps the metadata-cache entry of an object
// header it fails to decode (a corrupt file): allocated under H5O_protect, never freed. That
// frame alone is suppressed, so that H5File.EveryCorruptedMetadataByteIsReadOrRefused runs
// under ./dimerlab.sh sanitize; the project's own handles are closed on every path. libhdf5
// has no frame pointers, so the frame is seen only with slow unwinding on malloc.
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }
extern "C" const char* __lsan_default_suppressions() { return "leak:H5O_protect\n"; }
