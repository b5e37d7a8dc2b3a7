#include "tracking/io/frame_source.h"

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/error.h"
#include "tracking/io/bmp_decode.h"
#include "tracking/io/cine_source.h"
#include "tracking/io/image_codecs.h"
#include "tracking/io/library_messages.h"
#include "tracking/io/png_check.h"
#include "tracking/io/tiff_decode.h"

namespace dimer::tracking {
namespace fs = std::filesystem;

namespace {

constexpr int kDecodeFlags = cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE;

std::string Lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
bool IsImageExt(const std::string& ext) {
  return ext == ".png" || ext == ".tif" || ext == ".tiff" || ext == ".bmp" || ext == ".jpg" ||
         ext == ".jpeg";
}
bool IsTiffExt(const std::string& ext) { return ext == ".tif" || ext == ".tiff"; }
bool IsVideoExt(const std::string& ext) {
  return ext == ".avi" || ext == ".mp4" || ext == ".mov" || ext == ".mkv" || ext == ".mj2";
}

// OpenCV's own decoder warnings would duplicate our one-line reports.
void QuietOpenCv() {
  static const bool kDone = [] {
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    return true;
  }();
  (void)kDone;
}

// Accepts 8/16-bit single channel; converts colour to grey; rejects other pixel types.
std::string Normalise(cv::Mat* image) {
  if (image->empty()) return "not a decodable image (corrupt, truncated or not an image)";
  if (image->channels() == 3) cv::cvtColor(*image, *image, cv::COLOR_BGR2GRAY);
  if (image->channels() == 4) cv::cvtColor(*image, *image, cv::COLOR_BGRA2GRAY);
  if (image->channels() != 1 || (image->depth() != CV_8U && image->depth() != CV_16U)) {
    *image = cv::Mat();
    return "unsupported pixel type (expected 8- or 16-bit grey or colour)";
  }
  return "";
}

// One entry of a folder: a file, or a page of a multi-page TIFF.
struct Entry {
  std::string path, name;
  int page = -1;  // -1: whole single-image file
};

class ListSource : public FrameSource {
 public:
  ListSource(std::vector<Entry> entries, std::vector<std::string> warnings)
      : entries_(std::move(entries)), warnings_(std::move(warnings)) {}
  std::vector<std::string> warnings() const override { return warnings_; }
  size_t size() const override { return entries_.size(); }
  bool random_access() const override { return true; }
  Frame Read(size_t index) const override {
    const Entry& e = entries_.at(index);
    if (e.page < 0) return DecodeImageFile(e.path, index, e.name);
    Frame f;
    f.index = index;
    f.name = e.name;
    std::vector<cv::Mat> pages;
    std::string said;  // OpenCV's own message, said in the frame's reason instead
    try {
      CerrToString capture(&said);
      codecs::ReadPages(e.path, &pages, e.page, 1, kDecodeFlags);
    } catch (const cv::Exception& ex) {
      pages.clear();
      said += ex.what();
    }
    if (!pages.empty()) f.image = pages[0];
    f.error = Normalise(&f.image);
    if (f.image.empty() && !said.empty()) {
      f.error = "not a decodable image: " + OneLineLibraryMessage(said);
    }
    return f;
  }
  bool Next(Frame* frame) override {
    if (next_ >= entries_.size()) return false;
    *frame = Read(next_++);
    return true;
  }

 private:
  std::vector<Entry> entries_;
  std::vector<std::string> warnings_;
  size_t next_ = 0;
};

}  // namespace

bool LosslessVideoCodec(const std::string& fourcc) {
  std::string c;
  for (char ch : fourcc) c += char(std::toupper(static_cast<unsigned char>(ch)));
  static const char* const kLossless[] = {"FFV1", "HFYU", "FFVH", "Y800", "GREY", "Y8  ", "RAW ",
                                          "DIB ", "PNG ", "MPNG", "ULRG", "ULRA", "ULY0", "ULY2",
                                          "ULY4", "ULH0", "ULH2", "ULH4", "UQY2", "LAGS", "RGBA",
                                          "BGRA", "RGB ", "BGR "};
  for (const char* k : kLossless) {
    if (c == k) return true;
  }
  return false;
}

namespace {

class VideoSource : public FrameSource {
 public:
  explicit VideoSource(const std::string& path) : path_(path), name_(fs::path(path).filename()) {
    if (!cap_.Open(path)) throw InputError(path + ": cannot open as a video (no decoder for it)");
    const double n = cap_.FrameCount();
    size_ = n > 0 ? size_t(n) : 0;
  }
  size_t size() const override { return size_; }
  bool random_access() const override { return false; }
  Frame Read(size_t) const override {
    throw std::logic_error("VideoSource is sequential: use Next()");
  }
  RecordingInfo recording() const override {
    RecordingInfo info;
    info.video_codec = cap_.Fourcc();
    return info;
  }
  bool Next(Frame* frame) override {
    cv::Mat img;
    if (!cap_.Read(&img)) return false;
    frame->index = next_;
    frame->name = name_ + "#" + std::to_string(next_);
    ++next_;
    frame->image = img;
    frame->error = Normalise(&frame->image);
    return true;
  }

