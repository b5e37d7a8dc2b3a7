// Every dataset of every file kind describes itself (docs/FORMATS.md, "Self-description"):
// units, columns, codes, description, filters; every numeric root attribute has its unit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/h5_file.h"
#include "tests/app/file_kinds.h"
#include "tests/common/schema_check.h"

namespace dimer {
namespace {

TEST(FileSchema, EveryDatasetOfEveryFileKindDescribesItself) {
  testing::TempDir dir;
  const auto files = testing::MakeEveryFileKind(dir);
#if defined(DIMERLAB_HAVE_COMPARE)
  ASSERT_EQ(files.size(), 4u);  // sim, sweep, track and compare
#elif defined(DIMERLAB_HAVE_TRACKING)
  ASSERT_EQ(files.size(), 3u);  // sim, sweep and track
#endif
  for (const auto& f : files) {
    SCOPED_TRACE(f.kind);
    EXPECT_EQ(H5Reader(f.path).AttrString("/", "kind"), f.kind);
    const std::vector<std::string> problems = testing::SchemaProblems(f.path);
    std::string all;
    for (const auto& p : problems) all += "\n  " + p;
    EXPECT_TRUE(problems.empty()) << f.path << ":" << all;
  }
}

TEST(FileSchema, TheCheckFailsOnABareDataset) {
  // The checker itself must be able to fail: a dataset with no attributes, a 2-column one with
  // one column name, and a root number with no unit are all reported.
  testing::TempDir dir;
  const std::string path = dir / "bare.h5";
  {
    H5Writer w(path);
    w.SetAttr("/", "kind", "test");
    w.SetAttr("/", "speed", 1.0);
    w.WriteDoubles("/bare", {1, 2, 3}, {3});
    w.WriteDoubles("/pairs", {1, 2, 3, 4}, {2, 2}, "m", "x");
    w.SetAttr("/pairs", "description", "two points");
    w.WriteInt8("/coded", {0, 3}, {2});
    w.SetAttr("/coded", "codes", "0=a,1=b");
    w.SetAttr("/coded", "description", "codes without 3");
  }
  const std::vector<std::string> problems = testing::SchemaProblems(path);
  auto reported = [&](const std::string& text) {
    for (const auto& p : problems) {
      if (p.find(text) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(reported("/: no root attribute format"));
  EXPECT_TRUE(reported("root attribute speed has no unit"));
  EXPECT_TRUE(reported("/bare: no `description`"));
  EXPECT_TRUE(reported("/bare: numbers without `units`"));
  EXPECT_TRUE(reported("/pairs: `columns` names 1 columns of 2"));
  EXPECT_TRUE(reported("/coded: value 3 not explained by `codes`"));
}

}  // namespace
}  // namespace dimer

namespace dimer {
namespace {

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

TEST(FileSchema, ChunkedCompressedFilesStayBitIdenticalOnRerun) {
  // Determinism with chunking, deflate and checksums: same inputs, same bytes, every kind.
  setenv("SOURCE_DATE_EPOCH", "1763770000", 1);
  testing::TempDir dir;
  std::vector<std::string> first;
  for (const auto& f : testing::MakeEveryFileKind(dir)) first.push_back(Bytes(f.path));
  std::filesystem::remove_all(dir.path());
  std::filesystem::create_directories(dir.path());
  const auto again = testing::MakeEveryFileKind(dir);
  unsetenv("SOURCE_DATE_EPOCH");
  ASSERT_EQ(again.size(), first.size());
  for (size_t i = 0; i < again.size(); ++i) {
    EXPECT_FALSE(first[i].empty());
    EXPECT_TRUE(Bytes(again[i].path) == first[i]) << again[i].kind << " differs on rerun";
  }
}

}  // namespace
}  // namespace dimer
