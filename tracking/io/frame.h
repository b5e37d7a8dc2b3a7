#pragma once
// A frame and the interface every source of frames gives (frame_source.h opens one by the
// input's kind; cine_source.h, video and image folders implement it).
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dimer::tracking {

struct Frame {
  size_t index = 0;      // position in the sorted frame list
  std::string name;      // file name, or "file#page" for a page of a multi-page file
  cv::Mat image;         // single channel, CV_8U or CV_16U; empty when `error` is set
  std::string error;     // why the frame is unusable, empty when fine
};

// What a source's own header says about the recording (a .cine file); `known` false otherwise.
// The frame rate of a film that does not state its own (a folder of images, a TIFF stack, a
// one-sample trajectory rendered), frames/s: the paper's films ran at 2000 frames/s.
inline constexpr double kDefaultFps = 2000.0;

struct RecordingInfo {
  bool known = false;
  double fps = 0;                 // frames/s, as the header says (0: it does not)
  int64_t exposure_ns = 0;        // exposure (shutter open) time, ns
  int64_t trigger_seconds = 0;    // trigger time: seconds since 1970-01-01 UTC
  int64_t trigger_fraction = 0;   // trigger time: fraction of a second, units of 2^-32 s
  int64_t first_image_no = 0;     // camera number of the source's first frame (0 = trigger)
  int real_bpp = 0;               // bits per pixel the camera delivered (per colour in colour)
  // What the pixels are: "grey"; "bgr", interpolated colour made grey (OpenCV's BGR2GRAY); or
  // "mosaic", a colour sensor's raw Bayer mosaic made grey (tracking/io/mosaic_grey.h).
  std::string colour = "grey";
  int64_t cfa = 0;                // the colour filter array code as stored (SETUP.CFA)
  // "mosaic" only: each phase's level over its cell's mean (mosaic_grey.h) and the cells found.
  std::string mosaic_balance;
  // Each frame's time, s after the source's first frame, from the frames' own time stamps (a
  // .cine's TIME_ONLY block); empty when the source has none. Indexed like Frame::index.
  std::vector<double> frame_times;
  bool flip_v = false;            // a .cine's SETUP.bFlipV as stored (cine_source.h)
  // Video files (whatever `known` says): the codec's four characters as the container declares
  // them (e.g. "h264", "MJPG", "FFV1"); "" for other sources or when not declared.
  std::string video_codec;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Number of frames (for video, the count the container declares; reading may end earlier).
  virtual size_t size() const = 0;
  // True when Read(i) works in any order and from several threads at once (folders, TIFF).
  virtual bool random_access() const = 0;
  // Frame `index`. Random-access sources only.
  virtual Frame Read(size_t index) const = 0;
  // The next frame in order; false at the end. Every source supports it (one thread).
  virtual bool Next(Frame* frame) = 0;
  // The recording's header values, when the source has a header that says them.
  virtual RecordingInfo recording() const { return {}; }
  // What opening the source found wrong without refusing it (a TIFF stack whose pages cannot all
  // be counted), one line each naming the file: the caller reports them (the library prints
  // nothing).
  virtual std::vector<std::string> warnings() const { return {}; }
};

}  // namespace dimer::tracking
