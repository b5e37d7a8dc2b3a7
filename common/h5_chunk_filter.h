#pragma once
// HDF5's write-side filter pipeline of dimerlab's datasets (shuffle -> deflate -> Fletcher32,
// common/h5_file.h), run by dimerlab itself so that the chunks of a dataset are compressed on
// worker threads and handed to HDF5 already filtered (H5Dwrite_chunk). zlib is about half of the
// CPU time of a sim file with samples, which inside H5Dwrite would all run on the calling
// thread (docs/BENCHMARKS.md, bench_sim_speed).
//
// Each step does what the HDF5 1.10 filter does, byte for byte, so readers see the same
// datasets as from HDF5's own pipeline (h5py and h5dump with no plugin) and the file's bytes do
// not change (H5File.DirectChunksGiveHdf5sBytes keeps HDF5's pipeline as the oracle):
//   - shuffle (H5Zshuffle.c): byte j of element i goes to j * n + i, for n = chunk bytes /
//     element size whole elements; nothing for 1-byte elements or a single element; the bytes
//     past the last whole element (none here: chunks are whole elements) are copied last.
//   - deflate (H5Zdeflate.c): zlib's compress2 at the level, into compressBound bytes, so it
//     never fails and the filter mask stays 0 (checked on HDF5 1.10.8: a 1-element chunk is
//     stored 20 bytes long, mask 0).
//   - Fletcher32 (H5checksum.c, H5Zfletcher32.c): the checksum of 16-bit big-endian words over
//     the compressed bytes, appended little-endian.
// A partial edge chunk is filtered as a whole chunk, its missing rows zero (HDF5's default fill
// value, which is what its chunk cache holds there).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace dimer {

// Every chunk of a dataset whose bytes are `data` (row-major, chunks of whole rows, chunk k at
// byte k * chunk_bytes), filtered on up to `threads` threads (0: every core) and handed to
// `write` on the calling thread in chunk order, each as soon as it is ready; at most
// kChunksAheadPerThread chunks per thread are held filtered. The last chunk may be partial:
// zeros make up the rest. `deflate_level` 0 leaves deflate out (shuffle and checksum only).
// Chunks are independent: the bytes do not depend on `threads`. Returns false as soon as
// `write` does.
using ChunkWrite = std::function<bool(const std::vector<uint8_t>&)>;
bool FilterChunksInOrder(const uint8_t* data, size_t data_bytes, size_t chunk_bytes,
                         size_t elem_size, int deflate_level, int threads,
                         const ChunkWrite& write);

// The same with the raw bytes made on demand: `fill(k, n, out)` writes the first n bytes of
// chunk k (n = chunk_bytes but for a partial last chunk) on the worker that filters it, so that
// rows derived from other data are made in parallel and never held whole. Chunks k < ahead_count
// come filtered from `ahead(k)` instead (h5_chunks_ahead.h: filtered while the data was still
// being produced).
using ChunkFill = std::function<void(size_t k, size_t n, uint8_t* out)>;
bool FilterChunksInOrder(const ChunkFill& fill, size_t data_bytes, size_t chunk_bytes,
                         size_t elem_size, int deflate_level, int threads,
                         const ChunkWrite& write, size_t ahead_count = 0,
                         const std::function<std::vector<uint8_t>(size_t k)>& ahead = {});

// One chunk through the three filters, on the calling thread: what the workers above run.
std::vector<uint8_t> FilterChunk(const ChunkFill& fill, size_t k, size_t n, size_t chunk_bytes,
                                 size_t elem_size, int deflate_level);

// How far the workers may run ahead of the writer, chunks per thread: enough that a worker
// never waits for the write of a chunk, few enough that the memory held stays a few chunks.
constexpr size_t kChunksAheadPerThread = 4;

// The threads FilterChunksInOrder uses for `threads` (0: every core).
int FilterThreads(int threads);

// HDF5's Fletcher-32 (H5_checksum_fletcher32), exposed for its test.
uint32_t Hdf5Fletcher32(const uint8_t* data, size_t n);

}  // namespace dimer
