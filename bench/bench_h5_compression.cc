// HDF5 compression level: file size, write CPU and wall time and read time of a realistic sim
// file at deflate levels 0..9, always with shuffle and Fletcher32 (docs/BENCHMARKS.md,
// bench_h5_compression; the default level is common/h5_file.h's kDefaultDeflateLevel). A second
// table at the default level: HDF5's own filter pipeline (one thread) against dimerlab's chunks
// filtered on 1 thread and on every core (common/h5_chunk_filter.h), at three chunk sizes. A
// third, when libdeflate is installed: zlib against libdeflate, a faster encoder of the same
// format, on the same shuffled 256 KiB chunks (a measurement for the choice of encoder; a
// libdeflate stream is another stream of bytes, which zlib's inflate, and so every HDF5 reader,
// reads back: checked here).
// Usage: bench_h5_compression [periods]   (default 2000 periods at 25 Hz, 2000 samples/s)
// The file's datasets are simulated once, then rewritten at each level through H5Writer, so
// every level stores exactly the same data.
#include <sys/resource.h>
#include <zlib.h>
#ifdef DIMERLAB_BENCH_LIBDEFLATE
#include <libdeflate.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/h5_chunk_filter.h"
#include "common/h5_file.h"
#include "sim/run_sim.h"

using namespace dimer;
using Clock = std::chrono::steady_clock;

