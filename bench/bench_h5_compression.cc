// HDF5 compression level: file size, write time and read time of a realistic sim file at deflate
// levels 0..9, always with shuffle and Fletcher32 (docs/BENCHMARKS.md, "HDF5 compression level";
// the default level is common/h5_file.h's kDefaultDeflateLevel).
// Usage: bench_h5_compression [periods]   (default 2000 periods at 25 Hz, 2000 samples/s)
// The file's datasets are simulated once, then rewritten at each level through H5Writer, so
// every level stores exactly the same data.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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

void Save(const std::string& path, const std::vector<Dataset>& data, int level) {
  H5WriteOptions o;
  o.deflate_level = level;
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
  std::printf("| level | file MB | ratio | write s | read s | write MB/s |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  for (int level = 0; level <= 9; ++level) {
    const std::string path = dir + "/level" + std::to_string(level) + ".h5";
    const int reps = 3;  // best of three: the machine is shared
    double write_s = 1e30, read_s = 1e30;
    for (int k = 0; k < reps; ++k) {
      auto t0 = Clock::now();
      Save(path, data, level);
      write_s = std::min(write_s, Seconds(t0));
      t0 = Clock::now();
      Load(path);
      read_s = std::min(read_s, Seconds(t0));
    }
    const double mb = std::filesystem::file_size(path) / 1e6;
    std::printf("| %d | %.2f | %.2f | %.3f | %.3f | %.0f |\n", level, mb, raw / 1e6 / mb, write_s,
                read_s, raw / 1e6 / write_s);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
