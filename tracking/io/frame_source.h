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

#include <memory>
#include <string>
#include <vector>

#include "tracking/io/frame.h"

namespace dimer::tracking {

// "Natural" order: runs of digits compare as numbers, the rest byte-wise.
bool NaturalLess(const std::string& a, const std::string& b);

// True for the video codecs that keep every pixel (FFV1, HuffYUV, Ut Video, Lagarith, raw, PNG
// in a container). Every other codec (H.264, HEVC, MPEG-4, MJPEG, VP9, ...) is taken as lossy:
// it can be set lossless, but a lab's exports seldom are, and the file does not say.
bool LosslessVideoCodec(const std::string& fourcc);

// Opens a folder, a multi-page TIFF, a .cine file or a video (by extension). Throws InputError
// naming the path when it does not exist, holds no frames, or cannot be opened.
std::unique_ptr<FrameSource> OpenFrameSource(const std::string& path);

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
