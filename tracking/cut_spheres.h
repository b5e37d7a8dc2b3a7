#pragma once
// Spheres cut by the frame's edge, placed where a frame's own history cannot place them. The
// follower places a cut sphere from the frames before it (FrameFollower::MeasureCuts); a chunk
// of the film starts without any, and its last frames have no frames after them. So each chunk
// holds back the frames that missed a sphere (their images, at most kCutHeldFrames in a run)
// and goes back over them from the first frame that finds it; the frames it could not place at
// its start and its end are handed to the film, which places them across the seam from the
// neighbouring chunk's frames (PlaceAcrossSeam). With 16-frame chunks every sphere at least
// half in view of the mirror-lit walks that the template followed was found, 1,465 of 1,465
// (DimerIdentity.NeverSwappedOverRandomWalksOutOfEitherEdge/reflect_auto).
#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <vector>

#include "tracking/frame_follower.h"

namespace dimer::tracking {

// A run of frames missing a sphere is held back up to this long: one entering the frame is cut
// over less than its template's width (< 3 R) and only then acquired; at 0.5 px a frame and
// R 16 px that is under 96 frames, and a longer run costs memory without frames to place.
inline constexpr size_t kCutHeldFrames = 64;

// A frame that missed a sphere: its image as tracked and its index among the tracks.
struct HeldFrame {
  cv::Mat image;
  size_t index = 0;
};

// A chunk's held frames while it is tracked.
class ChunkCuts {
 public:
  // After each frame is tracked (frames->back()): holds it if it missed a sphere, and goes back
  // over the held run once a later frame finds what it missed.
  void Add(const FrameFollower& follower, cv::Mat image, std::vector<FrameTrack>* frames);
  // The held run that reaches the chunk's first frame (the head) and the one that reaches its
  // last (the tail), at the end of the chunk; indices in the chunk.
  std::vector<HeldFrame> head;
  std::vector<HeldFrame> Tail(size_t chunk_frames) const;

 private:
  std::deque<HeldFrame> run_;  // the latest run of frames that missed a sphere
  bool head_open_ = true;      // every frame so far missed a sphere
};

// From frames[from] through `held` (nearest first, each next to the one before), placing each
// one's missing spheres by the frames before it on the way (PlaceCutBeside); stops at the first
// frame that still misses a sphere the one before it has.
void PlaceAlong(const FrameFollower& follower, const std::vector<const HeldFrame*>& held,
                std::vector<FrameTrack>* frames, size_t from);

// A seam between two chunks of `frames` (`seam`: the later's first frame): the earlier's tail
// placed back from the later's first frames, the later's head forward from the earlier's last.
// Indices in `frames`.
void PlaceAcrossSeam(const FrameFollower& follower, const std::vector<HeldFrame>& tail,
                     const std::vector<HeldFrame>& head, std::vector<FrameTrack>* frames,
                     size_t seam);

// Every cut sphere's stated uncertainty (FrameTrack::sigma_px): where the frame had no whole
// sphere beside it to cut alike (FrameFollower::CutSigma), the root mean square of the sphere's
// own stated ones over the film, else of the other's.
void StateCutUncertainty(std::vector<FrameTrack>* frames);

}  // namespace dimer::tracking
