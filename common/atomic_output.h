#pragma once
// Atomic outputs (docs/FORMATS.md, "Conventions"): a file or folder is written under a temporary name beside its
// final path and renamed into place only when complete, so a crash or Ctrl-C never leaves a
// truncated result under the final name. An existing output is refused unless `force` is set;
// with `force` the old one is replaced only after the new one is complete.
#include <string>

namespace dimer {

class AtomicOutput {
 public:
  enum class Kind { kFile, kDirectory };
  // Throws InputError if `final_path` exists and !force, or its folder does not exist.
  AtomicOutput(std::string final_path, bool force, Kind kind = Kind::kFile);
  ~AtomicOutput();  // removes the temporary if Commit() was not reached
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::string& temp_path() const { return temp_path_; }
  const std::string& final_path() const { return final_path_; }
  void Commit();

 private:
  std::string final_path_, temp_path_;
  Kind kind_;
  bool committed_ = false;
};

// Fails early (InputError) if `final_path` could not be written as `kind`: it exists and
// !force, it exists as the other kind (a folder where a file is asked for, or the reverse: the
// final rename would fail after all the work), its folder is missing, or a file cannot be
// created in that folder (read-only, no permission, full). Long computations call it before they
// start. The two-argument form checks for a file.
void CheckCanWrite(const std::string& final_path, bool force, AtomicOutput::Kind kind);
void CheckCanWrite(const std::string& final_path, bool force);

}  // namespace dimer
