#include "tracking/io/level_scale.h"

#include <algorithm>
#include <mutex>

#include "common/error.h"

namespace dimer::tracking {
namespace {

// How many frames, spread over the source, are read for their brightest level.
constexpr size_t kFramesSampled = 16;

}  // namespace

LevelScale ChooseLevelScale(const FrameSource& source, int bits) {
  LevelScale s;
  const RecordingInfo rec = source.recording();
  const bool header = rec.known && rec.real_bpp > 8 && rec.real_bpp < 16;
  if (bits == 16 || (bits == 0 && !source.random_access())) return s;
  if (!source.random_access()) {  // a video, read once in order: the given bits, unchecked
    s.factor = 65535.0 / double((1u << unsigned(bits)) - 1u);
    s.bits = bits;
    s.reason = "--bits " + std::to_string(bits) + ": 16-bit levels scaled by " +
               std::to_string(s.factor) + " (not checked against the frames)";
    return s;
  }
  // The brightest level of up to kFramesSampled readable frames spread over the source (the
  // first readable one for the header's and the user's bits, which it must fit).
  std::string name;
  double hi = -1;
  size_t readable = 0;
  const size_t n = source.size();
  for (size_t j = 0; j < std::min(n, kFramesSampled); ++j) {
    const Frame f = source.Read(j * n / std::min(n, kFramesSampled));
    if (!f.error.empty()) continue;
    if (f.image.depth() != CV_16U) return s;
    double lo = 0, top = 0;
    cv::minMaxLoc(f.image, &lo, &top);
    if (top > hi) hi = top, name = f.name;
    ++readable;
    if (bits > 0 || header) break;
  }
  if (readable == 0) return s;
  // Without a header or --bits, levels that fit in fewer than 16 bits are taken as a camera's of
  // the fewest bits that hold them, 8 at least (a warning says so: a dark film of a 16-bit
  // camera would clip, past 2^bits, frames brighter than those sampled). A header that says 16
  // bits is believed.
  const bool guessed = bits == 0 && !rec.known && hi < double(1 << kGuessBitsUpTo);
  int needed = 8;
  while (needed < 16 && hi > double((1u << unsigned(needed)) - 1u)) ++needed;
  const int b = bits > 0 ? bits : header ? rec.real_bpp : guessed ? needed : 0;
  if (b == 0) return s;
  const double top = double((1u << unsigned(b)) - 1u);
  if (hi > top) {
    if (bits > 0) {
      throw InputError(name + ": levels up to " + std::to_string(int(hi)) + ", above --bits " +
                       std::to_string(bits) + " (0.." + std::to_string(int(top)) + ")");
    }
    s.reason = "levels up to " + std::to_string(int(hi)) + " in " + name + ", above the " +
               std::to_string(b) + "-bit range the header states: tracked as stored";
    return s;
  }
  s.factor = 65535.0 / top;
  s.bits = b;
  if (guessed) {
    s.warn = true;
    s.reason = name + ": 16-bit frames with levels up to " + std::to_string(int(hi)) +
               " (the brightest of " + std::to_string(readable) + " frames spread over the " +
               "film), taken as a " + std::to_string(b) + "-bit camera's and scaled by 65535/" +
               std::to_string(int(top)) + " (the tracker's levels are fractions of the full " +
               "scale); give the camera's bits with --bits (16: as stored)";
    return s;
  }
  s.reason = std::to_string(b) + "-bit levels (" +
             (bits > 0 ? std::string("--bits") : std::string("the header's RealBPP")) +
             ") scaled by 65535/" + std::to_string(int(top)) +
             " to the 16-bit range the tracker's levels are fractions of";
  return s;
}

Frame ScaledSource::Read(size_t index) const { return Scaled(inner_.Read(index)); }

bool ScaledSource::Next(Frame* frame) {
  if (!inner_.Next(frame)) return false;
  *frame = Scaled(std::move(*frame));
  return true;
}

size_t ScaledSource::clipped_frames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return clipped_.size();
}

std::string ScaledSource::first_clipped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return clipped_.empty() ? std::string() : clipped_.begin()->second;
}

namespace {

// The brightest level of a CV_16U image: a plain loop the compiler vectorises, 16 us for 640x320
// where cv::minMaxLoc (which also tracks where) takes 38, on every frame of a scaled film.
uint16_t Brightest(const cv::Mat& image) {
  uint16_t top = 0;
  for (int r = 0; r < image.rows; ++r) {
    const uint16_t* p = image.ptr<uint16_t>(r);
    for (int c = 0; c < image.cols * image.channels(); ++c) top = p[c] > top ? p[c] : top;
  }
  return top;
}

}  // namespace

Frame ScaledSource::Scaled(Frame f) const {
  if (f.error.empty() && f.image.depth() == CV_16U) {
    if (double(Brightest(f.image)) * factor_ > 65535.5) {
      std::lock_guard<std::mutex> lock(mutex_);
      clipped_.emplace(f.index, f.name);
    }
    cv::Mat s;
    f.image.convertTo(s, CV_16U, factor_);
    f.image = s;
  }
  return f;
}

std::unique_ptr<ScaledSource> ScaledLevels(FrameSource& inner, double factor) {
  return std::make_unique<ScaledSource>(inner, factor);
}

}  // namespace dimer::tracking