 private:
  std::string path_, name_;
  codecs::VideoReader cap_;
  size_t size_ = 0, next_ = 0;
};

// Pages of a TIFF (1 for single-page or unreadable files: those are then reported on read).
// OpenCV's complaint while counting (a truncated stack) becomes one warning naming the file: its
// pages past the damage are not read.
int TiffPages(const std::string& path, std::vector<std::string>* warnings) {
  if (TiffHasOnePage(path)) return 1;  // the common case, without opening libtiff
  std::string said;
  size_t n = 1;
  try {
    CerrToString capture(&said);
    n = codecs::CountPages(path, kDecodeFlags);
  } catch (const cv::Exception& e) {
    said += e.what();
  }
  if (!said.empty()) {
    warnings->push_back(path + ": cannot count its pages (" + OneLineLibraryMessage(said) +
                        "); read as one image");
  }
  return n > 1 ? int(n) : 1;
}

void AddEntries(const fs::path& file, std::vector<Entry>* out,
                std::vector<std::string>* warnings) {
  const std::string name = file.filename().string();
  const int pages =
      IsTiffExt(Lower(file.extension().string())) ? TiffPages(file.string(), warnings) : 1;
  if (pages == 1) {
    out->push_back({file.string(), name, -1});
    return;
  }
  for (int p = 0; p < pages; ++p) {
    out->push_back({file.string(), name + "#" + std::to_string(p), p});
  }
}

std::unique_ptr<FrameSource> OpenFolder(const std::string& path) {
  std::vector<fs::path> files;
  for (const auto& de : fs::directory_iterator(path)) {
    const std::string name = de.path().filename().string();
    if (name.empty() || name[0] == '.' || de.is_directory()) continue;
    if (IsImageExt(Lower(de.path().extension().string()))) files.push_back(de.path());
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return NaturalLess(a.filename().string(), b.filename().string());
  });
  std::vector<Entry> entries;
  std::vector<std::string> warnings;
  for (const auto& f : files) AddEntries(f, &entries, &warnings);
  if (entries.empty()) {
    throw InputError(path + ": no image files (.png .tif .tiff .bmp .jpg .jpeg) in this folder");
  }
  return std::make_unique<ListSource>(std::move(entries), std::move(warnings));
}

}  // namespace

bool NaturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i]));
    const bool db = std::isdigit(static_cast<unsigned char>(b[j]));
    if (da && db) {
      size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      // Compare the digit runs as numbers without overflow: strip zeros, then length, then text.
      size_t is = i, js = j;
      while (is + 1 < ie && a[is] == '0') ++is;
      while (js + 1 < je && b[js] == '0') ++js;
      if (ie - is != je - js) return ie - is < je - js;
      const int c = a.compare(is, ie - is, b, js, je - js);
      if (c != 0) return c < 0;
      if (ie - i != je - j) return ie - i < je - j;  // "01" after "1": stable tie-break
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

Frame DecodeImageFile(const std::string& path, size_t index, const std::string& name) {
  QuietOpenCv();
  Frame f;
  f.index = index;
  f.name = name;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) {
    f.error = "cannot open file for reading";
    return f;
  }
  // One read of the whole file into a buffer reused by this thread (no per-byte iteration,
  // no allocation per frame once the buffer has grown).
  thread_local std::vector<uchar> bytes;
  const std::streamoff size = in.tellg();
  bytes.resize(size > 0 ? size_t(size) : 0);
  in.seekg(0);
  if (!bytes.empty() && !in.read(reinterpret_cast<char*>(bytes.data()), size)) bytes.clear();
  if (bytes.empty()) {
    f.error = "empty file (0 bytes)";
    return f;
  }
  if (LooksLikePng(bytes.data(), bytes.size())) {
    // A broken PNG is reported here, in one line, before libpng could print its own message.
    const std::string problem = PngStructureProblem(bytes.data(), bytes.size());
    if (!problem.empty()) {
      f.error = "not a decodable image: PNG " + problem;
      return f;
    }
  }
  // Grey 8-bit BMP and plain grey TIFF, the common exports of camera software: decoded
  // directly (bmp_decode.h, tiff_decode.h); the same pixels as through OpenCV, less CPU.
  if (DecodeGreyBmp(bytes.data(), bytes.size(), &f.image)) return f;
  if (DecodePlainTiff(bytes.data(), bytes.size(), &f.image)) return f;
  std::string said;  // OpenCV's own message, said in the frame's reason instead
  try {
    CerrToString capture(&said);
    f.image = codecs::Decode(bytes, kDecodeFlags);
  } catch (const cv::Exception& e) {
    f.image = cv::Mat();
    said += e.what();
  }
  f.error = Normalise(&f.image);
  if (f.image.empty() && !said.empty()) {
    f.error = "not a decodable image: " + OneLineLibraryMessage(said);
  }
  return f;
}

Frame MemorySource::Read(size_t index) const {
  Frame f;
  f.index = index;
  f.name = "memory#" + std::to_string(index);
  f.image = frames_.at(index);  // shares the pixels, no copy
  f.error = Normalise(&f.image);
  return f;
}

bool MemorySource::Next(Frame* frame) {
  if (next_ >= frames_.size()) return false;
  *frame = Read(next_++);
  return true;
}

std::unique_ptr<FrameSource> OpenFrameSource(const std::string& path) {
  QuietOpenCv();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": no such file or folder");
  if (fs::is_directory(path, ec)) return OpenFolder(path);
  const std::string ext = Lower(fs::path(path).extension().string());
  if (ext == ".cine") return OpenCine(path);
  if (IsVideoExt(ext)) return std::make_unique<VideoSource>(path);
  if (IsImageExt(ext)) {
    std::vector<Entry> entries;
    std::vector<std::string> warnings;
    AddEntries(fs::path(path), &entries, &warnings);
    return std::make_unique<ListSource>(std::move(entries), std::move(warnings));
  }
  throw InputError(path +
                   ": not a folder of frames, an image, a .cine or a video (.avi .mp4 .mov .mkv)");
}

}  // namespace dimer::tracking
