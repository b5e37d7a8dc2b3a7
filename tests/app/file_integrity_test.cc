// A flipped byte in the stored data of any dataset, in a file of any kind, is reported as an
// error naming the dataset, never read as data (docs/FORMATS.md, "Storage and integrity").
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/h5_file.h"
#include "tests/app/file_kinds.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace dimer {
namespace {

struct Extent {
  haddr_t address;
  hsize_t size;
};

// Where the chunks of dataset `name` are stored in the file.
std::vector<Extent> ChunkExtents(const std::string& path, const std::string& name) {
  std::vector<Extent> out;
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(ds);
  hsize_t n = 0;
  H5Dget_num_chunks(ds, space, &n);
  for (hsize_t i = 0; i < n; ++i) {
    hsize_t offset[8] = {};
    unsigned mask = 0;
    Extent e{};
    H5Dget_chunk_info(ds, space, i, offset, &mask, &e.address, &e.size);
    out.push_back(e);
  }
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
  return out;
}

// Reads dataset `name` the way a tool would, by its type.
void ReadDataset(const std::string& path, const std::string& name) {
  H5Reader r(path);
  switch (r.DatasetType(name)) {
    case H5Reader::TypeClass::kFloat: r.ReadDoubles(name); break;
    case H5Reader::TypeClass::kInteger: r.ReadInt64(name); break;
    default: r.ReadStrings(name); break;
  }
}

void XorByte(int fd, haddr_t at, unsigned char mask) {
  unsigned char b = 0;
  ASSERT_EQ(pread(fd, &b, 1, static_cast<off_t>(at)), 1);
  b ^= mask;
  ASSERT_EQ(pwrite(fd, &b, 1, static_cast<off_t>(at)), 1);
}

// DIMERLAB_TEST_SCALE (default 1; 0.2 under the sanitizers): the share of bytes flipped.
double TestScale() {
  const char* s = std::getenv("DIMERLAB_TEST_SCALE");
  return s ? std::atof(s) : 1.0;
}

TEST(FileIntegrity, EveryFlippedByteInADatasetIsReportedNamingIt) {
  // Every byte; every 5th under the sanitizers (DIMERLAB_TEST_SCALE 0.2: 70 s there), where the
  // point is the error paths' memory, which every 5th byte takes as well.
  const hsize_t stride = std::max<hsize_t>(1, static_cast<hsize_t>(std::lround(1 / TestScale())));
  testing::TempDir dir;
  for (const auto& file : testing::MakeEveryFileKind(dir)) {
    SCOPED_TRACE(file.kind);
    const std::vector<std::string> names = H5Reader(file.path).DatasetNames();
    size_t flips = 0, bytes = 0;
    const int fd = open(file.path.c_str(), O_RDWR);
    ASSERT_GE(fd, 0);
    for (const std::string& name : names) {
      ASSERT_NO_THROW(ReadDataset(file.path, name)) << name;  // intact: reads
      for (const Extent& e : ChunkExtents(file.path, name)) {
        bytes += e.size;
        for (hsize_t i = 0; i < e.size; i += stride) {
          // Alternate a one-bit and an all-bits flip over the bytes.
          const unsigned char mask = (i % 2) ? 0xFF : static_cast<unsigned char>(1u << (i % 8));
          XorByte(fd, e.address + i, mask);
          try {
            ReadDataset(file.path, name);
            ADD_FAILURE() << name << ": byte " << i << " of a chunk at " << e.address
                          << " flipped and the data was read without error";
          } catch (const InputError& err) {
            EXPECT_NE(std::string(err.what()).find(name), std::string::npos) << err.what();
          }
          XorByte(fd, e.address + i, mask);  // restore
          ++flips;
        }
      }
      ASSERT_NO_THROW(ReadDataset(file.path, name)) << name;  // restored: reads again
    }
    close(fd);
    RecordProperty(file.kind + "_bytes_flipped", std::to_string(flips));
    EXPECT_GT(bytes, 500u);  // the file really has data to protect
    EXPECT_GE(flips * stride, bytes);
  }
}

}  // namespace
}  // namespace dimer

