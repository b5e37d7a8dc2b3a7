#pragma once
// Where frames come from: a folder of images (PNG, TIFF including multi-page, BMP, JPEG; 8- or
// 16-bit), one multi-page TIFF, a Phantom .cine file (cine_source.h), or a video file read
// through OpenCV. Folder entries are sorted
// naturally (frame_2 before frame_10). Frames are decoded on demand, never held for the whole
// sequence, so memory does not grow with its length.
//
// A frame that cannot be decoded is not an exception: Read() returns it with `error` set to a
// one-line reason (empty file, corrupt or truncated, unsupported pixel type) and the caller
// reports and skips it. Only a source that cannot be opened at all throws InputError.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dimer::tracking {

// "Natural" order: runs of digits compare as numbers, the rest byte-wise.
bool NaturalLess(const std::string& a, const std::string& b);

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

// True for the video codecs that keep every pixel (FFV1, HuffYUV, Ut Video, Lagarith, raw, PNG
// in a container). Every other codec (H.264, HEVC, MPEG-4, MJPEG, VP9, ...) is taken as lossy:
// it can be set lossless, but a lab's exports seldom are, and the file does not say.
bool LosslessVideoCodec(const std::string& fourcc);

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Opens a folder, a multi-page TIFF, a .cine file or a video (by extension). Throws InputError naming the
  // path when it does not exist, holds no frames, or cannot be opened.
  static std::unique_ptr<FrameSource> Open(const std::string& path);

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
};

// Frames already in memory (benchmarks, tests): random access, names "memory#i".
class MemorySource : public FrameSource {
 public:
  explicit MemorySource(std::vector<cv::Mat> frames) : frames_(std::move(frames)) {}
  size_t size() const override { return frames_.size(); }
  bool random_access() const override { return true; }
  Frame Read(size_t index) const override;
  bool Next(Frame* frame) override;

 private:
  std::vector<cv::Mat> frames_;
  size_t next_ = 0;
};

// Decodes one image file as a single-channel 8- or 16-bit frame (colour is converted to grey).
// A bad file gives a Frame with `error` set; it throws only when a file needs OpenCV's codecs and
// they cannot be loaded (image_codecs.h: CodecsUnavailable).
Frame DecodeImageFile(const std::string& path, size_t index, const std::string& name);

}  // namespace dimer::tracking
