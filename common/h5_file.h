#pragma once
// Thin RAII layer over the HDF5 C API, for the layouts of docs/FORMATS.md. Dataset names are
// absolute ("/events/t"); missing parent groups are created. Object timestamps are disabled so
// identical content gives identical bytes (determinism). Every failure names the file.
//
// Integrity (docs/FORMATS.md, "Storage and integrity"): every non-empty dataset is chunked and
// passes through shuffle + deflate + Fletcher32, in that order, so a flipped byte anywhere in a
// dataset's stored data fails the checksum on reading (the checksum is over the compressed
// bytes, checked before inflating) and the reader names the dataset instead of returning wrong
// numbers. Strings are stored fixed-length (null-terminated, UTF-8) so that they too live inside the
// checksummed chunks (variable-length strings would sit in an unchecked heap); string attributes
// likewise stay in their object header. The file uses the HDF5 1.10 format, whose superblock,
// object headers and chunk indexes carry their own checksums, so a flipped byte outside the
// data is an error too (or lands in padding). All three filters are built into every HDF5
// library: h5py, MATLAB and h5dump read the files with no plugin (HDF5 >= 1.10). The writer
// runs the three filters itself, on worker threads, and stores the filtered chunks with
// H5Dwrite_chunk: the bytes of HDF5's own pipeline (common/h5_chunk_filter.h).
#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace dimer {

using Dims = std::vector<hsize_t>;
class ChunksAhead;  // h5_chunks_ahead.h

// Deflate level used by default: the knee of the size/speed table in docs/BENCHMARKS.md
// (bench_h5_compression).
constexpr int kDefaultDeflateLevel = 1;

struct H5WriteOptions {
  int deflate_level = kDefaultDeflateLevel;  // 0..9 (0: shuffle and checksum only)
  size_t chunk_bytes = 256 * 1024;           // target size of one chunk before compression, bytes
  // Threads that filter (compress) the chunks of a dataset, 0: every core. The file's bytes do
  // not depend on it (common/h5_chunk_filter.h).
  int threads = 0;
  // true: chunks filtered by dimerlab (h5_chunk_filter.h) and written by H5Dwrite_chunk; false:
  // HDF5's own pipeline through H5Dwrite, on one thread: the same bytes (kept as the tests'
  // oracle).
  bool direct_chunks = true;
  // Chunks filtered while their rows were still being produced (h5_chunks_ahead.h), taken by
  // WriteDoubleRows for the datasets it has; made with this chunk size and deflate level.
  ChunksAhead* ahead = nullptr;
};

// Rows [first, first + rows) of a dataset of doubles, row-major, into `out` (WriteDoubleRows).
using RowFill = std::function<void(size_t first, size_t rows, double* out)>;

class H5Writer {
 public:
  explicit H5Writer(const std::string& path);  // creates or truncates
  H5Writer(const std::string& path, const H5WriteOptions& options);
  ~H5Writer();
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  // `units` is stored as the dataset's `units` attribute when non-empty (one unit for all
  // values, or one per column, comma-separated); `columns` (comma-separated names, one per
  // column of an N x k dataset) as its `columns` attribute when non-empty.
  void WriteDoubles(const std::string& name, const std::vector<double>& data, const Dims& dims,
                    const std::string& units = "", const std::string& columns = "");
  // The same dataset from rows made on demand, on the threads that compress the chunks, so that
  // rows derived from other data are never held whole; `fill` must be safe to call from several
  // threads at once. The same bytes as WriteDoubles of the rows.
  void WriteDoubleRows(const std::string& name, const Dims& dims, const RowFill& fill,
                       const std::string& units = "", const std::string& columns = "");
  void WriteUint8(const std::string& name, const std::vector<uint8_t>& data, const Dims& dims);
  void WriteInt8(const std::string& name, const std::vector<int8_t>& data, const Dims& dims);
  void WriteInt64(const std::string& name, const std::vector<int64_t>& data, const Dims& dims);
  void WriteStrings(const std::string& name, const std::vector<std::string>& data);

  // `object` is "/" for the root or a dataset/group name.
  void SetAttr(const std::string& object, const std::string& key, double value);
  void SetAttr(const std::string& object, const std::string& key, int64_t value);
  void SetAttr(const std::string& object, const std::string& key, const std::string& value);
  void SetAttr(const std::string& object, const std::string& key, const char* value) {
    SetAttr(object, key, std::string(value));
  }
  void Close();

 private:
  void Write(const std::string& name, hid_t mem_type, hid_t file_type, const void* data,
             const Dims& dims, const RowFill* rows = nullptr);
  herr_t WriteFilteredChunks(hid_t ds, const std::string& name, const uint8_t* data,
                             const RowFill* rows, const Dims& dims, size_t elem_size);
  void SetUnitsAndColumns(const std::string& name, const std::string& units,
                          const std::string& columns);
  void EnsureParents(const std::string& name);
  hid_t OpenObject(const std::string& object);
  std::string path_;
  H5WriteOptions options_;
  hid_t file_ = -1;
};

class H5Reader {
 public:
  explicit H5Reader(const std::string& path);  // InputError if missing or not HDF5
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  const std::string& path() const { return path_; }
  bool Has(const std::string& name) const;
  // The Read* functions throw InputError naming the file and dataset if it is missing, or if
  // its stored data fails its checksum or cannot be decoded (the HDF5 reason is appended).
  std::vector<double> ReadDoubles(const std::string& name, Dims* dims = nullptr) const;
  std::vector<uint8_t> ReadUint8(const std::string& name, Dims* dims = nullptr) const;
  std::vector<int8_t> ReadInt8(const std::string& name, Dims* dims = nullptr) const;
  std::vector<int64_t> ReadInt64(const std::string& name, Dims* dims = nullptr) const;
  std::vector<std::string> ReadStrings(const std::string& name) const;

  // Attributes: nullopt when absent (or, for AttrDouble, not a number; for AttrString, not a
  // string); InputError when the file's structure around them is corrupt.
  std::optional<double> AttrDouble(const std::string& object, const std::string& key) const;
  std::optional<std::string> AttrString(const std::string& object, const std::string& key) const;
  std::vector<std::string> AttrNames(const std::string& object) const;

  // Every dataset in the file (absolute names, sorted), for tools and the schema test.
  std::vector<std::string> DatasetNames() const;
  enum class TypeClass { kFloat, kInteger, kString, kOther };
  TypeClass DatasetType(const std::string& name) const;  // InputError if missing

 private:
  template <typename T>
  std::vector<T> Read(const std::string& name, hid_t mem_type, Dims* dims) const;
  // The attribute, or -1 when it (or its object) does not exist; InputError when the file is
  // too corrupt to tell.
  hid_t OpenAttr(const std::string& object, const std::string& key) const;
  [[noreturn]] void Corrupt(const std::string& object, const std::string& what) const;
  std::string path_;
  hid_t file_ = -1;
};

}  // namespace dimer
