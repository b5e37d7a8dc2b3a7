#pragma once
// The binary interface between the loader in dimer_tracking (image_codecs.cc) and
// libdimer_codecs.so (image_codecs_plugin.cc), the library that holds every call into OpenCV's
// imgcodecs and videoio (image_codecs.h says why they are apart). Both sides are built from this
// header in one build, so C++ types (cv::Mat, std::string) cross it safely; what can go wrong is a
// stale library from another build or OpenCV, which the loader refuses by the two numbers below.
// Change kImageCodecsAbi whenever a member of ImageCodecsTable changes.
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace dimer::tracking {

inline constexpr int kImageCodecsAbi = 2;  // 2: video_fourcc
// The one symbol the library exports: `const ImageCodecsTable* dimer_codecs_table()`.
inline constexpr char kImageCodecsEntry[] = "dimer_codecs_table";
inline constexpr char kImageCodecsFile[] = "libdimer_codecs.so";

// Each member has the semantics (and the cv::Exception) of the OpenCV call it is named after.
// Video objects are opaque handles made by *_new and freed by *_delete.
struct ImageCodecsTable {
  int abi;                     // kImageCodecsAbi of the build that made the library
  const char* opencv_version;  // CV_VERSION the library was compiled against
  cv::Mat (*decode)(const std::vector<uchar>& bytes, int flags);  // cv::imdecode
  bool (*read_pages)(const std::string& path, std::vector<cv::Mat>* pages, int start, int count,
                     int flags);                                   // cv::imreadmulti
  size_t (*count_pages)(const std::string& path, int flags);       // cv::imcount
  bool (*write)(const std::string& path, const cv::Mat& image,
                const std::vector<int>& params);                   // cv::imwrite
  void* (*video_new)();                                            // cv::VideoCapture
  bool (*video_open)(void* video, const std::string& path);
  bool (*video_read)(void* video, cv::Mat* frame);
  double (*video_frame_count)(void* video);  // CAP_PROP_FRAME_COUNT
  double (*video_fps)(void* video);          // CAP_PROP_FPS
  double (*video_fourcc)(void* video);       // CAP_PROP_FOURCC: the codec's 4 characters
  void (*video_delete)(void* video);
  void* (*writer_new)();                                           // cv::VideoWriter
  bool (*writer_open)(void* writer, const std::string& path, const char* fourcc, double fps,
                      cv::Size size);  // fourcc: 4 characters, e.g. "MJPG"
  bool (*writer_is_opened)(void* writer);
  void (*writer_write)(void* writer, const cv::Mat& image);
  void (*writer_release)(void* writer);
  void (*writer_delete)(void* writer);
};

}  // namespace dimer::tracking
