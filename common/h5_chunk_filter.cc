#include "common/h5_chunk_filter.h"

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace dimer {
namespace {

// H5Zshuffle.c: the j-th byte of every element together, for j = 0 .. elem_size - 1.
std::vector<uint8_t> Shuffle(const std::vector<uint8_t>& in, size_t elem_size) {
  const size_t n = in.size() / elem_size;
  if (elem_size <= 1 || n <= 1) return in;
  std::vector<uint8_t> out(in.size());
  for (size_t j = 0; j < elem_size; ++j) {
    uint8_t* dst = out.data() + j * n;
    const uint8_t* src = in.data() + j;
    for (size_t i = 0; i < n; ++i) dst[i] = src[i * elem_size];
  }
  const size_t whole = n * elem_size;  // leftover bytes of a partial element, last
  std::memcpy(out.data() + whole, in.data() + whole, in.size() - whole);
  return out;
}

// H5Zdeflate.c: compress2 into compressBound bytes (never a buffer error).
std::vector<uint8_t> Deflate(const std::vector<uint8_t>& in, int level) {
  uLongf out_len = compressBound(static_cast<uLong>(in.size()));
  std::vector<uint8_t> out(out_len);
  if (compress2(out.data(), &out_len, in.data(), static_cast<uLong>(in.size()), level) != Z_OK) {
    throw std::runtime_error("deflate failed on an HDF5 chunk");
  }
  out.resize(out_len);
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

std::vector<uint8_t> FilterChunk(const uint8_t* raw, size_t data_bytes, size_t chunk_bytes,
                                 size_t elem_size, int deflate_level) {
  std::vector<uint8_t> chunk(chunk_bytes, 0);
  std::memcpy(chunk.data(), raw, std::min(data_bytes, chunk_bytes));
  std::vector<uint8_t> out = Shuffle(chunk, elem_size);
  if (deflate_level > 0) out = Deflate(out, deflate_level);
  const uint32_t sum = Hdf5Fletcher32(out.data(), out.size());
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<uint8_t>(sum >> (8 * b)));
  return out;
}

int FilterThreads(int threads) {
  return threads > 0 ? threads
                     : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::vector<std::vector<uint8_t>> FilterChunks(const uint8_t* data, size_t data_bytes,
                                               size_t chunk_bytes, size_t elem_size,
                                               int deflate_level, int threads) {
  const size_t count = (data_bytes + chunk_bytes - 1) / chunk_bytes;
  std::vector<std::vector<uint8_t>> out(count);
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t k = next++; k < count; k = next++) {
      const size_t begin = k * chunk_bytes;
      out[k] = FilterChunk(data + begin, data_bytes - begin, chunk_bytes, elem_size,
                           deflate_level);
    }
  };
  const size_t helpers =
      std::min<size_t>(static_cast<size_t>(FilterThreads(threads)), count) - (count > 0);
  std::vector<std::thread> pool;
  // A failure on a helper thread (out of memory) must not terminate the process: it is kept
  // and rethrown here.
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  for (size_t i = 0; i < helpers; ++i) {
    pool.emplace_back([&] {
      try {
        work();
      } catch (...) {
        if (!failed.exchange(true)) failure = std::current_exception();
        next = count;
      }
    });
  }
  try {
    work();
  } catch (...) {
    next = count;
    for (std::thread& t : pool) t.join();
    throw;
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return out;
}

}  // namespace dimer
