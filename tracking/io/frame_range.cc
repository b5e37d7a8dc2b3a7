#include "tracking/io/frame_range.h"

#include <algorithm>
#include <cctype>
#include <limits>

#include "common/error.h"

namespace dimer::tracking {
namespace {

// A non-negative decimal integer, all of `s`; nullopt otherwise (signs, spaces, overflow).
std::optional<size_t> ParseIndex(const std::string& s) {
  if (s.empty() || s.size() > 18) return std::nullopt;
  size_t v = 0;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    v = v * 10 + size_t(c - '0');
  }
  return v;
}

class RangeSource : public FrameSource {
 public:
  RangeSource(std::unique_ptr<FrameSource> inner, size_t first, std::optional<size_t> end)
      : inner_(std::move(inner)), first_(first) {
    const size_t n = inner_->size();
    size_t stop = end.value_or(n);
    if (n > 0) stop = std::min(stop, n);
    // A sequential source that does not know its length (n = 0) reports the requested count.
    size_ = n == 0 && !end ? 0 : stop - std::min(first_, stop);
    limit_ = end ? *end - first_ : std::numeric_limits<size_t>::max();
  }
  size_t size() const override { return size_; }
  bool random_access() const override { return inner_->random_access(); }
  Frame Read(size_t index) const override { return inner_->Read(first_ + index); }
  bool Next(Frame* frame) override {
    if (!inner_->random_access()) {
      for (; skipped_ < first_; ++skipped_) {  // decoded and dropped: video cannot seek exactly
        Frame dropped;
        if (!inner_->Next(&dropped)) return false;
      }
      if (delivered_ >= limit_ || !inner_->Next(frame)) return false;
      ++delivered_;
      return true;
    }
    if (delivered_ >= size_) return false;
    *frame = Read(delivered_++);
    return true;
  }
  RecordingInfo recording() const override { return inner_->recording(); }
  std::vector<std::string> warnings() const override { return inner_->warnings(); }

 private:
  std::unique_ptr<FrameSource> inner_;
  size_t first_ = 0, size_ = 0, limit_ = 0, skipped_ = 0, delivered_ = 0;
};

}  // namespace

std::string FrameRange::ToString() const {
  return (first > 0 || !end ? std::to_string(first) : "") + ":" +
         (end ? std::to_string(*end) : "");
}

FrameRange ParseFrameRange(const std::string& text) {
  FrameRange r;
  if (text.empty()) return r;
  const size_t colon = text.find(':');
  const std::string bad = "--frames '" + text + "': expected A:B, A: or :B with frame numbers " +
                          "0 <= A < B (frames A..B-1, 0-based)";
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos) {
    throw UsageError(bad);
  }
  const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  if (a.empty() && b.empty()) throw UsageError(bad);
  if (!a.empty()) {
    const auto v = ParseIndex(a);
    if (!v) throw UsageError(bad);
    r.first = *v;
  }
  if (!b.empty()) {
    const auto v = ParseIndex(b);
    if (!v || *v <= r.first) throw UsageError(bad);
    r.end = *v;
  }
  return r;
}

std::unique_ptr<FrameSource> SelectFrames(std::unique_ptr<FrameSource> source,
                                          const FrameRange& range, const std::string& input) {
  if (range.all()) return source;
  const size_t n = source->size();
  if (n > 0 && range.first >= n) {
    throw InputError(input + ": --frames " + range.ToString() + " starts at frame " +
                     std::to_string(range.first) + " but there are only " + std::to_string(n) +
                     " frames (0.." + std::to_string(n - 1) + ")");
  }
  return std::make_unique<RangeSource>(std::move(source), range.first, range.end);
}

}  // namespace dimer::tracking
