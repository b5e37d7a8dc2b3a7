#pragma once
// For fuzz targets whose code under test reads a file by name: each input is written to one
// temporary file per process (the same name every time, removed at exit).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace dimer::fuzz {

inline const std::string& InputFile(const uint8_t* data, size_t size, const char* suffix) {
  static const std::string path = [suffix] {
    std::string p = "/tmp/dimerlab_fuzz_" + std::to_string(getpid()) + suffix;
    static std::string at_exit_path;
    at_exit_path = p;
    std::atexit([] { std::remove(at_exit_path.c_str()); });
    return p;
  }();
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

}  // namespace dimer::fuzz