namespace {

struct Dataset {
  std::string name;
  H5Reader::TypeClass type;
  Dims dims;
  std::vector<double> doubles;
  std::vector<int64_t> ints;
  std::vector<std::string> strings;
};

std::vector<Dataset> Load(const std::string& path) {
  H5Reader r(path);
  std::vector<Dataset> out;
  for (const std::string& name : r.DatasetNames()) {
    Dataset d{name, r.DatasetType(name), {}, {}, {}, {}};
    if (d.type == H5Reader::TypeClass::kFloat) d.doubles = r.ReadDoubles(name, &d.dims);
    if (d.type == H5Reader::TypeClass::kInteger) d.ints = r.ReadInt64(name, &d.dims);
    if (d.type == H5Reader::TypeClass::kString) d.strings = r.ReadStrings(name);
    out.push_back(std::move(d));
  }
  return out;
}

void Save(const std::string& path, const std::vector<Dataset>& data, const H5WriteOptions& o) {
  H5Writer w(path, o);
  for (const Dataset& d : data) {
    if (d.type == H5Reader::TypeClass::kFloat) w.WriteDoubles(d.name, d.doubles, d.dims);
    if (d.type == H5Reader::TypeClass::kInteger) w.WriteInt64(d.name, d.ints, d.dims);
    if (d.type == H5Reader::TypeClass::kString) w.WriteStrings(d.name, d.strings);
  }
  w.Close();
}

double Seconds(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double CpuSeconds() {  // this process, every thread, user + system
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Timing {
  double mb = 0, write_cpu_s = 1e30, write_s = 1e30, read_s = 1e30;
};

// Best of three of each (the machine is shared).
Timing Time(const std::string& path, const std::vector<Dataset>& data, const H5WriteOptions& o) {
  Timing t;
  for (int k = 0; k < 3; ++k) {
    const double cpu0 = CpuSeconds();
    auto t0 = Clock::now();
    Save(path, data, o);
    t.write_s = std::min(t.write_s, Seconds(t0));
    t.write_cpu_s = std::min(t.write_cpu_s, CpuSeconds() - cpu0);
    t0 = Clock::now();
    Load(path);
    t.read_s = std::min(t.read_s, Seconds(t0));
  }
  t.mb = std::filesystem::file_size(path) / 1e6;
  return t;
}

#ifdef DIMERLAB_BENCH_LIBDEFLATE
// The datasets cut into 256 KiB chunks of whole rows (the last one zero-padded) and shuffled, as
// the writer hands them to deflate.
std::vector<std::vector<uint8_t>> ShuffledChunks(const std::vector<Dataset>& data) {
  std::vector<std::vector<uint8_t>> chunks;
  for (const Dataset& d : data) {
    std::vector<uint8_t> bytes;
    size_t elem = 8, row = 8;
    if (d.type == H5Reader::TypeClass::kString) {
      elem = 1;
      for (const auto& s : d.strings) elem = std::max(elem, s.size() + 1);
      for (const auto& s : d.strings) {
        std::string padded = s;
        padded.resize(elem, '\0');
        bytes.insert(bytes.end(), padded.begin(), padded.end());
      }
      row = elem;
    } else {
      const auto* p = d.doubles.empty() ? reinterpret_cast<const uint8_t*>(d.ints.data())
                                        : reinterpret_cast<const uint8_t*>(d.doubles.data());
      bytes.assign(p, p + 8 * (d.doubles.size() + d.ints.size()));
      for (size_t i = 1; i < d.dims.size(); ++i) row *= d.dims[i];
    }
    if (bytes.empty()) continue;
    const size_t rows = std::max<size_t>(1, 256 * 1024 / row);
    const size_t chunk = std::min(bytes.size(), rows * row);
    for (size_t at = 0; at < bytes.size(); at += chunk) {
      std::vector<uint8_t> c(chunk, 0), s(chunk);
      std::memcpy(c.data(), bytes.data() + at, std::min(chunk, bytes.size() - at));
      const size_t n = chunk / elem;
      for (size_t j = 0; j < elem; ++j) {
        for (size_t i = 0; i < n; ++i) s[j * n + i] = c[i * elem + j];
      }
      chunks.push_back(elem > 1 && n > 1 ? s : c);
    }
  }
  return chunks;
}

// One chunk's deflate by an encoder: zlib's compress2 (HDF5's H5Zdeflate.c), zlib with one
// z_stream reset per chunk instead of allocated (the same stream parameters, so it must give
// the same bytes), or libdeflate.
enum class Encoder { kCompress2, kZlibReset, kLibdeflate };
const char* kEncoderNames[] = {"zlib 1.2.13 compress2", "zlib 1.2.13, stream reset",
                               "libdeflate 1.14"};

struct Deflater {
  Deflater(Encoder encoder, int deflate_level) : e(encoder), level(deflate_level) {
    if (e == Encoder::kZlibReset) deflateInit(&zs, level);
    if (e == Encoder::kLibdeflate) ld = libdeflate_alloc_compressor(level);
  }
  ~Deflater() {
    if (e == Encoder::kZlibReset) deflateEnd(&zs);
    if (ld) libdeflate_free_compressor(ld);
  }
  std::vector<uint8_t> operator()(const std::vector<uint8_t>& in) {
    uLongf n = compressBound(static_cast<uLong>(in.size()));
    std::vector<uint8_t> out(n);
    if (e == Encoder::kCompress2) {
      compress2(out.data(), &n, in.data(), in.size(), level);
    } else if (e == Encoder::kZlibReset) {
      deflateReset(&zs);
      zs.next_in = const_cast<uint8_t*>(in.data());
      zs.avail_in = static_cast<uInt>(in.size());
      zs.next_out = out.data();
      zs.avail_out = static_cast<uInt>(n);
      deflate(&zs, Z_FINISH);
      n = zs.total_out;
    } else {
      n = libdeflate_zlib_compress(ld, in.data(), in.size(), out.data(), out.size());
    }
    out.resize(n);
    return out;
  }
  Encoder e;
  int level;
  z_stream zs{};
  libdeflate_compressor* ld = nullptr;
};

// The file's double datasets written with `e`'s deflate inside HDF5's shuffle -> deflate ->
// Fletcher32 chunks (H5Dwrite_chunk, 256 KiB chunks of whole rows), then read by h5dump and by
// the HDF5 library through its own filters: true when both read every value back exactly.
bool Hdf5ReadsIt(const std::string& path, const std::vector<Dataset>& data, Encoder e) {
  Deflater deflater(e, 1);
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  for (const Dataset& d : data) {
    if (d.type != H5Reader::TypeClass::kFloat || d.doubles.empty()) continue;
    const size_t row = d.dims.size() > 1 ? d.dims[1] : 1;
    const hsize_t rows = std::min<hsize_t>(d.dims[0], std::max<size_t>(1, 32768 / row));
    Dims chunk = d.dims;
    chunk[0] = rows;
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(dcpl);
    H5Pset_deflate(dcpl, 1);
    H5Pset_fletcher32(dcpl);
    hid_t space = H5Screate_simple(static_cast<int>(d.dims.size()), d.dims.data(), nullptr);
    hid_t ds = H5Dcreate2(file, ("/" + std::to_string(&d - data.data())).c_str(),
                          H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    const size_t n = rows * row;  // doubles in a chunk
    for (size_t at = 0; at < d.doubles.size(); at += n) {
      std::vector<uint8_t> raw(8 * n, 0), shuffled(8 * n);
      std::memcpy(raw.data(), d.doubles.data() + at, 8 * std::min(n, d.doubles.size() - at));
      for (size_t j = 0; j < 8; ++j) {
        for (size_t i = 0; i < n; ++i) shuffled[j * n + i] = raw[i * 8 + j];
      }
      std::vector<uint8_t> out = deflater(n > 1 ? shuffled : raw);
      const uint32_t sum = Hdf5Fletcher32(out.data(), out.size());
      for (int b = 0; b < 4; ++b) out.push_back(static_cast<uint8_t>(sum >> (8 * b)));
      Dims offset(d.dims.size(), 0);
      offset[0] = at / row;
      H5Dwrite_chunk(ds, H5P_DEFAULT, 0, offset.data(), out.size(), out.data());
    }
    H5Dclose(ds);
    H5Sclose(space);
    H5Pclose(dcpl);
  }
  H5Fclose(file);
  if (std::system(("h5dump '" + path + "' > /dev/null 2>&1").c_str()) != 0) return false;
  H5Reader r(path);
  for (const Dataset& d : data) {
    if (d.type != H5Reader::TypeClass::kFloat || d.doubles.empty()) continue;
    if (r.ReadDoubles("/" + std::to_string(&d - data.data())) != d.doubles) return false;
  }
  return true;
}

// h5py (its own build of HDF5's filters) reads every dataset of `path` equal to `reference`'s:
// "yes", "NO", or "-" when no python3 on the PATH or in /usr/bin has h5py.
const char* H5pyReadsIt(const std::string& path, const std::string& reference) {
  const std::string script =
      "import sys, h5py, numpy; a = h5py.File(sys.argv[1]); b = h5py.File(sys.argv[2]); "
      "sys.exit(0 if all(numpy.array_equal(a[k][...], b[k][...]) for k in b) else 1)";
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    const std::string probe = std::string(python) + " -c 'import h5py' > /dev/null 2>&1";
    if (std::system(probe.c_str()) != 0) continue;
    const std::string run = std::string(python) + " -c '" + script + "' '" + path + "' '" +
                            reference + "' > /dev/null 2>&1";
    return std::system(run.c_str()) == 0 ? "yes" : "NO";
  }
  return "-";
}

void EncoderTable(const std::vector<Dataset>& data, const std::string& dir) {
  const std::vector<std::vector<uint8_t>> chunks = ShuffledChunks(data);
  std::printf("\nthe same shuffled 256 KiB chunks (%zu), deflate by three encoders\n\n",
              chunks.size());
  std::printf("| encoder | level | compressed MB | CPU s (best of 3) | same bytes as compress2 | "
              "read back by zlib, h5dump, libhdf5; h5py |\n");
  std::printf("|---|---:|---:|---:|---|---|\n");
  for (int level : {1, 6}) {
    std::vector<std::vector<uint8_t>> reference;
    for (Encoder e : {Encoder::kCompress2, Encoder::kZlibReset, Encoder::kLibdeflate}) {
      double best = 1e30, out_bytes = 0;
      bool round_trip = true;
      std::vector<std::vector<uint8_t>> out(chunks.size());
      for (int rep = 0; rep < 3; ++rep) {
        Deflater deflater(e, level);
        const double cpu0 = CpuSeconds();
        for (size_t k = 0; k < chunks.size(); ++k) out[k] = deflater(chunks[k]);
        best = std::min(best, CpuSeconds() - cpu0);
      }
      out_bytes = 0;
      for (size_t k = 0; k < chunks.size(); ++k) {
        out_bytes += out[k].size();
        std::vector<uint8_t> back(chunks[k].size());
        uLongf n = back.size();
        round_trip &= uncompress(back.data(), &n, out[k].data(), out[k].size()) == Z_OK &&
                      back == chunks[k];
      }
      if (e == Encoder::kCompress2) reference = out;
      const std::string file = dir + (e == Encoder::kCompress2 ? "/zlib.h5" : "/encoder.h5");
      const bool hdf5 = level != 1 || Hdf5ReadsIt(file, data, e);
      const char* h5py = level != 1 ? "" : H5pyReadsIt(file, dir + "/zlib.h5");
      std::printf("| %s | %d | %.2f | %.3f | %s | %s%s%s |\n",
                  kEncoderNames[static_cast<int>(e)], level, out_bytes / 1e6, best,
                  e == Encoder::kCompress2 ? "-" : out == reference ? "yes" : "no",
                  !round_trip ? "NO" : level != 1 ? "zlib: yes" : hdf5 ? "yes" : "NO",
                  level != 1 ? "" : "; h5py: ", h5py);
      std::fflush(stdout);
    }
  }
}
#endif

}  // namespace

int main(int argc, char** argv) {
  const double periods = argc > 1 ? std::atof(argv[1]) : 2000;
  const std::string dir = std::filesystem::temp_directory_path() / "dimerlab_bench_h5";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  sim::SimRunArgs sim;
  sim.options.cycles = periods;  // the paper's drift mode, 2000 samples/s, full event log
  sim.output = dir + "/source.h5";
  sim.progress = false;
  sim::RunSim(sim);
  const std::vector<Dataset> data = Load(sim.output);
  double raw = 0;
  for (const Dataset& d : data) {
    raw += 8.0 * (d.doubles.size() + d.ints.size());
    for (const auto& s : d.strings) raw += s.size();
  }
  std::printf("\n%.0f periods, %.2f MB of values (doubles, integers, string bytes)\n\n", periods,
              raw / 1e6);
  std::printf("| level | file MB | ratio | write CPU s | write wall s | read s | write MB/s |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int level = 0; level <= 9; ++level) {
    H5WriteOptions o;
    o.deflate_level = level;
    const Timing t = Time(dir + "/level" + std::to_string(level) + ".h5", data, o);
    std::printf("| %d | %.2f | %.2f | %.3f | %.3f | %.3f | %.0f |\n", level, t.mb, raw / 1e6 / t.mb,
                t.write_cpu_s, t.write_s, t.read_s, raw / 1e6 / t.write_s);
    std::fflush(stdout);
  }
  std::printf("\nlevel %d: who filters the chunks, and their size\n\n", kDefaultDeflateLevel);
  std::printf("| chunk KiB | filtered by | file MB | write CPU s | write wall s | read s | "
              "same bytes as HDF5's |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---|\n");
  for (size_t kib : {64, 256, 1024}) {
    std::string oracle;
    for (int how = 0; how < 3; ++how) {  // HDF5's pipeline, dimerlab on 1 thread, every core
      H5WriteOptions o;
      o.chunk_bytes = kib * 1024;
      o.direct_chunks = how > 0;
      o.threads = how == 2 ? 0 : 1;
      const std::string path = dir + "/chunks" + std::to_string(how) + ".h5";
      const Timing t = Time(path, data, o);
      std::ifstream f(path, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(f)), {});
      if (how == 0) oracle = bytes;
      std::printf("| %zu | %s | %.2f | %.3f | %.3f | %.3f | %s |\n", kib,
                  how == 0 ? "HDF5 (H5Dwrite)" : how == 1 ? "dimerlab, 1 thread"
                                                          : "dimerlab, every core",
                  t.mb, t.write_cpu_s, t.write_s, t.read_s,
                  how == 0 ? "-" : bytes == oracle ? "yes" : "NO");
      std::fflush(stdout);
    }
  }
#ifdef DIMERLAB_BENCH_LIBDEFLATE
  EncoderTable(data, dir);
#endif
  std::filesystem::remove_all(dir);
  return 0;
}
