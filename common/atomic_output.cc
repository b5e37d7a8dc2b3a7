#include "common/atomic_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "common/error.h"

namespace dimer {
namespace fs = std::filesystem;

namespace {
// Hidden sibling name ".<name>.<tag>-<pid>". Built by appending: GCC 12 warns falsely
// (-Wrestrict) on `"." + std::string`.
fs::path Sibling(const fs::path& p, const char* tag) {
  std::string name = ".";
  name += p.filename().string();
  name += tag;
  name += std::to_string(getpid());
  return (p.parent_path().empty() ? fs::path(".") : p.parent_path()) / name;
}

// Creates and removes an empty file in `dir`: the only reliable test that the folder takes new
// files (permission bits say nothing for root, nor for read-only mounts or a full disc).
bool FolderTakesFiles(const fs::path& dir) {
  const fs::path probe = dir / (".dimerlab-probe-" + std::to_string(getpid()));
  const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) return false;
  close(fd);
  unlink(probe.c_str());
  return true;
}

}  // namespace

void CheckCanWrite(const std::string& final_path, bool force, AtomicOutput::Kind kind) {
  if (final_path.empty()) throw InputError("output path is empty");
  fs::path p(final_path);
  std::error_code ec;
  if (fs::exists(p, ec)) {
    if (!force) throw InputError(final_path + ": already exists; pass --force to replace it");
    const bool is_dir = fs::is_directory(p, ec);
    if (kind == AtomicOutput::Kind::kFile && is_dir) {
      throw InputError(final_path + ": is a folder; --force replaces a file, never a folder: "
                                    "give a file name");
    }
    if (kind == AtomicOutput::Kind::kDirectory && !is_dir) {
      throw InputError(final_path + ": is a file, not a folder; give a folder name");
    }
  }
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec)) {
    throw InputError(final_path + ": folder " + dir.string() + " does not exist");
  }
  if (!FolderTakesFiles(dir)) {
    throw InputError(final_path + ": cannot create files in folder " + dir.string() +
                     " (read-only or no permission)");
  }
}

void CheckCanWrite(const std::string& final_path, bool force) {
  CheckCanWrite(final_path, force, AtomicOutput::Kind::kFile);
}

AtomicOutput::AtomicOutput(std::string final_path, bool force, Kind kind)
    : final_path_(std::move(final_path)), kind_(kind) {
  CheckCanWrite(final_path_, force, kind_);
  fs::path p(final_path_);
  std::error_code ec;
  temp_path_ = Sibling(p, ".tmp-").string();
  fs::remove_all(temp_path_, ec);
  if (kind_ == Kind::kDirectory) fs::create_directory(temp_path_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_path_, ec);
  }
}

void AtomicOutput::Commit() {
  std::error_code ec;
  fs::path final_p(final_path_);
  if (kind_ == Kind::kDirectory && fs::exists(final_p, ec)) {
    // rename() cannot replace a non-empty folder: move the old one aside, then drop it.
    fs::path old = Sibling(final_p, ".old-");
    fs::rename(final_p, old);
    fs::rename(temp_path_, final_p);
    fs::remove_all(old, ec);
  } else {
    fs::rename(temp_path_, final_p);
  }
  committed_ = true;
}

}  // namespace dimer
