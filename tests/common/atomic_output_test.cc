#include "common/atomic_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"

namespace dimer {
namespace atomic_output_test {
namespace {
namespace fs = std::filesystem;

std::string Slurp(const std::string& p) {
  std::ifstream f(p);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

TEST(AtomicOutput, NothingAppearsUnderTheFinalNameUntilCommit) {
  testing::TempDir dir;
  const std::string final_path = dir / "out.h5";
  {
    AtomicOutput out(final_path, false);
    std::ofstream(out.temp_path()) << "partial";
    EXPECT_FALSE(fs::exists(final_path));
    // Destroyed without Commit(): as after a crash or Ctrl-C.
  }
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_TRUE(fs::is_empty(dir.path()));
  {
    AtomicOutput out(final_path, false);
    std::ofstream(out.temp_path()) << "complete";
    out.Commit();
  }
  EXPECT_EQ(Slurp(final_path), "complete");
}

TEST(AtomicOutput, RefusesToOverwriteWithoutForce) {
  testing::TempDir dir;
  const std::string final_path = dir / "mine.h5";
  std::ofstream(final_path) << "user data";
  EXPECT_THROW(AtomicOutput(final_path, false), InputError);
  EXPECT_EQ(Slurp(final_path), "user data");
  {
    AtomicOutput out(final_path, true);
    std::ofstream(out.temp_path()) << "new";
    EXPECT_EQ(Slurp(final_path), "user data");  // still intact until the new one is complete
    out.Commit();
  }
  EXPECT_EQ(Slurp(final_path), "new");
}

TEST(AtomicOutput, FoldersAreReplacedOnlyWhenComplete) {
  testing::TempDir dir;
  const std::string final_dir = dir / "frames";
  fs::create_directory(final_dir);
  std::ofstream(final_dir + "/old.png") << "x";
  EXPECT_THROW(AtomicOutput(final_dir, false, AtomicOutput::Kind::kDirectory), InputError);
  {
    AtomicOutput out(final_dir, true, AtomicOutput::Kind::kDirectory);
    std::ofstream(out.temp_path() + "/new.png") << "y";
    out.Commit();
  }
  EXPECT_FALSE(fs::exists(final_dir + "/old.png"));
  EXPECT_TRUE(fs::exists(final_dir + "/new.png"));
}

TEST(AtomicOutput, MissingParentFolderIsAClearError) {
  testing::TempDir dir;
  try {
    AtomicOutput out(dir / "no/such/dir/out.h5", false);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

}  // namespace
}  // namespace atomic_output_test
}  // namespace dimer

namespace dimer {
namespace atomic_output_test {
namespace {

TEST(CheckCanWrite, RefusesAFolderWhereAFileIsAskedEvenWithForce) {
  testing::TempDir dir;
  fs::create_directory(dir / "results");
  EXPECT_THROW(CheckCanWrite(dir / "results", true), InputError);
  EXPECT_THROW(AtomicOutput(dir / "results", true), InputError);
  std::ofstream(dir / "file.h5") << "x";
  EXPECT_NO_THROW(CheckCanWrite(dir / "file.h5", true));
  EXPECT_THROW(CheckCanWrite(dir / "file.h5", true, AtomicOutput::Kind::kDirectory), InputError);
  EXPECT_NO_THROW(CheckCanWrite(dir / "results", true, AtomicOutput::Kind::kDirectory));
  EXPECT_TRUE(fs::exists(dir / "results"));  // a check never removes anything
}

TEST(CheckCanWrite, RefusesAFolderThatTakesNoNewFiles) {
  // /proc exists and is a folder, but no file can be created in it, even by root (for whom
  // permission bits would prove nothing).
  if (!fs::is_directory("/proc")) GTEST_SKIP() << "no /proc";
  try {
    CheckCanWrite("/proc/out.h5", false);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create files in folder /proc"),
              std::string::npos)
        << e.what();
  }
}

TEST(CheckCanWrite, LeavesNoProbeBehind) {
  testing::TempDir dir;
  CheckCanWrite(dir / "out.h5", false);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace atomic_output_test
}  // namespace dimer
