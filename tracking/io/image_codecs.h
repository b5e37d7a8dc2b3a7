#pragma once
// OpenCV's image file codecs (imgcodecs) and video files (videoio), loaded on first use.
//
// Why: on Debian, linking imgcodecs and videoio makes every start of the process load ~190 more
// shared libraries (GDAL, GDCM, OpenEXR, FFmpeg, GStreamer, ...), ~0.09 s of CPU, most of the
// start of `dimerlab track` (docs/BENCHMARKS.md, bench_track_e2e). The inputs
// tracked most (grey BMP, plain TIFF, .cine) are decoded by our own readers and need neither. So
// dimer_tracking and dimer_compare do not link them: the few calls below go through
// libdimer_codecs.so (image_codecs_plugin.cc), which links them and is dlopen()ed, once per
// process, by the first call that needs it (PNG, JPEG, compressed or multi-page TIFF, another
// BMP, video input, writing images or video).
//
// Every function has the semantics of the OpenCV call it names, cv::Exception included; flags
// and parameters are OpenCV's (cv::IMREAD_*, cv::IMWRITE_*: imgcodecs.hpp is included for its
// enums only; calling its functions outside the library would fail to link dimerlab-full).
//
// Where the library is looked for, in order (one path is chosen, and only that one is tried):
//   1. the file named by the environment variable DIMERLAB_CODECS, when set (tests, or a
//      library kept elsewhere);
//   2. the installed layout: PREFIX/lib/dimerlab/, from PREFIX/libexec/dimerlab/dimerlab-full;
//   3. for an executable inside the build tree (dimerlab-full, the tests, the benches): the build
//      tree's copy.
// When it cannot be loaded, the call throws CodecsUnavailable: one line naming the file and the
// loader's reason, which the CLI prints as its error.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace dimer::tracking {

class CodecsUnavailable : public std::runtime_error {
 public:
  explicit CodecsUnavailable(const std::string& what) : std::runtime_error(what) {}
};

namespace codecs {

// Loads the library now if not yet loaded; throws CodecsUnavailable. For callers that go on to
// use the codecs from threads that could not carry the exception out (render's workers).
void Require();
// The file that is (or would be) loaded, after the rules above.
std::string LibraryPath();

cv::Mat Decode(const std::vector<uchar>& bytes, int flags);  // cv::imdecode
bool ReadPages(const std::string& path, std::vector<cv::Mat>* pages, int start, int count,
               int flags);                                     // cv::imreadmulti
size_t CountPages(const std::string& path, int flags);         // cv::imcount
bool Write(const std::string& path, const cv::Mat& image,
           const std::vector<int>& params = {});               // cv::imwrite

// cv::VideoCapture on a file.
class VideoReader {
 public:
  VideoReader() = default;
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  bool Open(const std::string& path);
  bool Read(cv::Mat* frame);
  double FrameCount() const;  // CAP_PROP_FRAME_COUNT: what the container declares, or <= 0
  double Fps() const;         // CAP_PROP_FPS
  // CAP_PROP_FOURCC as its 4 characters (e.g. "h264", "MJPG", "FFV1"); "" when unknown.
  std::string Fourcc() const;

 private:
  void* handle_ = nullptr;
};

// cv::VideoWriter.
class VideoWriter {
 public:
  VideoWriter() = default;
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // fourcc: the codec's 4 characters, e.g. "MJPG".
  bool Open(const std::string& path, const char (&fourcc)[5], double fps, cv::Size size);
  bool IsOpened() const;
  void Write(const cv::Mat& image);
  void Release();

 private:
  void* handle_ = nullptr;
};

}  // namespace codecs
}  // namespace dimer::tracking
