#include "common/h5_chunks_ahead.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace dimer {

ChunksAhead::ChunksAhead(const H5WriteOptions& o)
    : chunk_bytes_(o.chunk_bytes), deflate_level_(o.deflate_level) {
  const int threads = FilterThreads(o.threads);
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { Work(); });
}

ChunksAhead::~ChunksAhead() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  queued_.notify_all();
  for (std::thread& t : workers_) t.join();
}

size_t ChunksAhead::ChunkRows(size_t row_bytes, size_t chunk_bytes) {
  return std::max<size_t>(1, chunk_bytes / std::max<size_t>(row_bytes, 1));
}

void ChunksAhead::AddDoubleRows(const std::string& name, size_t columns, RowFill fill) {
  Add(name, columns, std::move(fill));
}

void ChunksAhead::AddAppendedRows(const std::string& name, size_t columns) {
  Add(name, columns, RowFill());
}

void ChunksAhead::Add(const std::string& name, size_t columns, RowFill fill) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (Find(name)) throw std::logic_error("ChunksAhead: dataset added twice: " + name);
  for (const Dataset& d : datasets_) {  // a worker may hold a dataset's address
    if (d.queued > 0) throw std::logic_error("ChunksAhead: dataset added after rows: " + name);
  }
  Dataset d;
  d.name = name;
  d.elem_size = sizeof(double);
  d.row_bytes = columns * sizeof(double);
  d.chunk_rows = ChunkRows(d.row_bytes, chunk_bytes_);
  d.fill = std::move(fill);
  datasets_.push_back(std::move(d));
}

// With the lock held.
void ChunksAhead::Queue(size_t dataset, std::vector<double> rows) {
  Dataset& d = datasets_[dataset];
  tasks_.push_back({dataset, d.queued, std::move(rows)});
  ++d.queued;
  d.done.resize(d.queued);
  d.ready.resize(d.queued, 0);
}

void ChunksAhead::AppendRows(const std::string& name, const double* rows, size_t count) {
  bool queued = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Dataset* d = const_cast<Dataset*>(Find(name));
    if (!d || d->fill) throw std::logic_error("ChunksAhead: no appended dataset " + name);
    const size_t columns = d->row_bytes / sizeof(double), whole = d->chunk_rows * columns;
    for (const double* end = rows + count * columns; rows < end;) {
      const size_t take = std::min<size_t>(whole - d->partial.size(), end - rows);
      d->partial.insert(d->partial.end(), rows, rows + take);
      rows += take;
      if (d->partial.size() == whole) {
        Queue(static_cast<size_t>(d - datasets_.data()), std::move(d->partial));
        d->partial = {};
        d->partial.reserve(whole);
        queued = true;
      }
    }
  }
  if (queued) queued_.notify_all();
}

void ChunksAhead::RowsReady(size_t rows) {
  bool queued = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < datasets_.size(); ++i) {
      if (!datasets_[i].fill) continue;  // appended rows: AppendRows queues them
      while (datasets_[i].queued < rows / datasets_[i].chunk_rows) {
        Queue(i, {});
        queued = true;
      }
    }
  }
  // Called every period: waking the idle workers for nothing would cost more than the period.
  if (queued) queued_.notify_all();
}

const ChunksAhead::Dataset* ChunksAhead::Find(const std::string& name) const {
  for (const Dataset& d : datasets_) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

size_t ChunksAhead::Count(const std::string& name, size_t elem_size, size_t chunk_rows) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const Dataset* d = Find(name);
  return d && d->elem_size == elem_size && d->chunk_rows == chunk_rows ? d->queued : 0;
}

std::vector<uint8_t> ChunksAhead::Take(const std::string& name, size_t k) {
  std::unique_lock<std::mutex> lock(mutex_);
  Dataset* d = const_cast<Dataset*>(Find(name));
  if (!d || k >= d->queued) throw std::logic_error("ChunksAhead: no chunk " + name);
  if (d->ready[k] == 2) throw std::logic_error("ChunksAhead: chunk taken twice: " + name);
  filtered_.wait(lock, [&] { return failure_ || d->ready[k]; });
  if (!d->ready[k]) std::rethrow_exception(failure_);
  d->ready[k] = 2;  // taken: the memory goes with it
  return std::move(d->done[k]);
}

void ChunksAhead::Work() {
  for (;;) {
    Task task;
    const Dataset* d;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      queued_.wait(lock, [&] { return stop_ || !tasks_.empty(); });
      if (stop_) return;
      task = std::move(tasks_.front());
      tasks_.pop_front();
      d = &datasets_[task.dataset];  // datasets_ no longer grows once rows are queued
    }
    const size_t bytes = d->chunk_rows * d->row_bytes;
    const ChunkFill fill = [d, &task](size_t k, size_t, uint8_t* out) {
      if (task.rows.empty()) {
        d->fill(k * d->chunk_rows, d->chunk_rows, reinterpret_cast<double*>(out));
      } else {
        std::memcpy(out, task.rows.data(), task.rows.size() * sizeof(double));
      }
    };
    std::vector<uint8_t> out;
    try {
      out = FilterChunk(fill, task.chunk, bytes, bytes, d->elem_size, deflate_level_);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!failure_) failure_ = std::current_exception();
      filtered_.notify_all();
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      Dataset& w = datasets_[task.dataset];
      w.done[task.chunk] = std::move(out);
      w.ready[task.chunk] = 1;
    }
    filtered_.notify_all();
  }
}

}  // namespace dimer
