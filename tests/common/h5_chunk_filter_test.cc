#include "common/h5_chunk_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "common/h5_file.h"
#include "common/provenance.h"
#include "tests/common/test_tmpdir.h"

namespace dimer {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

// Datasets of every shape the writer meets: one element, one chunk, many chunks with a partial
// edge chunk, 2-D rows, every element type, strings of several widths, an empty dataset;
// numbers with structure (a trajectory's smooth columns) and without (noise bits).
void WriteEveryShape(const std::string& path, const H5WriteOptions& o) {
  H5Writer w(path, o);
  uint64_t lcg = 12345;
  auto noise = [&] {
    lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(lcg >> 11) / 9007199254740992.0;
  };
  w.WriteDoubles("/one", {3.14159}, {1}, "m");
  std::vector<double> smooth(4001), rows(6 * 1500);
  for (size_t i = 0; i < smooth.size(); ++i) smooth[i] = 1e-3 * std::sin(0.01 * i);
  for (double& x : rows) x = noise();
  w.WriteDoubles("/smooth", smooth, {smooth.size()}, "m");
  w.WriteDoubles("/state", rows, {1500, 6}, "m,m,rad,m/s,m/s,rad/s", "x,z,theta,u,v,omega");
  w.WriteDoubles("/exact", std::vector<double>(2 * 64, 0.5), {64, 2});
  std::vector<int8_t> sphere(3001);
  for (size_t i = 0; i < sphere.size(); ++i) sphere[i] = static_cast<int8_t>(i % 3);
  w.WriteInt8("/events/sphere", sphere, {sphere.size()});
  w.WriteUint8("/found", std::vector<uint8_t>(2 * 999, 1), {999, 2});
  std::vector<int64_t> index(777);
  for (size_t i = 0; i < index.size(); ++i) index[i] = static_cast<int64_t>(i * i);
  w.WriteInt64("/frame_index", index, {index.size()});
  std::vector<std::string> kinds;
  for (int i = 0; i < 2500; ++i) kinds.push_back(i % 7 ? "impact" : "L:slip_stick R:slip_reversal");
  w.WriteStrings("/events/detail", kinds);
  w.WriteDoubles("/empty", {}, {0, 6});
  WriteProvenance(w, "sim", {{"ar", 3.9}});
  w.Close();
}

// (deflate level, chunk bytes)
class DirectChunks : public ::testing::TestWithParam<std::tuple<int, size_t>> {};

// HDF5's own pipeline (direct_chunks = false) is the oracle: dimerlab's filtered chunks give the
// same file, byte for byte, on any number of threads.
TEST_P(DirectChunks, GiveHdf5sBytesForAnyThreadCount) {
  testing::TempDir dir;
  setenv("SOURCE_DATE_EPOCH", "0", 1);
  H5WriteOptions o;
  o.deflate_level = std::get<0>(GetParam());
  o.chunk_bytes = std::get<1>(GetParam());
  o.direct_chunks = false;
  WriteEveryShape(dir / "hdf5.h5", o);
  const std::string oracle = Slurp(dir / "hdf5.h5");
  ASSERT_GT(oracle.size(), 1000u);
  o.direct_chunks = true;
  for (int threads : {1, 2, 3, 8}) {
    o.threads = threads;
    const std::string name = "direct" + std::to_string(threads) + ".h5";
    WriteEveryShape(dir / name, o);
    EXPECT_TRUE(Slurp(dir / name) == oracle) << threads << " threads";
  }
  unsetenv("SOURCE_DATE_EPOCH");
  H5Reader r(dir / "direct2.h5");  // and it reads back through HDF5's filters
  Dims dims;
  const std::vector<double> state = r.ReadDoubles("/state", &dims);
  EXPECT_EQ(dims, (Dims{1500, 6}));
  EXPECT_EQ(r.ReadStrings("/events/detail")[7], "L:slip_stick R:slip_reversal");
  EXPECT_EQ(r.ReadInt64("/frame_index")[776], 776 * 776);
}

INSTANTIATE_TEST_SUITE_P(LevelsAndChunks, DirectChunks,
                         ::testing::Combine(::testing::Values(0, 1, 6),
                                            ::testing::Values(size_t{1000}, size_t{256 * 1024})));

TEST(Hdf5Fletcher32, SumsBigEndianWordsAndAnOddLastByte) {
  const uint8_t even[] = {0x01, 0x02};
  EXPECT_EQ(Hdf5Fletcher32(even, 2), 0x01020102u);
  const uint8_t odd[] = {0x01, 0x02, 0x03};  // sum1 = 0x0102 + 0x0300, sum2 = 0x0102 + sum1
  EXPECT_EQ(Hdf5Fletcher32(odd, 3), 0x05040402u);
}

}  // namespace
}  // namespace dimer
