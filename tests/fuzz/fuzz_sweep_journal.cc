// libFuzzer target: a sweep journal file as found on resume (SweepJournal's reader: magic,
// records, checksums, the identity, then each point's payload), and the payload decoder alone.
// InputError is the expected answer to a file that is not a journal of this sweep.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "common/error.h"
#include "sim/sweep_journal.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  dimer::sim::PointResult p;
  (void)dimer::sim::DecodePoint(bytes, &p);
  char path[] = "/tmp/dimerlab_fuzz_journal_XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return 0;
  const bool written = write(fd, data, size) == static_cast<ssize_t>(size);
  close(fd);
  if (written) {
    try {
      dimer::sim::SweepJournal journal(path, "ar = 3.9\nshard = 1/1\n");
      (void)journal.recovered();
    } catch (const dimer::InputError&) {
    }
  }
  std::remove(path);
  return 0;
}
