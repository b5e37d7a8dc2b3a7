#include "common/h5_chunk_filter.h"

#include <zlib.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace dimer {
namespace {

// One thread's buffers, reused from chunk to chunk: fresh 256 KiB buffers are fresh pages that
// the kernel zeroes for every chunk.
struct Scratch {
  std::vector<uint8_t> chunk, shuffled, deflated;
};

// H5Zshuffle.c: the j-th byte of every element together, for j = 0 .. elem_size - 1. False
// (nothing to do) for 1-byte elements or a single element.
bool Shuffle(const std::vector<uint8_t>& in, size_t elem_size, std::vector<uint8_t>* out) {
  const size_t n = in.size() / elem_size;
  if (elem_size <= 1 || n <= 1) return false;
  out->resize(in.size());
  for (size_t j = 0; j < elem_size; ++j) {
    uint8_t* dst = out->data() + j * n;
    const uint8_t* src = in.data() + j;
    for (size_t i = 0; i < n; ++i) dst[i] = src[i * elem_size];
  }
  const size_t whole = n * elem_size;  // leftover bytes of a partial element, last
  std::memcpy(out->data() + whole, in.data() + whole, in.size() - whole);
  return true;
}

// H5Zdeflate.c: compress2 into compressBound bytes (never a buffer error).
void Deflate(const std::vector<uint8_t>& in, int level, std::vector<uint8_t>* out) {
  uLongf out_len = compressBound(static_cast<uLong>(in.size()));
  out->resize(out_len);
  if (compress2(out->data(), &out_len, in.data(), static_cast<uLong>(in.size()), level) != Z_OK) {
    throw std::runtime_error("deflate failed on an HDF5 chunk");
  }
  out->resize(out_len);
}

std::vector<uint8_t> Filter(const ChunkFill& fill, size_t k, size_t n, size_t chunk_bytes,
                            size_t elem_size, int deflate_level, Scratch* s) {
  s->chunk.resize(chunk_bytes);
  fill(k, n, s->chunk.data());
  std::memset(s->chunk.data() + n, 0, chunk_bytes - n);
  const std::vector<uint8_t>* stage = &s->chunk;
  if (Shuffle(*stage, elem_size, &s->shuffled)) stage = &s->shuffled;
  if (deflate_level > 0) {
    Deflate(*stage, deflate_level, &s->deflated);
    stage = &s->deflated;
  }
  std::vector<uint8_t> out;
  out.reserve(stage->size() + 4);
  out.assign(stage->begin(), stage->end());
  const uint32_t sum = Hdf5Fletcher32(out.data(), out.size());
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<uint8_t>(sum >> (8 * b)));
  return out;
}

}  // namespace

uint32_t Hdf5Fletcher32(const uint8_t* data, size_t n) {
  // Sums of 16-bit words, first byte high; 360 words is the most that cannot overflow before
  // the reduction (H5checksum.c).
  uint32_t sum1 = 0, sum2 = 0;
  size_t words = n / 2;
  while (words > 0) {
    size_t block = std::min<size_t>(words, 360);
    words -= block;
    do {
      sum1 += (static_cast<uint32_t>(data[0]) << 8) | static_cast<uint32_t>(data[1]);
      data += 2;
      sum2 += sum1;
    } while (--block);
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  }
  if (n % 2) {
    sum1 += static_cast<uint32_t>(*data) << 8;
    sum2 += sum1;
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  }
  sum1 = (sum1 & 0xffff) + (sum1 >> 16);
  sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  return (sum2 << 16) | sum1;
}

int FilterThreads(int threads) {
  return threads > 0 ? threads
                     : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::vector<uint8_t> FilterChunk(const ChunkFill& fill, size_t k, size_t n, size_t chunk_bytes,
                                 size_t elem_size, int deflate_level) {
  thread_local Scratch s;
  return Filter(fill, k, n, chunk_bytes, elem_size, deflate_level, &s);
}

bool FilterChunksInOrder(const uint8_t* data, size_t data_bytes, size_t chunk_bytes,
                         size_t elem_size, int deflate_level, int threads,
                         const ChunkWrite& write) {
  const ChunkFill copy = [&](size_t k, size_t n, uint8_t* out) {
    std::memcpy(out, data + k * chunk_bytes, n);
  };
  return FilterChunksInOrder(copy, data_bytes, chunk_bytes, elem_size, deflate_level, threads,
                             write);
}

bool FilterChunksInOrder(const ChunkFill& fill, size_t data_bytes, size_t chunk_bytes,
                         size_t elem_size, int deflate_level, int threads,
                         const ChunkWrite& write, size_t ahead_count,
                         const std::function<std::vector<uint8_t>(size_t k)>& ahead) {
  const size_t count = (data_bytes + chunk_bytes - 1) / chunk_bytes;
  ahead_count = std::min(ahead_count, count);
  auto filter = [&](size_t k, Scratch* s) {
    const size_t begin = k * chunk_bytes;
    const size_t n = std::min(data_bytes - begin, chunk_bytes);
    return Filter(fill, k, n, chunk_bytes, elem_size, deflate_level, s);
  };
  const size_t workers =
      std::min<size_t>(static_cast<size_t>(FilterThreads(threads)), count - ahead_count);
  if (workers <= 1) {  // on this thread, one chunk at a time
    Scratch s;
    for (size_t k = 0; k < count; ++k) {
      if (!write(k < ahead_count ? ahead(k) : filter(k, &s))) return false;
    }
    return true;
  }
  // Workers filter chunk after chunk into their slots, at most `window` chunks ahead of the
  // writer; this thread writes each slot in chunk order as soon as it is filled.
  const size_t window = kChunksAheadPerThread * workers;
  std::vector<std::vector<uint8_t>> slots(count);
  std::vector<char> ready(count, 0);
  std::mutex mutex;
  std::condition_variable filled, room;
  size_t next = ahead_count, written = ahead_count;
  bool stop = false;
  std::exception_ptr failure;
  auto work = [&] {
    Scratch s;
    for (;;) {
      size_t k;
      {
        std::unique_lock<std::mutex> lock(mutex);
        room.wait(lock, [&] { return stop || next >= count || next < written + window; });
        if (stop || next >= count) return;
        k = next++;
      }
      std::vector<uint8_t> bytes;
      try {
        bytes = filter(k, &s);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
        filled.notify_all();
        room.notify_all();
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      slots[k] = std::move(bytes);
      ready[k] = 1;
      filled.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (size_t i = 0; i < workers; ++i) pool.emplace_back(work);
  bool ok = true;
  for (size_t k = 0; k < count && ok; ++k) {
    std::vector<uint8_t> bytes;
    if (k < ahead_count) {  // the workers go on past ahead_count meanwhile
      try {
        ok = write(ahead(k));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        ok = false;
      }
      continue;
    }
    {
      std::unique_lock<std::mutex> lock(mutex);
      filled.wait(lock, [&] { return stop || ready[k]; });
      if (!ready[k]) break;  // a worker failed
      bytes = std::move(slots[k]);
    }
    ok = write(bytes);
    std::lock_guard<std::mutex> lock(mutex);
    written = k + 1;
    room.notify_all();
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    stop = true;
    room.notify_all();
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return ok;
}

}  // namespace dimer
