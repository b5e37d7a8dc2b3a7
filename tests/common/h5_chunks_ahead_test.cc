#include "common/h5_chunks_ahead.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/h5_file.h"
#include "tests/common/test_tmpdir.h"

namespace dimer {
namespace h5_chunks_ahead_test {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

// Rows of a smooth 3-column signal; row i is a function of i alone.
void Rows(size_t first, size_t rows, double* out) {
  for (size_t i = first; i < first + rows; ++i) {
    for (int c = 0; c < 3; ++c) *out++ = std::sin(1e-3 * static_cast<double>(i) + c);
  }
}

constexpr size_t kRows = 10'000;  // 1000-byte chunks of 41 rows: 243 whole, a partial last

void WriteFile(const std::string& path, const H5WriteOptions& o) {
  H5Writer w(path, o);
  w.WriteDoubleRows("/a", {kRows, 3}, Rows, "m", "x,y,z");
  w.WriteDoubleRows("/b", {kRows, 3}, Rows);
  w.Close();
}

// The chunks filtered ahead, as the rows grow by uneven steps (read in place for /a, handed
// over for /b), give HDF5's own file byte for byte (its pipeline the oracle), on any number of
// threads.
TEST(ChunksAhead, GiveHdf5sBytesForAnyThreadCount) {
  testing::TempDir dir;
  setenv("SOURCE_DATE_EPOCH", "0", 1);
  H5WriteOptions o;
  o.chunk_bytes = 1000;
  o.direct_chunks = false;
  WriteFile(dir / "hdf5.h5", o);
  const std::string oracle = Slurp(dir / "hdf5.h5");
  o.direct_chunks = true;
  for (int threads : {1, 2, 5}) {
    o.threads = threads;
    ChunksAhead ahead(o);
    ahead.AddDoubleRows("/a", 3, Rows);
    ahead.AddAppendedRows("/b", 3);
    std::vector<double> piece(3 * 777);
    for (size_t n = 0; n < kRows; n += 777) {
      ahead.RowsReady(n);
      const size_t rows = std::min<size_t>(777, kRows - n);
      Rows(n, rows, piece.data());
      ahead.AppendRows("/b", piece.data(), rows);
    }
    ahead.RowsReady(kRows);
    EXPECT_EQ(ahead.Count("/a", 8, 41), kRows / 41);
    EXPECT_EQ(ahead.Count("/b", 8, 41), kRows / 41);
    EXPECT_EQ(ahead.Count("/a", 8, 40), 0u) << "another chunk shape";
    EXPECT_EQ(ahead.Count("/c", 8, 41), 0u) << "not ahead";
    o.ahead = &ahead;
    WriteFile(dir / "ahead.h5", o);
    o.ahead = nullptr;
    EXPECT_TRUE(Slurp(dir / "ahead.h5") == oracle) << threads << " threads";
    EXPECT_THROW(ahead.Take("/a", 0), std::logic_error) << "taken by the writer already";
  }
  unsetenv("SOURCE_DATE_EPOCH");
}

// A fill that throws on a worker reaches the writer as that exception, not as a hang.
TEST(ChunksAhead, AWorkersFailureReachesTheWriter) {
  H5WriteOptions o;
  o.chunk_bytes = 1000;
  o.threads = 2;
  ChunksAhead ahead(o);
  ahead.AddDoubleRows("/a", 3, [](size_t first, size_t, double*) {
    if (first >= 41 * 3) throw std::runtime_error("row source failed");
  });
  ahead.RowsReady(kRows);
  EXPECT_THROW(ahead.Take("/a", 5), std::runtime_error);
}

}  // namespace
}  // namespace h5_chunks_ahead_test
}  // namespace dimer
