#pragma once
// The resume journal of a sweep (docs/FORMATS.md, "Sweep files"): OUTPUT.journal beside the
// output, append-only, one record per finished point, each record fsync'd before the next point
// is counted as done. A killed sweep (Ctrl-C, kill -9, a lost node) loses at most the points
// that were running; the rerun of the same command reads the journal and computes only the
// points not in it.
//
// Layout: the line "dimerlab sweep journal 2\n" (2: records hold orbit_periods), then records [u32 n][n bytes][u32 CRC-32 of
// them] (little-endian). The first record is the sweep's identity (canonical spec + shard):
// a journal of another sweep is refused, never mixed in. A record whose length or CRC does not
// check (a write torn by the kill) ends the journal: it and anything after it are cut off.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/sweep_point.h"

namespace dimer::sim {

uint32_t Crc32(const void* data, size_t n);  // IEEE 802.3 (zlib's crc32)

class SweepJournal {
 public:
  // Opens `path`, or creates it with `identity`. InputError naming the file if it holds another
  // identity or is not a journal.
  SweepJournal(std::string path, const std::string& identity);
  ~SweepJournal();
  SweepJournal(const SweepJournal&) = delete;
  SweepJournal& operator=(const SweepJournal&) = delete;

  // The points found on opening, in journal order (a point appears once: duplicates are skipped).
  const std::vector<PointResult>& recovered() const { return recovered_; }
  long discarded_bytes() const { return discarded_bytes_; }  // torn tail cut off on opening
  // Appends one finished point and fsyncs it. Not thread-safe: callers serialise.
  void Append(const PointResult& p);
  // Closes and deletes the journal (after the final file is in place).
  void Remove();

 private:
  void Load(const std::string& identity);  // reads the records, or starts the journal
  void WriteRecord(const std::string& payload);
  std::string path_;
  int fd_ = -1;
  std::vector<PointResult> recovered_;
  long discarded_bytes_ = 0;
};

// Record payloads (exposed for tests).
std::string EncodePoint(const PointResult& p);
bool DecodePoint(const std::string& payload, PointResult* p);  // false: malformed

}  // namespace dimer::sim
