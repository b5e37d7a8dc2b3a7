#include "tracking/cut_spheres.h"

#include <array>
#include <limits>

namespace dimer::tracking {

void PlaceAlong(const FrameFollower& follower, const std::vector<const HeldFrame*>& held,
                std::vector<FrameTrack>* frames, size_t from) {
  size_t prev = from;
  for (const HeldFrame* h : held) {
    const bool back = h->index < prev;
    if (back ? h->index + 1 != prev : h->index != prev + 1) return;  // not next to it
    const bool has_beyond = back ? prev + 1 < frames->size() : prev >= 1;
    const FrameTrack* beyond = has_beyond ? &(*frames)[back ? prev + 1 : prev - 1] : nullptr;
    if (!follower.PlaceCutBeside(h->image, (*frames)[prev], beyond, &(*frames)[h->index])) {
      return;
    }
    prev = h->index;
  }
}

namespace {

// Back over `run` (the latest last) from frames[from].
void GoBack(const FrameFollower& follower, const std::deque<HeldFrame>& run,
            std::vector<FrameTrack>* frames, size_t from) {
  std::vector<const HeldFrame*> held;
  for (auto it = run.rbegin(); it != run.rend(); ++it) {
    if (it->index < from) held.push_back(&*it);
  }
  PlaceAlong(follower, held, frames, from);
}

}  // namespace

void ChunkCuts::Add(const FrameFollower& follower, cv::Mat image,
                    std::vector<FrameTrack>* frames) {
  const size_t last = frames->size() - 1;
  if ((*frames)[last].found[0] && (*frames)[last].found[1]) {
    GoBack(follower, run_, frames, last);  // by the dimer's vector
    run_.clear();
    head_open_ = false;
    return;
  }
  if (head_open_ && head.size() < kCutHeldFrames) head.push_back({image, last});
  if (run_.size() == kCutHeldFrames) run_.pop_front();
  run_.push_back({std::move(image), last});
  // A sphere alone found in two frames after one that missed it: back by its own motion.
  for (int k = 0; k < 2 && last >= 2; ++k) {
    const std::vector<FrameTrack>& f = *frames;
    if (f[last].found[k] && f[last - 1].found[k] && !f[last - 2].found[k]) {
      GoBack(follower, run_, frames, last - 1);
    }
  }
}

std::vector<HeldFrame> ChunkCuts::Tail(size_t chunk_frames) const {
  if (run_.empty() || run_.back().index + 1 != chunk_frames) return {};
  return {run_.begin(), run_.end()};
}

void PlaceAcrossSeam(const FrameFollower& follower, const std::vector<HeldFrame>& tail,
                     const std::vector<HeldFrame>& head, std::vector<FrameTrack>* frames,
                     size_t seam) {
  if (seam == 0 || seam >= frames->size()) return;
  std::vector<const HeldFrame*> held;
  for (const HeldFrame& h : head) held.push_back(&h);
  PlaceAlong(follower, held, frames, seam - 1);  // forward from the earlier chunk
  held.clear();
  for (auto it = tail.rbegin(); it != tail.rend(); ++it) held.push_back(&*it);
  PlaceAlong(follower, held, frames, seam);  // back from the later chunk
}

void StateCutUncertainty(std::vector<FrameTrack>* frames) {
  std::array<Eigen::Vector2d, 2> sum{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  std::array<size_t, 2> n{0, 0};
  for (const FrameTrack& f : *frames) {
    for (int k = 0; k < 2; ++k) {
      if (f.found[k] && f.cut[k] && f.sigma_px[k].allFinite()) {
        sum[k] += f.sigma_px[k].cwiseProduct(f.sigma_px[k]);
        ++n[k];
      }
    }
  }
  std::array<Eigen::Vector2d, 2> rms;
  for (int k = 0; k < 2; ++k) {
    const size_t m = n[k] ? n[k] : n[1 - k];
    const Eigen::Vector2d s = n[k] ? sum[k] : sum[1 - k];
    rms[k] = m ? Eigen::Vector2d((s / double(m)).cwiseSqrt())
               : Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  for (FrameTrack& f : *frames) {
    for (int k = 0; k < 2; ++k) {
      if (f.found[k] && f.cut[k] && !f.sigma_px[k].allFinite()) f.sigma_px[k] = rms[k];
    }
  }
}

}  // namespace dimer::tracking
