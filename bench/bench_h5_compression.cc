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

void EncoderTable(const std::vector<Dataset>& data) {
  const std::vector<std::vector<uint8_t>> chunks = ShuffledChunks(data);
  std::printf("\nthe same shuffled 256 KiB chunks (%zu), deflate by two encoders\n\n",
              chunks.size());
  std::printf("| encoder | level | compressed MB | CPU s (best of 3) | zlib inflates it back |\n");
  std::printf("|---|---:|---:|---:|---|\n");
  for (int level : {1, 2, 3, 6}) {
    for (int libdeflate = 0; libdeflate < 2; ++libdeflate) {
      double best = 1e30, out_bytes = 0;
      bool round_trip = true;
      for (int rep = 0; rep < 3; ++rep) {
        libdeflate_compressor* c = libdeflate_alloc_compressor(level);
        std::vector<std::vector<uint8_t>> out(chunks.size());
        const double cpu0 = CpuSeconds();
        for (size_t k = 0; k < chunks.size(); ++k) {
          uLongf n = compressBound(static_cast<uLong>(chunks[k].size()));
          out[k].resize(n);
          if (libdeflate) {
            n = libdeflate_zlib_compress(c, chunks[k].data(), chunks[k].size(), out[k].data(),
                                         out[k].size());
          } else {
            compress2(out[k].data(), &n, chunks[k].data(), chunks[k].size(), level);
          }
          out[k].resize(n);
        }
        best = std::min(best, CpuSeconds() - cpu0);
        libdeflate_free_compressor(c);
        out_bytes = 0;
        for (size_t k = 0; k < chunks.size(); ++k) {
          out_bytes += out[k].size();
          std::vector<uint8_t> back(chunks[k].size());
          uLongf n = back.size();
          round_trip &= uncompress(back.data(), &n, out[k].data(), out[k].size()) == Z_OK &&
                        back == chunks[k];
        }
      }
      std::printf("| %s | %d | %.2f | %.3f | %s |\n", libdeflate ? "libdeflate 1.14" : "zlib 1.2.13",
                  level, out_bytes / 1e6, best, round_trip ? "yes" : "NO");
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
  EncoderTable(data);
#endif
  std::filesystem::remove_all(dir);
  return 0;
}
