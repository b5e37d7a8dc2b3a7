// libdimer_codecs.so: the only code of dimerlab's binaries that calls OpenCV's imgcodecs and
// videoio, so that only this library links them (image_codecs.h says why). Thin forwards: no
// behaviour of its own, exceptions pass through to the caller as OpenCV throws them.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "tracking/io/image_codecs_table.h"

namespace dimer::tracking {
namespace {

cv::Mat Decode(const std::vector<uchar>& bytes, int flags) { return cv::imdecode(bytes, flags); }

bool ReadPages(const std::string& path, std::vector<cv::Mat>* pages, int start, int count,
               int flags) {
  return cv::imreadmulti(path, *pages, start, count, flags);
}

size_t CountPages(const std::string& path, int flags) { return cv::imcount(path, flags); }

bool Write(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  return cv::imwrite(path, image, params);
}

cv::VideoCapture* Capture(void* video) { return static_cast<cv::VideoCapture*>(video); }
cv::VideoWriter* Writer(void* writer) { return static_cast<cv::VideoWriter*>(writer); }

const ImageCodecsTable kTable = {
    kImageCodecsAbi,
    CV_VERSION,
    Decode,
    ReadPages,
    CountPages,
    Write,
    []() -> void* { return new cv::VideoCapture(); },
    [](void* v, const std::string& path) { return Capture(v)->open(path); },
    [](void* v, cv::Mat* frame) { return Capture(v)->read(*frame); },
    [](void* v) { return Capture(v)->get(cv::CAP_PROP_FRAME_COUNT); },
    [](void* v) { return Capture(v)->get(cv::CAP_PROP_FPS); },
    [](void* v) { return Capture(v)->get(cv::CAP_PROP_FOURCC); },
    [](void* v) { delete Capture(v); },
    []() -> void* { return new cv::VideoWriter(); },
    [](void* w, const std::string& path, const char* fourcc, double fps, cv::Size size) {
      const int code = cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]);
      return Writer(w)->open(path, code, fps, size);
    },
    [](void* w) { return Writer(w)->isOpened(); },
    [](void* w, const cv::Mat& image) { Writer(w)->write(image); },
    [](void* w) { Writer(w)->release(); },
    [](void* w) { delete Writer(w); },
};

}  // namespace
}  // namespace dimer::tracking

// The library's one exported symbol (the target is built with hidden visibility).
extern "C" __attribute__((visibility("default"))) const dimer::tracking::ImageCodecsTable*
dimer_codecs_table() {
  return &dimer::tracking::kTable;
}
