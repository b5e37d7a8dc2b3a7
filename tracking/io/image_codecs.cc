// The loader of libdimer_codecs.so (image_codecs.h) and the calls that go through its table.
#include "tracking/io/image_codecs.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "tracking/io/image_codecs_table.h"

// Set by tracking/io/CMakeLists.txt.
#ifndef DIMERLAB_CODECS_FROM_EXE
#error "DIMERLAB_CODECS_FROM_EXE: the library's folder relative to the installed dimerlab-full"
#endif
#ifndef DIMERLAB_BUILD_DIR
#error "DIMERLAB_BUILD_DIR: the build tree (CMAKE_BINARY_DIR)"
#endif
#ifndef DIMERLAB_CODECS_BUILD_PATH
#error "DIMERLAB_CODECS_BUILD_PATH: the library in the build tree"
#endif

namespace dimer::tracking::codecs {
namespace {

std::string ExecutablePath() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  return n > 0 ? std::string(buf, size_t(n)) : std::string();
}

struct Library {
  const ImageCodecsTable* table = nullptr;
  std::string error;  // why `table` is null
};

// dlerror() on one line, without repeating the path the message already starts with.
std::string LoaderReason(const std::string& path) {
  const char* e = dlerror();
  std::string reason = e ? e : "unknown reason";
  if (reason.compare(0, path.size() + 2, path + ": ") == 0) reason.erase(0, path.size() + 2);
  for (char& c : reason) {
    if (c == '\n') c = ' ';
  }
  return reason;
}

Library Load() {
  const std::string path = LibraryPath();
  const std::string what = "cannot load " + path +
                           ", OpenCV's image and video codecs (needed for PNG, JPEG, compressed "
                           "TIFF, video, and writing images): ";
  // RTLD_NOW: every dependency is resolved here, so a missing one is reported now, in one line,
  // and never later from inside a decode.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) return {nullptr, what + LoaderReason(path)};
  using Entry = const ImageCodecsTable* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, kImageCodecsEntry));
  const ImageCodecsTable* table = entry ? entry() : nullptr;
  std::string problem;
  if (!table) {
    problem = std::string("no ") + kImageCodecsEntry + "(): not dimerlab's codecs library";
  } else if (table->abi != kImageCodecsAbi) {
    problem = "interface version " + std::to_string(table->abi) + ", this dimerlab needs " +
              std::to_string(kImageCodecsAbi) + " (a library from another build: reinstall)";
  } else if (std::strcmp(table->opencv_version, CV_VERSION) != 0) {
    problem = std::string("built against OpenCV ") + table->opencv_version +
              ", this dimerlab against " + CV_VERSION + " (reinstall)";
  }
  if (!problem.empty()) {
    dlclose(handle);
    return {nullptr, what + problem};
  }
  // Never closed: OpenCV keeps per-thread state and registered back-ends in the library's code
  // for the life of the process.
  return {table, ""};
}

const ImageCodecsTable& Table() {
  static std::once_flag once;
  static Library library;
  std::call_once(once, [] { library = Load(); });
  if (!library.table) throw CodecsUnavailable(library.error);
  return *library.table;
}

}  // namespace

std::string LibraryPath() {
  const char* env = std::getenv("DIMERLAB_CODECS");
  if (env && *env) return env;
  const std::string exe = ExecutablePath();
  const std::filesystem::path dir = std::filesystem::path(exe).parent_path();
  const std::string installed =
      (dir / DIMERLAB_CODECS_FROM_EXE / kImageCodecsFile).lexically_normal().string();
  if (access(installed.c_str(), F_OK) == 0) return installed;
  // An executable of the build tree uses the build tree's library (an installed one never does:
  // it would run code from a build that may have changed since).
  const std::string build_dir = std::string(DIMERLAB_BUILD_DIR) + "/";
  if (exe.compare(0, build_dir.size(), build_dir) == 0) return DIMERLAB_CODECS_BUILD_PATH;
  return installed;
}

void Require() { (void)Table(); }

cv::Mat Decode(const std::vector<uchar>& bytes, int flags) { return Table().decode(bytes, flags); }

bool ReadPages(const std::string& path, std::vector<cv::Mat>* pages, int start, int count,
               int flags) {
  return Table().read_pages(path, pages, start, count, flags);
}

size_t CountPages(const std::string& path, int flags) { return Table().count_pages(path, flags); }

bool Write(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  return Table().write(path, image, params);
}

VideoReader::~VideoReader() {
  if (handle_) Table().video_delete(handle_);
}

bool VideoReader::Open(const std::string& path) {
  if (!handle_) handle_ = Table().video_new();
  return Table().video_open(handle_, path);
}

bool VideoReader::Read(cv::Mat* frame) { return handle_ && Table().video_read(handle_, frame); }

double VideoReader::FrameCount() const { return handle_ ? Table().video_frame_count(handle_) : 0; }

double VideoReader::Fps() const { return handle_ ? Table().video_fps(handle_) : 0; }
std::string VideoReader::Fourcc() const {
  const double v = handle_ ? Table().video_fourcc(handle_) : 0;
  if (!(v > 0) || !std::isfinite(v)) return "";
  const auto code = static_cast<uint32_t>(v);
  std::string s;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((code >> (8 * i)) & 0xff);
    if (c < 32 || c > 126) return "";  // not a printable code
    s += c;
  }
  return s;
}

VideoWriter::~VideoWriter() {
  if (handle_) Table().writer_delete(handle_);
}

bool VideoWriter::Open(const std::string& path, const char (&fourcc)[5], double fps,
                       cv::Size size) {
  if (!handle_) handle_ = Table().writer_new();
  return Table().writer_open(handle_, path, fourcc, fps, size);
}

bool VideoWriter::IsOpened() const { return handle_ && Table().writer_is_opened(handle_); }

void VideoWriter::Write(const cv::Mat& image) {
  if (handle_) Table().writer_write(handle_, image);
}

void VideoWriter::Release() {
  if (handle_) Table().writer_release(handle_);
}

}  // namespace dimer::tracking::codecs
