#pragma once
// Chunks of datasets filtered (shuffle -> deflate -> Fletcher32, h5_chunk_filter.h) on worker
// threads while their rows are still being produced, for H5Writer to store later
// (H5WriteOptions::ahead). A simulation that records samples then runs on one core while its
// file's chunks are compressed on the other, instead of compressing them all after it ends
// (docs/BENCHMARKS.md, bench_sim_speed; SimFile.RunSimGivesHdf5sBytes holds the bytes equal).
//
// Only whole chunks are filtered ahead: a dataset of n >= rows-per-chunk rows has the same
// whole chunks whatever n turns out to be, so a run that stops early still finds its chunks
// right; the last, partial chunk is left to the writer.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/h5_chunk_filter.h"
#include "common/h5_file.h"

namespace dimer {

class ChunksAhead {
 public:
  // The chunk size, deflate level and threads (0: every core) of `o`, which the writer must
  // use too: a dataset written with other settings ignores its chunks here.
  explicit ChunksAhead(const H5WriteOptions& o);
  ~ChunksAhead();  // stops the workers; chunks not taken are dropped
  ChunksAhead(const ChunksAhead&) = delete;
  ChunksAhead& operator=(const ChunksAhead&) = delete;

  // A dataset of doubles, `columns` to a row (H5Writer::WriteDoubleRows); `fill` runs on the
  // workers and may read only rows that RowsReady published. Every dataset is added before the
  // first RowsReady.
  void AddDoubleRows(const std::string& name, size_t columns, RowFill fill);
  // Rows [0, rows) of every dataset added with a fill are final: their whole chunks are queued
  // for the workers.
  void RowsReady(size_t rows);

  // A dataset of doubles whose rows the producer hands over as they come (a log that grows by
  // reallocation, which the workers could not read in place): each whole chunk is copied out
  // and queued.
  void AddAppendedRows(const std::string& name, size_t columns);
  void AppendRows(const std::string& name, const double* rows, size_t count);

  // For the writer of `name` in chunks of `chunk_rows` rows of `elem_size` elements: how many
  // leading chunks come from Take (0 for a dataset not added or of another shape).
  size_t Count(const std::string& name, size_t elem_size, size_t chunk_rows) const;
  // Chunk k of `name` (k < Count), filtered, waiting for it; rethrows a worker's failure.
  std::vector<uint8_t> Take(const std::string& name, size_t k);

  // Rows of `row_bytes` bytes in one chunk of about `chunk_bytes` (at least 1): the shape
  // H5Writer gives a dataset of at least that many rows.
  static size_t ChunkRows(size_t row_bytes, size_t chunk_bytes);

 private:
  struct Dataset {
    std::string name;
    size_t elem_size, row_bytes, chunk_rows;
    RowFill fill;                // empty for appended rows
    std::vector<double> partial;  // appended rows of the chunk not yet whole
    size_t queued = 0;  // chunks 0 .. queued-1 are queued or done
    std::vector<std::vector<uint8_t>> done;
    std::vector<char> ready;
  };
  struct Task {
    size_t dataset, chunk;
    std::vector<double> rows;  // an appended chunk's rows; empty: the dataset's fill makes them
  };
  void Add(const std::string& name, size_t columns, RowFill fill);
  void Queue(size_t dataset, std::vector<double> rows);
  void Work();
  const Dataset* Find(const std::string& name) const;

  size_t chunk_bytes_;
  int deflate_level_;
  std::vector<Dataset> datasets_;
  mutable std::mutex mutex_;
  std::condition_variable queued_, filtered_;
  std::deque<Task> tasks_;
  bool stop_ = false;
  std::exception_ptr failure_;
  std::vector<std::thread> workers_;
};

}  // namespace dimer
