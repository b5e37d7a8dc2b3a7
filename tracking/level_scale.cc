#include "tracking/level_scale.h"

#include <algorithm>

namespace dimer::tracking {
namespace {

// How many frames from the start are tried for a readable one.
constexpr size_t kFirstFramesTried = 16;

class ScaledSource : public FrameSource {
 public:
  ScaledSource(FrameSource& inner, double factor) : inner_(inner), factor_(factor) {}
  size_t size() const override { return inner_.size(); }
  bool random_access() const override { return inner_.random_access(); }
  RecordingInfo recording() const override { return inner_.recording(); }
  Frame Read(size_t index) const override { return Scaled(inner_.Read(index)); }
  bool Next(Frame* frame) override {
    if (!inner_.Next(frame)) return false;
    *frame = Scaled(std::move(*frame));
    return true;
  }

 private:
  Frame Scaled(Frame f) const {
    if (f.error.empty() && f.image.depth() == CV_16U) {
      cv::Mat s;
      f.image.convertTo(s, CV_16U, factor_);
      f.image = s;
    }
    return f;
  }
  FrameSource& inner_;
  double factor_;
};

}  // namespace

LevelScale ChooseLevelScale(const FrameSource& source) {
  LevelScale s;
  const RecordingInfo rec = source.recording();
  if (!rec.known || rec.real_bpp <= 8 || rec.real_bpp >= 16 || !source.random_access()) return s;
  for (size_t i = 0; i < std::min(source.size(), kFirstFramesTried); ++i) {
    const Frame f = source.Read(i);
    if (!f.error.empty()) continue;
    if (f.image.depth() != CV_16U) return s;
    double lo = 0, hi = 0;
    cv::minMaxLoc(f.image, &lo, &hi);
    const double top = double((1 << rec.real_bpp) - 1);
    if (hi > top) {
      s.reason = "levels up to " + std::to_string(int(hi)) + " in " + f.name + ", above the " +
                 std::to_string(rec.real_bpp) + "-bit range the header states: tracked as stored";
      return s;
    }
    s.factor = 65535.0 / top;
    s.bits = rec.real_bpp;
    s.reason = std::to_string(rec.real_bpp) + "-bit levels (the header's RealBPP) scaled by " +
               "65535/" + std::to_string(int(top)) + " to the 16-bit range the tracker's levels "
               "are fractions of";
    return s;
  }
  return s;
}

std::unique_ptr<FrameSource> ScaledLevels(FrameSource& inner, double factor) {
  return std::make_unique<ScaledSource>(inner, factor);
}

}  // namespace dimer::tracking
