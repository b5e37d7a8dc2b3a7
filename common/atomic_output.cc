#include "common/atomic_output.h"

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
}  // namespace

void CheckCanWrite(const std::string& final_path, bool force) {
  if (final_path.empty()) throw InputError("output path is empty");
  fs::path p(final_path);
  std::error_code ec;
  if (fs::exists(p, ec) && !force) {
    throw InputError(final_path + ": already exists; pass --force to replace it");
  }
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec)) {
    throw InputError(final_path + ": folder " + dir.string() + " does not exist");
  }
}

AtomicOutput::AtomicOutput(std::string final_path, bool force, Kind kind)
    : final_path_(std::move(final_path)), kind_(kind) {
  CheckCanWrite(final_path_, force);
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