namespace dimer {
namespace {

// Everything a reader can get from a file: every dataset's values and every root attribute.
std::string Content(const std::string& path) {
  H5Reader r(path);
  std::string out;
  for (const std::string& key : r.AttrNames("/")) {
    out += key + "=";
    if (auto d = r.AttrDouble("/", key)) out += std::to_string(*d);
    if (auto s = r.AttrString("/", key)) out += *s;
    out += "\n";
  }
  for (const std::string& name : r.DatasetNames()) {
    out += name + ":";
    for (const std::string& key : r.AttrNames(name)) {
      out += key + "=" + r.AttrString(name, key).value_or("?") + ";";
    }
    switch (r.DatasetType(name)) {
      case H5Reader::TypeClass::kFloat:
        for (double v : r.ReadDoubles(name)) out += std::to_string(v) + ",";
        break;
      case H5Reader::TypeClass::kInteger:
        for (int64_t v : r.ReadInt64(name)) out += std::to_string(v) + ",";
        break;
      default:
        for (const auto& v : r.ReadStrings(name)) out += v + ",";
    }
    out += "\n";
  }
  return out;
}

#if defined(__SANITIZE_ADDRESS__)
struct LeakCheckPause {
  LeakCheckPause() { __lsan_disable(); }
  ~LeakCheckPause() { __lsan_enable(); }
};
#else
struct LeakCheckPause {
  ~LeakCheckPause() {}  // user-provided: no unused-variable warning where it does nothing
};
#endif

// Beyond the datasets' data: a flipped byte in the superblock, an object header, a chunk index
// or an attribute is an error too, or lands in padding and changes nothing a reader can see.
// Every `stride`-th byte of the sim file (every 4th; fewer under the sanitizers).
TEST(FileIntegrity, AFlippedByteAnywhereIsAnErrorOrChangesNothing) {
  const off_t stride = std::max<off_t>(1, static_cast<off_t>(std::lround(4 / TestScale())));
  // HDF5 1.10 itself leaks on some error paths through corrupt metadata, blocks it may have
  // taken from its free lists long before (never our ids: the count below proves that each of
  // our error paths closed what it opened). The sanitizer build's leak checker ignores what is
  // allocated during this test.
  LeakCheckPause pause;
  testing::TempDir dir;
  const auto files = testing::MakeEveryFileKind(dir);
  const std::string path = files[0].path;
  const std::string good = Content(path);
  const int fd = open(path.c_str(), O_RDWR);
  const off_t size = lseek(fd, 0, SEEK_END);
  int silent_changes = 0, errors = 0, harmless = 0;
  for (off_t at = 0; at < size; at += stride) {
    XorByte(fd, at, 0x10);
    try {
      if (Content(path) != good) {
        ++silent_changes;
        if (silent_changes < 20) ADD_FAILURE() << "byte " << at << " changed content silently";
      } else {
        ++harmless;
      }
    } catch (const std::exception&) {
      ++errors;
    }
    // Every error path closed what it opened: no HDF5 file or object is left open.
    const ssize_t open_ids = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
    if (open_ids != 0) {
      ADD_FAILURE() << "byte " << at << ": " << open_ids << " HDF5 objects left open";
      break;
    }
    XorByte(fd, at, 0x10);
  }
  close(fd);
  RecordProperty("bytes_flipped_reported", errors);
  RecordProperty("bytes_flipped_harmless", harmless);
  EXPECT_EQ(silent_changes, 0);
  EXPECT_GT(errors, 20 * harmless);  // nearly every byte matters, and is protected
}

}  // namespace
}  // namespace dimer

#ifdef DIMERLAB_HAVE_TRACKING
namespace dimer {
namespace {

// The case that went wrong before checksums: one flipped bit in /tips/left turned x = 1.08 mm
// into 1.9e305 m and `render` carried on. Now render stops with an error naming the dataset.
TEST(FileIntegrity, RenderRefusesASimFileWithAFlippedBitInTheTips) {
  testing::TempDir dir;
  const std::string sim = testing::MakeEveryFileKind(dir)[0].path;
  const std::vector<Extent> chunks = ChunkExtents(sim, "/tips/left");
  ASSERT_FALSE(chunks.empty());
  const int fd = open(sim.c_str(), O_RDWR);
  XorByte(fd, chunks[0].address + chunks[0].size / 2, 0x40);  // one bit
  close(fd);
  tracking::RenderArgs render;
  render.input = sim;
  render.output = dir / "frames_of_corrupt";
  render.quiet = true;
  try {
    tracking::RunRender(render);
    FAIL() << "render read corrupt data without complaint";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/tips/left"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(render.output));
}

}  // namespace
}  // namespace dimer
#endif
