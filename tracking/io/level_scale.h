#pragma once
// 16-bit frames from a camera of fewer bits, scaled to the 16-bit range before tracking.
//
// Why. A 10- or 12-bit Phantom's .cine holds its levels as stored, 0..1023 or 0..4095 in 16-bit
// pixels (and 10-bit packed files are delivered so, cine_source.h), while the tracker's levels
// are fractions of the container's full scale (the plate edge's least step, a silhouette's
// threshold, a clipped plate's level: 65535 for 16-bit frames). POV-Ray front_point written as
// such a file lost the plate and the rows (4.9 px off, scatter 0.49 px) at 10 bits; at 12 bits
// it passed, with little margin for a dimmer scene. A gain moves no edge, so the frames are
// multiplied by 65535 / (2^bits - 1): the camera's saturation becomes the container's, and the
// thresholds mean what they were set for.
//
// The bits are the user's (`dimerlab track --bits B`), else the .cine header's RealBPP when the
// first readable frame stays within them (a file whose software already scaled its levels is
// tracked as it is). Other 16-bit sources (TIFF, PNG) carry no such header: when the levels of
// up to 16 frames spread over the film fit in fewer than 16 bits, they are taken as a camera's
// of the fewest bits that hold them (8 at least), with a warning, since a dark film of a 16-bit
// camera looks the same (its frames brighter than those sampled, if beyond 2^bits, would clip);
// else tracked as stored. Guessed at 10 and 12 bits only, 16-bit frames filling a quarter of
// the range (8-bit levels x 64) lost spheres and plate on 8 of 22 POV-Ray films (ring light
// 49 px off, an over-exposed plate 0.41 px; see povray.quarter_range).
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "tracking/io/frame_source.h"

namespace dimer::tracking {

struct LevelScale {
  double factor = 1;   // levels are multiplied by this (1: tracked as stored)
  int bits = 0;        // the camera's bits per pixel it rests on (0: none)
  std::string reason;  // why, or why not (empty when the source has nothing to scale)
  bool warn = false;   // `reason` is a warning (16-bit levels that may be a camera's fewer bits)
  // Frames whose levels the factor took past 65535 (clipped), and the first of them; set by
  // TrackSequence after the track.
  size_t clipped_frames = 0;
  std::string first_clipped;
};

// Levels of 16-bit frames that fit in this many bits, with no header or --bits to say the
// camera's, are taken as a camera's of the fewest bits (8 at least) that hold them.
inline constexpr int kGuessBitsUpTo = 15;

// `bits`: the camera's bits per pixel as the user gives them (8..16; 16: never scale), 0: the
// header's. Throws InputError naming the frame when the given bits cannot hold its levels.
LevelScale ChooseLevelScale(const FrameSource& source, int bits = 0);

// `inner` with every readable 16-bit frame multiplied by `factor` (rounded, saturated); other
// frames as they are. Same size, order, names and errors. The frames whose levels the factor
// took past 65535 are counted (once each, however often read): their brightest pixels were
// clipped, which a guessed camera's bits can do to a frame brighter than those sampled.
class ScaledSource : public FrameSource {
 public:
  ScaledSource(FrameSource& inner, double factor) : inner_(inner), factor_(factor) {}
  size_t size() const override { return inner_.size(); }
  bool random_access() const override { return inner_.random_access(); }
  RecordingInfo recording() const override { return inner_.recording(); }
  Frame Read(size_t index) const override;
  bool Next(Frame* frame) override;
  size_t clipped_frames() const;
  std::string first_clipped() const;  // the name of the first (by index); empty: none

 private:
  Frame Scaled(Frame f) const;
  FrameSource& inner_;
  double factor_;
  mutable std::mutex mutex_;
  mutable std::map<size_t, std::string> clipped_;  // frame index -> name
};
std::unique_ptr<ScaledSource> ScaledLevels(FrameSource& inner, double factor);

}  // namespace dimer::tracking
